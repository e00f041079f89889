#!/usr/bin/env python3
"""Measure the 3D ball of Lab 3: steps per second at several mesh resolutions, and the
largest dt each integrator keeps stable at several gas amounts (bisection on dt; a run is
stable when `sim` finishes T seconds without its blow-up check firing).

    tools/softbody_stability.py APP [--scene scenes/softbody_ball.json] [--seconds 0.5]
        [--subdivisions 2 3 4] [--gas 30 300] [--integrators NAME ...]

APP is build/framework/app/springlab-reference. Prints two tables (Markdown).
"""
import argparse
import json
import pathlib
import re
import subprocess
import tempfile


def variant(base, tmp, **changes):
    scene = json.loads(json.dumps(base))
    body = scene["softbody"]
    if "subdivisions" in changes:
        body["mesh"]["subdivisions"] = changes["subdivisions"]
    if "gas" in changes:
        body["gas"]["nRT"] = changes["gas"]
    name = "_".join(f"{k}{v}" for k, v in changes.items())
    path = pathlib.Path(tmp) / f"ball_{name}.json"
    path.write_text(json.dumps(scene))
    return str(path)


def run(app, scene, steps, dt=None, integrator=None):
    cmd = [app, "sim", scene, "--steps", str(steps), "--save-every", str(steps), "--out",
           str(pathlib.Path(scene).with_suffix(".out.json"))]
    if dt:
        cmd += ["--dt", repr(dt)]
    if integrator:
        cmd += ["--integrator", integrator]
    return subprocess.run(cmd, capture_output=True, text=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("app")
    ap.add_argument("--scene", default=str(pathlib.Path(__file__).resolve().parent.parent / "scenes/softbody_ball.json"))
    ap.add_argument("--seconds", type=float, default=0.5, help="simulated time per stability run")
    ap.add_argument("--subdivisions", type=int, nargs="+", default=[2, 3, 4])
    ap.add_argument("--gas", type=float, nargs="+", default=[30.0, 300.0])
    ap.add_argument("--integrators", nargs="+",
                    default=["symplectic_euler", "explicit_euler", "position_verlet", "velocity_verlet"])
    args = ap.parse_args()
    base = json.loads(pathlib.Path(args.scene).read_text())
    base_dir = pathlib.Path(args.scene).resolve().parent

    with tempfile.TemporaryDirectory(dir=base_dir) as tmp:
        print("| subdivisions | masses | steps/s (scene dt, symplectic Euler, 2000 steps) |")
        print("|---|---|---|")
        for s in args.subdivisions:
            scene = variant(base, tmp, subdivisions=s)
            out = run(app=args.app, scene=scene, steps=2000)
            rate = re.search(r"([0-9.e+]+) steps/s", out.stdout)
            print(f"| {s} | {10 * 4 ** s + 2} | {rate.group(1) if rate else out.stderr.strip()} |")

        print()
        print(f"| integrator | nRT (J) | largest stable dt (s), {args.seconds} s runs | predicted 2 / w_max (s) |")
        print("|---|---|---|---|")
        for gas in args.gas:
            scene = variant(base, tmp, gas=gas)
            for integrator in args.integrators:
                lo, hi = 1e-6, 2e-2
                predicted = ""
                for _ in range(14):
                    dt = (lo * hi) ** 0.5
                    out = run(args.app, scene, max(1, int(args.seconds / dt)), dt, integrator)
                    if out.returncode == 0:
                        lo = dt
                    elif out.returncode == 4:
                        hi = dt
                        m = re.search(r"= ([0-9.e+-]+) s\.", out.stderr)
                        predicted = m.group(1) if m else predicted
                    else:
                        raise SystemExit(out.stderr)
                print(f"| {integrator} | {gas:g} | {lo:.3g} | {predicted or '-'} |")


if __name__ == "__main__":
    main()
