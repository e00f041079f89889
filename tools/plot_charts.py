#!/usr/bin/python3
"""Draw springlab's speed-against-accuracy charts from the CSV files the app writes.

usage: /usr/bin/python3 tools/plot_charts.py work-precision|stability|resolution FOLDER
       /usr/bin/python3 tools/plot_charts.py plan KIND SCENE ROOT TREE [OPTIONS...]

FOLDER holds the CSV and JSON files of `springlab-* chart KIND`.
Writes KIND.png and KIND.svg (stability also stability_map.png/.svg) into the same folder.
`plan` is what `./springlab chart` asks first: it prints the output folder, then the options
for the app one per line (the user's, plus the scene's chart defaults for the options the
user did not give). Needs matplotlib for drawing (Debian's python3-matplotlib, so run it with
/usr/bin/python3); `plan` needs only the standard library.
"""
import csv
import json
import math
import pathlib
import sys

plt = None  # matplotlib.pyplot, imported by main() when a chart is drawn


# ---- defaults and output folders of `./springlab chart` -------------------------------------
# Per chart kind and scene (file name without .json): the options that make the chart show
# what it is for on that scene, in a few minutes. The handouts' charts use the same settings
# (tools/handout_charts.sh). An option the user gives replaces its default; `--set KEY=...`
# replaces only the default of that KEY.
# - work-precision: a window without contact events (the rope reaches the ground after about
#   0.55 s; its ground contact zig-zags the curves and hides the orders); the cloth at 32 x 32
#   with stretch limiting off (a position correction that hides the integrators' error).
# - stability: the same cloth; the stiffness x dt map only where it is cheap (the rope).
# - resolution: an observable that depends on the resolution, with resolutions that finish.
CLOTH = ["--set", "net.resolution=32", "--set", "net.stretch_limit.enabled=false"]
CHART_DEFAULTS = {
    ("work-precision", "rope"): ["--time", "0.5"],
    ("work-precision", "rope_2d"): ["--time", "0.5"],
    ("work-precision", "mass_on_spring"): ["--time", "5"],
    ("work-precision", "net_hanging"): CLOTH + ["--time", "0.2", "--levels", "6", "--repeats", "1"],
    ("work-precision", "softbody_ball"): ["--time", "0.2", "--levels", "6", "--repeats", "1"],
    ("stability", "mass_on_spring"): ["--no-map"],
    ("stability", "net_hanging"): CLOTH + ["--no-map"],
    ("stability", "softbody_ball"): ["--no-map"],
    ("resolution", "rope"): ["--observable", "sag", "--tol", "0.02"],
    ("resolution", "net_hanging"): ["--observable", "drape_height", "--tol", "0.02", "--time", "1",
                                    "--resolutions", "8,16,32"],
    ("resolution", "softbody_ball"): ["--observable", "volume", "--tol", "0.02", "--time", "0.5",
                                      "--resolutions", "1,2,3"],
}
FLAGS = {"--no-map"}  # options without a value


def split_options(args):
    """The options as (key, [tokens]) in order: `--set K=V` is keyed by K, `--opt=v` is split."""
    options, i = [], 0
    while i < len(args):
        a = args[i]
        if a.startswith("--") and "=" in a and not a.startswith("--set="):
            name, value = a.split("=", 1)
            tokens, i = [name, value], i + 1
        elif a.startswith("--set="):
            tokens, i = ["--set", a[len("--set="):]], i + 1
        elif a in FLAGS or not a.startswith("--") or i + 1 >= len(args):
            tokens, i = [a], i + 1
        else:
            tokens, i = [a, args[i + 1]], i + 2
        key = tokens[0]
        if key == "--set" and len(tokens) == 2:
            key = "--set " + tokens[1].split("=", 1)[0]
        options.append((key, tokens))
    return options


def with_defaults(kind, scene_name, args):
    """The user's options, then the defaults of (kind, scene) the user did not give."""
    given = {key for key, _ in split_options(args)}
    added = [tokens for key, tokens in split_options(CHART_DEFAULTS.get((kind, scene_name), [])) if key not in given]
    return list(args) + [t for tokens in added for t in tokens]


