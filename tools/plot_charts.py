#!/usr/bin/python3
"""Draw springlab's speed-against-accuracy charts from the CSV files the app writes.

usage: /usr/bin/python3 tools/plot_charts.py work-precision|stability|resolution FOLDER

FOLDER holds the CSV and JSON files of `springlab-* chart KIND` (default out/charts/<scene>).
Writes KIND.png and KIND.svg (stability also stability_map.png/.svg) into the same folder.
Needs matplotlib: Debian's python3-matplotlib, so run it with /usr/bin/python3.
"""
import csv
import json
import math
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# One colour and marker per integrator, the same in every chart.
STYLE = {
    "explicit_euler": ("tab:red", "v"),
    "symplectic_euler": ("tab:blue", "o"),
    "position_verlet": ("tab:green", "s"),
    "velocity_verlet": ("tab:olive", "D"),
    "midpoint": ("tab:purple", "^"),
    "rk4": ("tab:orange", "P"),
    "implicit_euler": ("tab:brown", "X"),
    "implicit_euler_blocks": ("tab:pink", "*"),
    # position-based and projective methods (Lab 2, exercises 2.11 and 2.12)
    "xpbd": ("tab:cyan", "h"),
    "projective_dynamics": ("black", "p"),
}
EXTRA = ["tab:gray", "tab:cyan", "black"]


def style(name, index=0):
    return STYLE.get(name, (EXTRA[index % len(EXTRA)], "o"))


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def save(fig, folder, stem):
    for ext in ("png", "svg"):
        fig.savefig(folder / f"{stem}.{ext}", dpi=130, bbox_inches="tight")
    plt.close(fig)
    print(f"wrote {folder / stem}.png and .svg")


def title_of(facts):
    sets = facts.get("sets") or []
    return facts.get("name", facts.get("scene", "")) + (f" ({', '.join(sets)})" if sets else "")


def work_precision(folder):
    rows = read_csv(folder / "work_precision.csv")
    facts = json.loads((folder / "work_precision.json").read_text())
    methods = list(dict.fromkeys(r["integrator"] for r in rows))
    fig, axes = plt.subplots(2, 2, figsize=(12, 9), sharey="row")
    panels = [("final_error_m", "wall_s", "wall time per run (s, median)"),
              ("final_error_m", "force_evaluations", "force evaluations per run"),
              ("max_error_m", "wall_s", "wall time per run (s, median)"),
              ("max_error_m", "force_evaluations", "force evaluations per run")]
    for ax, (err_key, cost_key, xlabel) in zip(axes.flat, panels):
        finite = [float(r[err_key]) for r in rows if r["stable"] == "1" and math.isfinite(float(r[err_key]))]
        top = max(finite) * 3 if finite else 1.0
        for i, m in enumerate(methods):
            colour, marker = style(m, i)
            ok = [r for r in rows if r["integrator"] == m and r["stable"] == "1"]
            bad = [r for r in rows if r["integrator"] == m and r["stable"] != "1"]
            ax.plot([max(float(r[cost_key]), 1e-9) for r in ok], [max(float(r[err_key]), 1e-16) for r in ok],
                    marker=marker, color=colour, label=m, lw=1.4, ms=5)
            # Unstable runs: drawn at the top of the panel, not dropped.
            if bad:
                ax.scatter([max(float(r[cost_key]), 1e-9) for r in bad], [top] * len(bad), marker="x", color=colour,
                           s=50, zorder=5)
        ax.axhline(top, color="0.6", lw=0.8, ls=":")
        ax.text(0.99, 0.97, "x: blew up", transform=ax.transAxes, va="top", ha="right", fontsize=8, color="0.3")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(xlabel)
        what = "at the final time" if err_key == "final_error_m" else "largest over the run"
        ax.set_ylabel(f"position error {what} (m)")
        ax.grid(True, which="major", alpha=0.3)
    axes[0, 0].legend(fontsize=8, loc="lower left")
    fig.suptitle(f"Work-precision: {title_of(facts)}\n{facts['duration_s']:g} s simulated; error = largest distance "
                 f"of any mass from an RK4 run at dt = {facts['reference_dt_s']:.3g} s; "
                 f"w_max = {facts['w_max_rad_s']:.4g} rad/s", fontsize=10)
    save(fig, folder, "work_precision")


