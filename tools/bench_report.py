#!/usr/bin/env python3
"""The performance table of `./springlab bench`, from Google Benchmark's JSON.

usage: tools/bench_report.py BENCHMARKS.json [--out REPORT.md]

Reads the medians of springlab_bench's run (or the single runs, without repetitions) and
prints, as Markdown: the machine and its measured memory bandwidth (the triad), the spring
force pass against the memory-traffic floor, one cloth step per integrator, the cloth
thesis' frame broken down into phases next to the thesis' own figures, and the rope and
the ball, and the cloth's 5 s drape by method beside Bullet's position-based cloth (when the
run has the Bullet rows). Exits 1 naming the file when it holds no springlab benchmark.
"""
import argparse
import json
import re
import sys

# The cloth thesis' table (ms per frame; Ryzen 9 7950X, 8 threads; implicit Euler with
# per-particle blocks): r -> (total, forces, integration, collisions, stretch limit, normals).
THESIS = {
    8: (0.215, 0.094, 0.102, 0.003, 0.010, 0.006),
    16: (0.422, 0.202, 0.148, 0.008, 0.038, 0.025),
    32: (1.014, 0.477, 0.268, 0.026, 0.157, 0.086),
    48: (1.894, 0.829, 0.471, 0.058, 0.342, 0.193),
    64: (2.939, 1.169, 0.691, 0.109, 0.636, 0.333),
}
# ClothDrape's method argument (bench/net_drape.cpp) and the two materials of the drape table.
DRAPE_METHODS = ["implicit Euler, blocks", "implicit Euler, sparse CG", "XPBD", "projective dynamics"]
DRAPE_MATERIALS = ["thesis", "fabric"]
PHASES = ["forces", "integration", "collisions", "stretch_limit", "normals", "other"]
UNIT_MS = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}


def load(path):
    """name without the aggregate suffix -> benchmark entry (the median when repeated)."""
    try:
        with open(path) as f:
            data = json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        sys.exit(f"bench_report: {path}: cannot read Google Benchmark JSON: {e}")
    runs = {}
    for b in data.get("benchmarks", []):
        kind = b.get("aggregate_name")
        if kind not in (None, "median"):
            continue
        name = b.get("run_name", b["name"])
        if kind is None and name in runs:  # repetitions without aggregates: keep the first
            continue
        runs[name] = b
    if not any(n.startswith(("NetStep", "SpringForcePass", "MemoryTriad", "NetFrame", "RopeStep", "BallStep",
                             "ClothDrape", "BulletClothDrape", "StepStableDt"))
               for n in runs):
        sys.exit(f"bench_report: {path}: no springlab benchmark in it (field 'benchmarks')")
    return data.get("context", {}), runs


def ms(b):
    return b["real_time"] * UNIT_MS[b.get("time_unit", "ns")]


def args(name):
    """'NetFrame/r:64/threads:1/real_time' -> {'r': 64, 'threads': 1}"""
    return {k: int(v) for k, v in re.findall(r"(\w+):(\d+)", name)}


def fmt(x, digits=3):
    if x is None:
        return "–"
    return f"{x:.{digits}g}" if abs(x) < 1000 else f"{x:.0f}"


def table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    out += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(out)


