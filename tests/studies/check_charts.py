#!/usr/bin/env python3
"""The chart and advise commands end to end, on small settings: each writes its CSV files,
unstable runs are kept (not dropped), the plot script makes PNG and SVG charts (when Debian's
python3-matplotlib is installed), and advise prints a JSON snippet that loads as a scene.

    check_charts.py APP ROOT OUTDIR
"""
import csv
import json
import re
import pathlib
import shutil
import subprocess
import sys

app, root, out = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
plot = root / "tools" / "plot_charts.py"
debian_python = pathlib.Path("/usr/bin/python3")
failures = []
shutil.rmtree(out, ignore_errors=True)


def run(*args):
    p = subprocess.run([*args], capture_output=True, text=True, timeout=240)
    if p.returncode != 0:
        failures.append(f"{' '.join(map(str, args))}: exit {p.returncode}\n{p.stdout}\n{p.stderr}")
    return p


def can_plot():
    return debian_python.exists() and subprocess.run([debian_python, "-c", "import matplotlib"]).returncode == 0


oscillator = root / "scenes" / "mass_on_spring.json"
rope = root / "scenes" / "rope.json"
charts = [
    ("work-precision", oscillator, ["--time", "2", "--levels", "7", "--repeats", "1"], ["work_precision.csv"]),
    ("stability", rope, ["--set", "rope.masses=20", "--time", "0.5"],
     ["stability.csv", "stability_map.csv", "stability_boundary.csv"]),
    ("resolution", rope, ["--observable", "tip_y", "--tol", "0.05", "--time", "0.5", "--resolutions", "5,10,20"],
     ["resolution.csv", "resolution_series.csv"]),
]
for kind, scene, extra, files in charts:
    folder = out / kind
    run(app, "chart", kind, str(scene), "--out", str(folder), *extra)
    for f in files:
        if not (folder / f).exists() or len((folder / f).read_text().splitlines()) < 2:
            failures.append(f"chart {kind}: {f} missing or empty")
    if can_plot():
        p = run(debian_python, plot, kind, str(folder))
        # The plot script names labels that cover each other or the data.
        for line in p.stdout.splitlines():
            if line.startswith("overlapping labels"):
                failures.append(f"chart {kind}: {line}")
        stems = [kind.replace("-", "_")] + (["stability_map"] if kind == "stability" else [])
        for stem in stems:
            for ext in ("png", "svg"):
                path = folder / f"{stem}.{ext}"
                if not path.exists() or path.stat().st_size < 5000:
                    failures.append(f"chart {kind}: {path.name} missing or too small")

# Work-precision keeps the runs that blew up (explicit Euler at the largest dt over 2 s).
rows = list(csv.DictReader(open(out / "work-precision" / "work_precision.csv")))
if not any(r["stable"] == "0" for r in rows):
    failures.append("work-precision: expected some unstable runs to be kept and flagged")
if {r["integrator"] for r in rows} < {"explicit_euler", "symplectic_euler", "midpoint", "rk4"}:
    failures.append("work-precision: not every integrator was swept")

# The stability map has stable and unstable cells.
cells = list(csv.DictReader(open(out / "stability" / "stability_map.csv")))
if not ({c["stable"] for c in cells} >= {"0", "1"}):
    failures.append("stability map: expected both stable and unstable cells")

# advise prints a snippet that, pasted into the scene, loads and runs.
p = run(app, "advise", str(rope), "--set", "rope.masses=20", "--tol", "0.2", "--time", "0.3", "--resolutions", "5,10,20",
        "--integrators", "symplectic_euler,rk4")
try:
    snippet = json.loads(p.stdout)
    scene = json.loads(rope.read_text())
    scene.update(snippet)
    pasted = out / "advised.json"
    pasted.write_text(json.dumps(scene))
    run(app, "sim", str(pasted), "--steps", "100", "--out", str(out / "advised_run.json"))
except json.JSONDecodeError:
    failures.append(f"advise: stdout is not JSON:\n{p.stdout}")
# ... and says on stderr what it does: a progress line per run (which, how many left, the time
# left), the tolerance asked for and its two halves, and a table whose columns do not run
# together ("implicit_euler_blocksdt = ...").
if not re.search(r"^advise: run 1 of at most \d+ \(.+\) done after \d+ s; \d+ left, about \d+ s", p.stderr, re.M):
    failures.append(f"advise: no progress lines on stderr:\n{p.stderr}")
if "--tol 0.2: " not in p.stderr or "within 0.2 (relative)" not in p.stderr or "0.1 for the resolution" not in p.stderr:
    failures.append(f"advise: the tolerance asked for (0.2) and its halves are not said:\n{p.stderr}")
if re.search(r"[a-z]dt = ", p.stderr):
    failures.append(f"advise: a column runs into the next:\n{p.stderr}")

# An unknown observable is a clear error (exit 2) naming the ones the scene has.
p = subprocess.run([app, "chart", "resolution", str(rope), "--observable", "volume", "--out", str(out / "bad")],
                   capture_output=True, text=True, timeout=60)
if p.returncode != 2 or "sag" not in p.stderr:
    failures.append(f"unknown observable: exit {p.returncode}, expected 2 naming sag\n{p.stderr}")

# `./springlab chart`'s plan: each lab's default scene gets the options that show what the
# chart is for (the rope's work-precision window ends before the rope reaches the ground);
# an option the user gives wins; runs with other options, kinds or trees get their own folder.
def plan(kind, scene, tree, *options):
    p = subprocess.run([sys.executable, str(plot), "plan", kind, str(root / "scenes" / scene), str(out), tree, *options],
                       capture_output=True, text=True, timeout=60)
    lines = p.stdout.splitlines()
    if p.returncode != 0 or not lines:
        failures.append(f"plan {kind} {scene}: exit {p.returncode}\n{p.stderr}")
        return "", []
    return lines[0], lines[1:]


folder, options = plan("work-precision", "rope.json", "student")
if options != ["--time", "0.5"]:
    failures.append(f"plan: the rope's work-precision default should be --time 0.5 (no ground contact), got {options}")
if plan("work-precision", "rope.json", "student", "--time", "0.3")[1] != ["--time", "0.3"]:
    failures.append("plan: the user's --time should replace the default")
cloth = plan("stability", "net_hanging.json", "student", "--set", "net.resolution=16")[1]
if cloth != ["--set", "net.resolution=16", "--set", "net.stretch_limit.enabled=false", "--no-map"]:
    failures.append(f"plan: the user's --set of one key should keep the other defaults, got {cloth}")
for kind, scene in (("work-precision", "net_hanging.json"), ("work-precision", "softbody_ball.json"),
                    ("resolution", "rope.json"), ("resolution", "net_hanging.json"), ("resolution", "softbody_ball.json")):
    if not plan(kind, scene, "student")[1]:
        failures.append(f"plan: no defaults for {kind} on {scene}, a lab's default scene")
folders = {plan("work-precision", "rope.json", "student")[0], plan("work-precision", "rope.json", "student", "--time", "1")[0],
           plan("work-precision", "rope.json", "reference")[0], plan("stability", "rope.json", "student")[0]}
if len(folders) != 4:
    failures.append(f"plan: runs with other options, trees or kinds must get their own folder: {sorted(folders)}")

for f in failures:
    print("FAIL:", f)
print("chart commands: ok" if not failures else f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