def stability(folder):
    rows = read_csv(folder / "stability.csv")
    facts = json.loads((folder / "stability.json").read_text())
    fig, ax = plt.subplots(figsize=(10.5, 5.5))
    names = [r["integrator"] for r in rows]
    xs = range(len(rows))
    measured = [float(r["measured_dt_s"]) for r in rows]
    finite = [m for m in measured if 0 < m < float("inf")]
    inf = float("inf")
    predictions = [float(r["predicted_dt_s"]) for r in rows]
    top = max(finite + [p for p in predictions if 0 < p < inf]) * 3 if finite else 1.0
    for x, r in zip(xs, rows):
        colour, marker = style(r["integrator"], x)
        m = float(r["measured_dt_s"])
        ax.scatter([x], [m if 0 < m < float("inf") else top], marker=marker, s=90, color=colour, zorder=4)
        p = float(r["predicted_dt_s"])
        if p == float("inf"):
            # Unconditionally stable in theory (implicit Euler): say what the bisection found.
            text = "c = inf: no limit found" if m == float("inf") else f"c = inf in theory;\nfails at {m:.3g} s"
            ax.annotate(text, (x, m if m < float("inf") else top), textcoords="offset points", xytext=(-40, 12),
                        fontsize=8, color="0.3")
        elif p > 0:
            ax.hlines(p, x - 0.35, x + 0.35, color="black", lw=2)
            ax.annotate(f"measured {m / p:.3f}x\npredicted", (x, m), textcoords="offset points", xytext=(12, 4),
                        fontsize=8)
        else:
            ax.annotate("no undamped limit (c = 0):\nsurvives the trial time only", (x, m),
                        textcoords="offset points", xytext=(-40, 12), fontsize=8, color="0.3")
    # Legend proxies: the marker of each method is its measured dt, the bar the prediction.
    ax.scatter([], [], marker="o", color="0.4", s=60, label="measured (bisection on the blow-up check)")
    ax.plot([], [], color="black", lw=2, label="predicted c / w_max")
    lo = min(finite + [top]) / 3
    ax.set_ylim(lo, top * 1.5)
    ax.set_xlim(-0.7, len(rows) - 0.3)
    ax.set_xticks(list(xs))
    ax.set_xticklabels(names, rotation=20)
    ax.set_yscale("log")
    ax.set_ylabel("largest stable dt (s)")
    ax.grid(True, axis="y", which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    ax.set_title(f"Stability: {title_of(facts)}\nw_max = {facts['w_max_rad_s']:.4g} rad/s (Lanczos; Gershgorin bound "
                 f"{facts['gershgorin_rad_s']:.4g}); each trial {facts['duration_s']:.3g} s under the blow-up check",
                 fontsize=10)
    save(fig, folder, "stability")

    map_path = folder / "stability_map.csv"
    if not map_path.exists():
        return
    cells = read_csv(map_path)
    boundary = read_csv(folder / "stability_boundary.csv")
    use_k = facts.get("map_spring_constant_N_m", 0) > 0
    xkey = "spring_constant_N_m" if use_k else "stiffness_scale"
    fig, ax = plt.subplots(figsize=(8, 6))
    for label, colour, test in (("stable", "tab:green", lambda c: c["run"] == "1" and c["stable"] == "1"),
                                ("blew up", "tab:red", lambda c: c["run"] == "1" and c["stable"] != "1"),
                                ("not run (too many steps)", "0.7", lambda c: c["run"] != "1")):
        sel = [c for c in cells if test(c)]
        if sel:
            ax.scatter([float(c[xkey]) for c in sel], [float(c["dt_s"]) for c in sel], marker="s", s=70,
                       color=colour, label=label, edgecolors="none")
    pred = [(float(b[xkey]), float(b["predicted_dt_s"])) for b in boundary if float(b["predicted_dt_s"]) > 0]
    if pred:
        ax.plot([p[0] for p in pred], [p[1] for p in pred], color="black", lw=2,
                label=f"predicted c / w_max (c = {facts['map_stability_constant']:.3g})")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("spring constant k (N/m)" if use_k else "stiffness scale (x every spring's k)")
    ax.set_ylabel("dt (s)")
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=8, loc="lower left")
    ax.set_title(f"Stiffness x dt with {facts['map_integrator']}: {title_of(facts)}\n"
                 f"each cell {facts['map_duration_s']:.3g} s under the blow-up check", fontsize=10)
    save(fig, folder, "stability_map")