def report(context, runs):
    lines = []
    # ---- machine and bandwidth
    bandwidth = {}  # threads -> bytes/s
    for name, b in runs.items():
        if name.startswith("MemoryTriad"):
            bandwidth[args(name).get("threads", 1)] = b.get("bytes_per_second")
    caches = ", ".join(f"L{c['level']} {c['size'] // 1024} KiB" + (f" (shared by {c['num_sharing']})" if c.get("num_sharing", 1) > 1 else "")
                       for c in context.get("caches", []) if c.get("type") in ("Data", "Unified"))
    lines.append("## Machine\n")
    lines.append(f"{context.get('num_cpus', '?')} CPUs at {context.get('mhz_per_cpu', '?')} MHz; caches {caches or '?'}; "
                 f"run {context.get('date', '?')}.")
    if bandwidth:
        lines.append("Memory bandwidth (STREAM triad, 3 x 128 MiB arrays per thread): " +
                     ", ".join(f"{t} thread{'s' if t > 1 else ''} {bandwidth[t] / 1e9:.1f} GB/s" for t in sorted(bandwidth)) + ".")
    lines.append("")

    # ---- spring force pass against the floor
    rows = []
    for name, b in sorted(runs.items(), key=lambda kv: (args(kv[0]).get("r", 0), args(kv[0]).get("threads", 0))):
        if not name.startswith("SpringForcePass"):
            continue
        a = args(name)
        ns = b["ns_per_spring"]  # the counter is inverted per 1e-9 spring: ns per spring
        bytes_per = b.get("bytes_per_spring")
        bw = bandwidth.get(a.get("threads", 1))
        floor = bytes_per / bw * 1e9 if bw and bytes_per else None
        rows.append([a.get("r"), a.get("threads"), int(b.get("springs", 0)), fmt(ns), fmt(bytes_per),
                     fmt(floor), fmt(ns / floor if floor else None)])
    if rows:
        lines.append("## Spring force pass\n")
        lines.append("ns per spring of `evaluateForces` on an r x r cloth; floor = the bytes the pass must move at the "
                     "triad's bandwidth for the same thread count.\n")
        lines.append(table(["r", "threads", "springs", "ns/spring", "bytes/spring", "floor ns/spring", "x floor"], rows))
        lines.append("")

    # ---- one step per integrator
    steps = {}
    for name, b in runs.items():
        m = re.match(r"NetStep(\w+?)/", name)
        if m:
            a = args(name)
            steps[(a["r"], a["material"], a["threads"], m.group(1))] = b
    if steps:
        lines.append("## One cloth step\n")
        lines.append("ms per step, reference solution. Material thesis: 1 kg per mass, k = 75/22/8 N/m; fabric: "
                     "0.2 kg/m^2, k = 400/150/15 N/m. Symplectic Euler at dt = 1/60 s (thesis) or 0.1 ms (fabric), "
                     "implicit Euler at 1/60 s; CG to a relative residual of 1e-6, warm-started.\n")
        rows = []
        for key in sorted({k[:3] for k in steps}, key=lambda k: (k[1], k[2], k[0])):
            r, material, threads = key
            se, ie, ib = (steps.get(key + (n,)) for n in ("SymplecticEuler", "ImplicitEuler", "ImplicitEulerBlocks"))
            rows.append([r, "thesis" if material == 0 else "fabric", threads,
                         fmt(ms(se)) if se else "–", fmt(ms(ie)) if ie else "–",
                         fmt(ie["cg_iterations"]) if ie else "–",
                         fmt(ie["ms_integration"]) if ie else "–",
                         fmt(ms(ib)) if ib else "–",
                         fmt(1000.0 / ms(ie)) if ie else "–"])
        lines.append(table(["r", "material", "threads", "symplectic Euler", "implicit, sparse CG", "CG iterations",
                            "of which Jacobians, assembly, CG", "implicit, blocks", "sparse steps/s"], rows))
        lines.append("")

    # ---- the thesis frame
    frames = {}
    for name, b in runs.items():
        if name.startswith("NetFrame"):
            a = args(name)
            frames[(a["r"], a["threads"])] = b
    if frames:
        lines.append("## The cloth thesis' frame, by phase\n")
        lines.append("ms per frame (one implicit Euler step with per-particle blocks at 1/60 s), sphere + ground "
                     "collisions, 10 % stretch limit, thesis wind (normals); thesis = the cloth thesis' own table "
                     "(Ryzen 9 7950X, up to 8 threads).\n")
        rows = []
        for (r, threads), b in sorted(frames.items()):
            t = THESIS.get(r)
            rows.append([r, threads, fmt(ms(b))] + [fmt(b.get("ms_" + p)) for p in PHASES] +
                        [fmt(t[0]) if t else "–", fmt(t[0] / ms(b)) + "x" if t else "–"])
        lines.append(table(["r", "threads", "total", "forces", "integration", "collisions", "stretch limit", "normals",
                            "other", "thesis total", "speed-up"], rows))
        lines.append("")

    # ---- the 5 s drape, ours and Bullet's
    rows = []
    for name, b in runs.items():
        if name.startswith(("ClothDrape", "BulletClothDrape")):
            a = args(name)
            if name.startswith("Bullet"):
                method, rank = f"Bullet, position-based, {a.get('piterations', 10)} iterations", (0, a.get("piterations", 10))
            else:
                method, rank = DRAPE_METHODS[a["method"]], (1, a["method"])
            rows.append((a["material"], a["r"], rank, method, b))
    if rows:
        lines.append("## The cloth's drape after 5 s, ours and Bullet's\n")
        lines.append("ms per 1/60 s frame (CPU time, one thread) and the lowest point after 5 s (m, pins at 0). "
                     "Thesis: 1 kg per mass, k = 75/22/8 N/m, one 1/60 s step per frame; fabric: "
                     "scenes/net_hanging.json without its sphere (0.2 kg/m^2, k = 400/40/2 N/m, two 1/120 s steps). "
                     "Both held at two corners with a 10 % stretch limit. Bullet 3.24 (float): btSoftBody patch, "
                     "bending constraints at distance 2, the position iterations named.\n")
        table_rows = []
        for material, r, _, method, b in sorted(rows, key=lambda x: (x[0], x[1], x[2])):
            table_rows.append([DRAPE_MATERIALS[material], r, method, fmt(b.get("ms_per_frame")),
                               fmt(0.0 - b.get("drape_m", 0.0) + 0.0, 4)])
        lines.append(table(["material", "r", "method", "ms/frame", "drape (m)"], table_rows))
        if not any(m.startswith("Bullet") for _, _, _, m, _ in rows):
            lines.append("\nNo Bullet rows: springlab_bench was built without SPRINGLAB_BULLET_BENCH (needs libbullet-dev).")
        # At equal drape: Bullet's fewest iterations that hang within 2 % of the full implicit
        # solve (position-based cloth stretches less with more iterations), beside our methods
        # that hang within 2 % of it too.
        for material, r in sorted({(m, r) for m, r, _, _, _ in rows}):
            here = [(rank, method, b) for m, rr, rank, method, b in rows if (m, rr) == (material, r)]
            full = [b for rank, _, b in here if rank == (1, 1)]
            if not full or not full[0].get("drape_m"):
                continue
            target = full[0]["drape_m"]
            close = lambda b: abs(b.get("drape_m", 0.0) - target) <= 0.02 * abs(target)
            bullet = sorted([(rank[1], b) for rank, _, b in here if rank[0] == 0 and close(b)], key=lambda x: x[0])
            ours = [(method, b) for rank, method, b in here if rank[0] == 1 and close(b)]
            if not ours:
                continue
            fastest = min(ours, key=lambda x: x[1].get("ms_per_frame", float("inf")))
            if bullet:
                lines.append(f"\nAt equal drape ({DRAPE_MATERIALS[material]}, r = {r}; within 2 % of the full implicit "
                             f"solve's {-target:.3f} m): Bullet from {bullet[0][0]} iterations, "
                             f"{fmt(bullet[0][1].get('ms_per_frame'))} ms/frame; ours: the full implicit solve "
                             f"{fmt(full[0].get('ms_per_frame'))} ms/frame, fastest {fastest[0]}, "
                             f"{fmt(fastest[1].get('ms_per_frame'))} ms/frame.")
            else:
                lines.append(f"\nAt equal drape ({DRAPE_MATERIALS[material]}, r = {r}): no Bullet run of this report "
                             f"hangs within 2 % of the full implicit solve's {-target:.3f} m.")
        lines.append("")

    # ---- rope and ball
    rows = []
    for name, b in sorted(runs.items()):
        if name.startswith(("RopeStep", "BallStep")):
            a = args(name)
            what = f"rope, {a.get('masses')} masses" if name.startswith("Rope") else \
                f"ball, subdivisions {a.get('subdivisions')}, {int(b.get('masses', 0))} masses"
            rows.append([what, fmt(ms(b) * 1e3), fmt(1000.0 / ms(b)), fmt(b.get("ms_forces", 0) / ms(b) * 100, 2) + " %"])
    if rows:
        lines.append("## Rope and ball\n")
        lines.append("One symplectic Euler step of the lab's default scene.\n")
        lines.append(table(["scene", "us/step", "steps/s", "forces share"], rows))
        lines.append("")

    # ---- the stability limit (bench/step_stability.cpp labels each run with its method)
    rows = []
    for name, b in sorted(runs.items(), key=lambda item: (args(item[0]).get("method", 0), args(item[0]).get("r", 0))):
        if name.startswith("StepStableDt"):
            a = args(name)
            rows.append([str(a.get("r")), b.get("label") or str(a.get("method")), fmt(b.get("cpu_s")),
                         fmt(b.get("limit_ms"))])
    if rows:
        lines.append("## The stability limit of the step\n")
        lines.append("stepStableDt on net_hanging.json (r x r masses, as shipped), one thread: CPU seconds and the "
                     "limit found.\n")
        lines.append(table(["r", "method", "CPU s", "limit (ms)"], rows))
        lines.append("")
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("json", help="Google Benchmark JSON of springlab_bench")
    parser.add_argument("--out", help="also write the report here (Markdown)")
    o = parser.parse_args()
    text = report(*load(o.json))
    print(text)
    if o.out:
        with open(o.out, "w") as f:
            f.write(text + "\n")


if __name__ == "__main__":
    main()