def slug(tokens):
    """A folder-name-safe summary of options: `--time 0.5 --set net.resolution=32` -> `time-0.5_net.resolution-32`."""
    parts = []
    for key, option in split_options(tokens):
        if key in ("--out", "--threads"):
            continue
        name = option[0].lstrip("-")
        value = option[1] if len(option) > 1 else ""
        if name == "set":
            name, value = value.split("=", 1) if "=" in value else (value, "")
        text = name + ("-" + value.replace(",", "-") if value else "")
        part = "".join(c if c.isalnum() or c in "._-" else "" for c in text)
        parts.append(part)
    return "_".join(parts)


def plan(kind, scene, root, tree, args):
    """The output folder and the app's options of one `./springlab chart` run. Runs with other
    options, another tree or another kind get another folder, so none overwrites another:
    out/charts/<scene>/<kind>[_<options>][_reference]/."""
    name = pathlib.Path(scene).name
    name = name[:-len(".json")] if name.endswith(".json") else name
    full = with_defaults(kind, name, args)
    user_out = [tokens[1] for key, tokens in split_options(args) if key == "--out" and len(tokens) == 2]
    if user_out:
        folder = pathlib.Path(user_out[-1])
    else:
        tag = "_".join(p for p in (kind, slug(full), "reference" if tree == "reference" else "") if p)
        folder = pathlib.Path(root) / "out" / "charts" / name / tag[:150]
    return folder, [t for key, tokens in split_options(full) if key != "--out" for t in tokens]


def _pyplot():
    # matplotlib only where a chart is drawn: `plan` runs on any Python.
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot

    return matplotlib.pyplot

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


def overlapping_texts(fig):
    """Pairs of visible, non-empty texts of the figure whose boxes overlap (as drawn)."""
    import matplotlib.text

    renderer = fig.canvas.get_renderer()
    # Tick labels count only where matplotlib draws them: visible, at a tick inside the view.
    ticks, drawn = set(), []
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            lo, hi = sorted(axis.get_view_interval())
            for locs, labels in ((axis.get_majorticklocs(), axis.get_majorticklabels()),
                                 (axis.get_minorticklocs(), axis.get_minorticklabels())):
                for loc, label in zip(locs, labels):
                    ticks.add(id(label))
                    if lo - 1e-9 * abs(lo) <= loc <= hi + 1e-9 * abs(hi):
                        drawn.append(label)
    drawn_ids = {id(t) for t in drawn}
    texts = [t for t in fig.findobj(matplotlib.text.Text)
             if t.get_visible() and t.get_text().strip() and (id(t) not in ticks or id(t) in drawn_ids)]
    boxes = [(t.get_text(), t.get_window_extent(renderer)) for t in texts]
    pairs = []
    for i in range(len(boxes)):
        for j in range(i + 1, len(boxes)):
            (a, p), (b, q) = boxes[i], boxes[j]
            if p.width > 0 and q.width > 0 and p.overlaps(q):
                pairs.append((a, b))
    return pairs


def covering_notes(fig):
    """Notes written into an axes (annotations, ax.text) that cover one of its markers or
    bars, or reach out of it: (note, what) pairs."""
    from matplotlib.collections import LineCollection
    from matplotlib.transforms import Bbox

    renderer = fig.canvas.get_renderer()
    found = []
    for ax in fig.axes:
        frame = ax.get_window_extent(renderer)
        marks = []
        for coll in ax.collections:
            if isinstance(coll, LineCollection):
                for seg in coll.get_segments():
                    pts = ax.transData.transform(seg)
                    marks.append(Bbox([pts.min(axis=0) - 1, pts.max(axis=0) + 1]))
            else:
                sizes = coll.get_sizes()
                for k, xy in enumerate(coll.get_offsets()):
                    r = (sizes[k % len(sizes)] ** 0.5 / 2 if len(sizes) else 3) * fig.dpi / 72
                    cx, cy = ax.transData.transform(xy)
                    marks.append(Bbox([[cx - r, cy - r], [cx + r, cy + r]]))
        for t in ax.texts:
            if not (t.get_visible() and t.get_text().strip()):
                continue
            box = t.get_window_extent(renderer)
            if box.x0 < frame.x0 - 1 or box.x1 > frame.x1 + 1 or box.y0 < frame.y0 - 1 or box.y1 > frame.y1 + 1:
                found.append((t.get_text(), "the edge of its panel"))
            if any(box.overlaps(m) for m in marks):
                found.append((t.get_text(), "a marker or bar"))
    return found


