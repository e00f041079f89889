#!/usr/bin/env python3
"""A program with one exercise stubbed must stop with exit 3 and name that exercise.

    check_stub_exits.py --program P --stub labs/02_net/jacobian.cpp --manifest tests/02_net/exercises.json
                        --scenes scenes/ --work DIR [--xvfb /usr/bin/Xvfb]

The exercises of the stub file are the ids its NotImplemented throws name. Each is run where
the lab reaches it: the manifest's "run" of the exercise ({"scene": "...json", "integrator":
"...", "steps": N}; default the lab's scene for 240 steps). `sim` must exit 3 and print "exercise <id>"; so must a
headless viewer run (90 frames on a virtual display of its own) when --xvfb is given. A negative return
code (a signal: SIGABRT from an exception that left a parallel loop, SIGSEGV) is a failure.
"""
import argparse
import contextlib
import json
import os
import pathlib
import re
import subprocess
import sys

def describe(code):
    return f"signal {-code}" if code < 0 else f"exit code {code}"


@contextlib.contextmanager
def virtual_display(xvfb):
    """An Xvfb server of this check's own (Xvfb picks a free display and prints its number),
    so checks running side by side never race for a display as `xvfb-run -a` can."""
    server = subprocess.Popen([xvfb, "-displayfd", "1", "-screen", "0", "640x480x24", "-nolisten", "tcp"],
                              stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    try:
        number = server.stdout.readline().strip()
        if not number.isdigit():
            raise RuntimeError(f"{xvfb} did not start a display")
        yield f":{number}"
    finally:
        server.terminate()
        server.wait(timeout=30)


def check(argv, exercise, what, env=None):
    try:
        run = subprocess.run(argv, capture_output=True, text=True, timeout=240, env=env)
    except subprocess.TimeoutExpired:
        return [f"{what}: still running after 240 s"]
    output = run.stdout + run.stderr
    problems = []
    if run.returncode != 3:
        problems.append(f"{what}: {describe(run.returncode)}, expected 3 (exercise {exercise} missing)")
    if f"exercise {exercise} " not in output:
        problems.append(f"{what}: the output does not name exercise {exercise}")
    if problems:
        problems.append(f"  command: {' '.join(argv)}\n  output (last lines):\n    "
                        + "\n    ".join(output.strip().splitlines()[-8:]))
    return problems


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--program", required=True)
    ap.add_argument("--stub", required=True, type=pathlib.Path)
    ap.add_argument("--manifest", required=True, type=pathlib.Path)
    ap.add_argument("--scenes", required=True, type=pathlib.Path)
    ap.add_argument("--work", required=True, type=pathlib.Path)
    ap.add_argument("--xvfb", help="the Xvfb server, to run the viewer too")
    args = ap.parse_args()
    manifest = json.loads(args.manifest.read_text())
    exercises = {e["id"]: e for e in manifest["exercises"]}
    ids = list(dict.fromkeys(re.findall(r'NotImplemented\("([^"]+)"', args.stub.read_text())))
    if not ids:
        print(f"{args.stub}: no stub throws NotImplemented", file=sys.stderr)
        return 1
    args.work.mkdir(parents=True, exist_ok=True)
    problems = []
    for exercise in ids:
        run = exercises[exercise].get("run", {})
        # The exercise's own scene, else the lab's (the one `./springlab run LAB` opens).
        scene = str(args.scenes / run.get("scene", manifest["scene"]))
        options = ["--integrator", run["integrator"]] if "integrator" in run else []
        steps = str(run.get("steps", 240))
        sim = [args.program, "sim", scene, "--steps", steps, "--save-every", steps,
               "--out", str(args.work / "sim.json"), *options]
        problems += check(sim, exercise, f"exercise {exercise}, sim")
        if args.xvfb:
            view = [args.program, "view", scene, "--frames", "90", "--snapshot", str(args.work / "view.png"), *options]
            with virtual_display(args.xvfb) as display:
                problems += check(view, exercise, f"exercise {exercise}, viewer", dict(os.environ, DISPLAY=display))
        if not problems:
            print(f"exercise {exercise} missing: sim and viewer exit 3 and name it ({pathlib.Path(scene).name})")
    for problem in problems:
        print(f"PROBLEM: {problem}", file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