def resolution(folder):
    rows = read_csv(folder / "resolution.csv")
    series = read_csv(folder / "resolution_series.csv")
    facts = json.loads((folder / "resolution.json").read_text())
    value_key = [k for k in series[0].keys() if k not in ("resolution", "time_s")][0]
    key = facts["resolution_key"]
    fig, (left, right) = plt.subplots(1, 2, figsize=(13, 5.2))
    cmap = plt.get_cmap("viridis")
    for i, r in enumerate(rows):
        res = r["resolution"]
        pts = [s for s in series if s["resolution"] == res]
        colour = cmap(i / max(1, len(rows) - 1))
        left.plot([float(s["time_s"]) for s in pts], [float(s[value_key]) for s in pts], color=colour,
                  lw=2.2 if r["chosen"] == "1" else 1.2, label=f"{key} = {res}" + ("  (chosen)" if r["chosen"] == "1" else ""))
    left.set_xlabel("time (s)")
    left.set_ylabel(f"{facts['observable']} ({facts['unit']})")
    left.grid(True, alpha=0.3)
    left.legend(fontsize=8)
    left.set_title(f"{facts['observable']} over time at each resolution", fontsize=10)

    errs = [(float(r["cost_mass_evaluations"]), float(r["relative_error"]), r) for r in rows]
    finite = [e for e in errs if 0 < e[1] < float("inf")]
    floor = min([e[1] for e in finite] + [facts["tolerance"]]) / 10
    for i, (cost, err, r) in enumerate(errs):
        colour = cmap(i / max(1, len(rows) - 1))
        y = err if 0 < err < float("inf") else floor
        marker = "o" if err > 0 else "*"
        right.scatter([cost], [y], color=colour, s=140 if r["chosen"] == "1" else 60, marker=marker, zorder=4,
                      edgecolors="black" if r["chosen"] == "1" else "none")
        label = f"{r['resolution']}" + (" (finest: the reference)" if err == 0 else "")
        right.annotate(label, (cost, y), textcoords="offset points", xytext=(6, 6), fontsize=8)
    right.plot([e[0] for e in finite], [e[1] for e in finite], color="0.5", lw=1)
    right.axhline(facts["tolerance"], color="tab:red", ls="--", lw=1.2, label=f"tolerance {facts['tolerance']:g}")
    right.set_xscale("log")
    right.set_yscale("log")
    right.set_xlabel("cost (force evaluations x masses)")
    right.set_ylabel(f"relative error of {facts['observable']} (largest over the run)")
    right.grid(True, which="major", alpha=0.3)
    right.legend(fontsize=8)
    right.set_title(f"coarsest within tolerance: {key} = {facts['chosen']}", fontsize=10)
    fig.suptitle(f"Resolution: {title_of(facts)}, {facts['integrator']}", fontsize=11)
    save(fig, folder, "resolution")


def main():
    if len(sys.argv) != 3 or sys.argv[1] not in ("work-precision", "stability", "resolution"):
        print(__doc__, file=sys.stderr)
        return 2
    folder = pathlib.Path(sys.argv[2])
    {"work-precision": work_precision, "stability": stability, "resolution": resolution}[sys.argv[1]](folder)
    return 0


if __name__ == "__main__":
    sys.exit(main())