def save(fig, folder, stem):
    # Labels that cover each other, or a note over the data, are bugs of the chart: say so
    # (tests/studies/check_charts.py fails on these lines).
    fig.canvas.draw()
    for a, b in overlapping_texts(fig):
        print(f"overlapping labels in {stem}: {a!r} and {b!r}")
    for note, what in covering_notes(fig):
        print(f"overlapping labels in {stem}: {note!r} covers {what}")
    for ext in ("png", "svg"):
        fig.savefig(folder / f"{stem}.{ext}", dpi=130, bbox_inches="tight")
    plt.close(fig)
    print(f"wrote {folder / stem}.png and .svg")


def title_of(facts):
    sets = facts.get("sets") or []
    return facts.get("name", facts.get("scene", "")) + (f" ({', '.join(sets)})" if sets else "")


def blown_up_summary(rows, methods):
    """One line per method with runs that blew up: how many, and from which dt up (a run
    that blew up is kept in the CSV, summarised here rather than drawn as a cross per run)."""
    lines = []
    for m in methods:
        bad = sorted(float(r["dt_s"]) for r in rows if r["integrator"] == m and r["stable"] != "1")
        if bad:
            ok = [float(r["dt_s"]) for r in rows if r["integrator"] == m and r["stable"] == "1"]
            note = f"{m}: {len(bad)} of {len(bad) + len(ok)} runs blew up, dt {bad[0]:.3g} s"
            note += f" to {bad[-1]:.3g} s" if len(bad) > 1 else ""
            if ok and max(ok) > bad[0]:
                note += " (not every larger dt: see the CSV)"
            lines.append(note)
    return lines


def work_precision(folder):
    rows = read_csv(folder / "work_precision.csv")
    facts = json.loads((folder / "work_precision.json").read_text())
    methods = list(dict.fromkeys(r["integrator"] for r in rows))
    # Three columns: error against wall time, against force evaluations, and against dt (so
    # every point's dt can be read off: each method's points are the same dt ladder, and a
    # point in the other panels has the dt of the point at its height here).
    fig, axes = plt.subplots(2, 3, figsize=(16, 9), sharey="row")
    panels = [("final_error_m", "wall_s", "wall time per run (s, median)"),
              ("final_error_m", "force_evaluations", "force evaluations per run"),
              ("final_error_m", "dt_s", "time step dt (s)"),
              ("max_error_m", "wall_s", "wall time per run (s, median)"),
              ("max_error_m", "force_evaluations", "force evaluations per run"),
              ("max_error_m", "dt_s", "time step dt (s)")]
    for ax, (err_key, cost_key, xlabel) in zip(axes.flat, panels):
        for i, m in enumerate(methods):
            colour, marker = style(m, i)
            ok = [r for r in rows if r["integrator"] == m and r["stable"] == "1"]
            ax.plot([max(float(r[cost_key]), 1e-9) for r in ok], [max(float(r[err_key]), 1e-16) for r in ok],
                    marker=marker, color=colour, label=m, lw=1.4, ms=5)
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
    # The runs that blew up, one line per method, under the panels.
    summary = blown_up_summary(rows, methods) or ["no run blew up"]
    fig.text(0.5, -0.01, "Not drawn, blew up:\n" + "\n".join(summary), ha="center", va="top", fontsize=8.5,
             color="0.25")
    save(fig, folder, "work_precision")


def stability(folder):
    rows = read_csv(folder / "stability.csv")
    facts = json.loads((folder / "stability.json").read_text())
    # About 1.2 inches a method, so each column's note has room beside its neighbours'.
    fig, ax = plt.subplots(figsize=(max(10.5, 1.2 * len(rows) + 1.5), 5.8))
    names = [r["integrator"] for r in rows]
    xs = range(len(rows))
    inf = float("inf")
    measured = [float(r["measured_dt_s"]) for r in rows]
    predictions = [float(r["predicted_dt_s"]) for r in rows]
    finite = [m for m in measured if 0 < m < inf]
    top = max(finite + [p for p in predictions if 0 < p < inf]) * 3 if finite else 1.0
    undamped = [float(r.get("undamped_dt_s", 0) or 0) for r in rows]
    # The chart's floor: a third below the smallest limit measured or predicted (a prediction
    # far below every measured one, explicit Euler's on the rope, is written, not drawn).
    bottom = min(finite + [top]) / 3
    # A bisection whose trial needs more steps than the chart runs measured nothing (NaN).
    not_tried = "not measured (its trial\nneeds too many steps)"
    for x, r, m, p, u in zip(xs, rows, measured, predictions, undamped):
        colour, marker = style(r["integrator"], x)
        shown = m if 0 < m < inf else top
        if 0 < m < inf:
            ax.scatter([x], [shown], marker=marker, s=90, color=colour, zorder=4)
        elif m != m:
            # Not measured (NaN): the trial needs more steps than the chart runs; no marker.
            pass
        elif m == inf:
            # No limit found: every trial survived, so the limit lies above the largest dt
            # tried. An arrow up off the chart, not a point a reader would take for a limit.
            ax.annotate("", xy=(x, top * 3.5), xytext=(x, top / 2.5), zorder=4,
                        arrowprops=dict(arrowstyle="-|>", color=colour, lw=2.2, mutation_scale=18))
        else:
            # No stable dt found: every trial failed down to the smallest dt the bisection could
            # afford. An arrow down off the chart.
            ax.annotate("", xy=(x, bottom * 1.02), xytext=(x, bottom * 2.5), zorder=4,
                        arrowprops=dict(arrowstyle="-|>", color=colour, lw=2.2, mutation_scale=18))
        # The undamped rule c / w_max, dashed, where the method has one: how far damping,
        # contacts and pressure move the limit.
        if 0 < u < inf:
            ax.hlines(u, x - 0.35, x + 0.35, color="0.45", lw=1.2, linestyles="dashed")
        # Each column's note is centred on it, above both its marker and its bar, in a few
        # short lines: it stays within the column and never covers a marker or a bar.
        if p != p:
            # NaN: the step is not smooth where the scene settles (a contact switching there),
            # so it has no linearised limit; only the measured one is drawn.
            text = "predicted: none (the\nstep is not smooth\nwhere it settles)" + (";\n" + not_tried if m != m else "")
            above = shown
        elif p == inf:
            # Stable at every dt the prediction tried: say what the bisection found.
            text = ("predicted: no limit;\nnone found (the arrow:\nabove every trial dt)" if m == inf
                    else "predicted: no limit;\n" + not_tried if m != m else f"predicted: no limit;\nfails at {m:.3g} s")
            above = shown
        elif p > 0:
            if p >= bottom:
                ax.hlines(p, x - 0.35, x + 0.35, color="black", lw=2)
            # A trial stretched to its cap (100 times the study's duration, stabilityTrialDuration
            # in framework/studies/stability.cpp) still could not
            # show the growth just past the limit (explicit Euler on the ball: the wobble only the
            # air damps grows by e in about 9 minutes at 1.03 times the limit).
            capped = float(r.get("duration_s", 0) or 0) >= 99 * float(facts.get("duration_s", inf))
            if m != m:
                text = f"predicted {p:.2g} s;\n{not_tried}"
            elif m == 0:
                text = f"predicted {p:.2g} s;\nmeasured: no stable\ndt (arrow down)"
            elif capped and m > 1.05 * p:
                text = f"measured\n{m / p:.3g} x predicted\n(slow growth unseen\nin {float(r['duration_s']):.3g} s)"
            else:
                text = f"measured\n{m / p:.3g} x predicted"
            # A miss (measured more than 5 % below the prediction) with a state the trials passed
            # through before they failed stiffer than the rest: that state (stiffest_on_the_way_*,
            # a frozen state's limit, a diagnostic and not a prediction; every row has it in the CSV).
            way = float(r.get("stiffest_on_the_way_dt_s", "nan") or "nan")
            way_at = float(r.get("stiffest_on_the_way_at_s", "nan") or "nan")
            if way_at == way_at and 0 < way < p and 0 < m < 0.95 * p:
                text += f";\nstiffest on the way\n{way:.2g} s (t = {way_at:.2g} s)"
            above = max(shown if m == m else 0, p, u if 0 < u < inf else 0)
        else:
            # Unstable at every dt: a trial that survives grows too slowly to show within it.
            text = "predicted: no\nstable dt" + ("; none\nmeasured (arrow down)" if m == 0 else
                                                 ";\n" + not_tried if m != m else
                                                 f";\nsurvives its trial\nup to {m:.2g} s (slow\ngrowth unseen)")
            above = shown
        # Under the arrow up where no limit was found (it fills the room above); above the
        # arrow down where no stable dt was found.
        if m == inf:
            where, offset, va = top / 2.5, -6, "top"
        elif m == 0:
            where, offset, va = bottom * 2.5, 6, "bottom"
        elif m != m:
            # Not measured: above the prediction's bar, or near the floor when that is off the chart.
            where, offset, va = max(above, bottom * 1.2), 10, "bottom"
        else:
            where, offset, va = above, 10, "bottom"
        ax.annotate(text, (x, where), textcoords="offset points", xytext=(0, offset),
                    ha="center", va=va, fontsize=7.5, color="0.15" if 0 < p < inf else "0.35")
    # Legend proxies: the marker of each method is its measured dt, the bar the prediction.
    # Above the axes, so it covers no column.
    ax.scatter([], [], marker="o", color="0.4", s=60, label="measured (bisection on the blow-up check and, past the limit, the rest check)")
    ax.plot([], [], color="black", lw=2, label="predicted: limit of the linearised step")
    ax.plot([], [], color="0.45", lw=1.2, ls="dashed", label="undamped rule c / w_max")
    ax.set_ylim(bottom, top * 4)  # room above the highest marker for its note
    ax.set_xlim(-0.6, len(rows) - 0.4)
    ax.set_xticks(list(xs))
    # Names level, every second one a line lower, so long neighbours never meet.
    ax.set_xticklabels(names, fontsize=9)
    for i, tick in enumerate(ax.xaxis.get_major_ticks()):
        tick.set_pad(3.5 + 13 * (i % 2))
    ax.set_yscale("log")
    ax.set_ylabel("largest stable dt (s)")
    ax.grid(True, axis="y", which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=3, frameon=False)
    ax.set_title(f"Stability: {title_of(facts)}\nw_max = {facts['w_max_rad_s']:.4g} rad/s (Lanczos; Gershgorin bound "
                 f"{facts['gershgorin_rad_s']:.4g}); each trial at least {facts['duration_s']:.3g} s under the blow-up check",
                 fontsize=10, pad=24)
    save(fig, folder, "stability")

    map_path = folder / "stability_map.csv"
    if not map_path.exists():
        return
    cells = read_csv(map_path)
    boundary = read_csv(folder / "stability_boundary.csv")
    inf = float("inf")
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
    pred = [(float(b[xkey]), float(b["predicted_dt_s"])) for b in boundary if 0 < float(b["predicted_dt_s"]) < inf]
    if pred:
        ax.plot([p[0] for p in pred], [p[1] for p in pred], color="black", lw=2,
                label="predicted: limit of the linearised step")
    undamped = [(float(b[xkey]), float(b["undamped_dt_s"])) for b in boundary if 0 < float(b["undamped_dt_s"]) < inf]
    if undamped:
        ax.plot([p[0] for p in undamped], [p[1] for p in undamped], color="0.45", lw=1.2, ls="dashed",
                label=f"undamped rule c / w_max (c = {facts['map_stability_constant']:.3g})")
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
        # The last (costliest) point's label to its left, so it stays inside the panel.
        last = cost >= max(e[0] for e in errs)
        right.annotate(label, (cost, y), textcoords="offset points", xytext=(-8, 6) if last else (6, 6),
                       ha="right" if last else "left", fontsize=8)
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
    if len(sys.argv) >= 6 and sys.argv[1] == "plan":
        folder, options = plan(sys.argv[2], sys.argv[3], sys.argv[4], sys.argv[5], sys.argv[6:])
        print(folder)
        for option in options:
            print(option)
        return 0
    if len(sys.argv) != 3 or sys.argv[1] not in ("work-precision", "stability", "resolution"):
        print(__doc__, file=sys.stderr)
        return 2
    global plt
    plt = _pyplot()
    folder = pathlib.Path(sys.argv[2])
    {"work-precision": work_precision, "stability": stability, "resolution": resolution}[sys.argv[1]](folder)
    return 0


if __name__ == "__main__":
    sys.exit(main())
