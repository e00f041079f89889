#!/usr/bin/env python3
"""`springlab sim` at 0.97 and 1.03 times the step's stability limit: exit 0, then exit 4.

Usage: check_sim_at_the_limit.py SPRINGLAB_BINARY SOURCE_DIR [capped|resting]

The rows are those whose instability past the limit the energy does not show: a contact or the
stretch limit caps the growing mode, and the masses turn back every step (detector 5) or keep
moving where a stable step comes to rest (detector 6). Telling that from the scene's own motion
takes the same scene at half the limit, which the stability chart's trials are held to; before
`sim` measured it too, every row here ran to the end at 1.03 times its limit (exit 0).

The wind ball under velocity Verlet, the trampoline under position Verlet and the pillow under
velocity Verlet hold a mode that the floor, the stretch limit or the pillow's own wobble caps
within every allowance of the check (all three ran to the end at 1.03 times before): what reports it is the rest check after the run (the scene's rest, disturbed, does not hold
at that dt), which `sim` runs past the limit where the scene rests at half the limit.

`resting`: bodies that fell and rest on a projected collider, where the step is not smooth (a
push into the collider is projected away, a pull moves freely) and the limit holds the masses the
contacts hold one-sidedly (step_stability.cpp, findHeldMasses); before that, no limit ("not
smooth"). The runs are the oracle the limit is held to.

The limit is sim's own: a one-step run far past it prints it ("... times the step's stability
limit (L s)"). Each run lasts the stability chart's trial time for that scene and method
(stability.csv, duration_s), rounded up.
"""
import math
import re
import subprocess
import sys
from pathlib import Path

# scene, integrator, the chart's trial time (s)
ROWS = [
    ("softbody_cube_asc", "rk4", 20.0),
    ("softbody_cube_asc", "explicit_euler", 214.0),
    ("net_sphere_slope_weak_wind", "velocity_verlet", 4.5),
    ("net_sphere_slope_strong_wind", "velocity_verlet", 4.5),
    ("softbody_ring_2d", "midpoint", 9628.0),
    # The floor caps the mode within the check's allowances; the rest check sees it.
    ("softbody_wind", "velocity_verlet", 3.04),
    # The stretch limit's projection slows the growth below what the run's check sees in 2 s.
    ("net_trampoline", "position_verlet", 2.06),
    ("softbody_pillow_obj", "velocity_verlet", 4.35),
    # The dropped ball at its rest on the floor: the floor caps the mode; the rest check sees it.
    ("softbody_ball", "symplectic_euler", 3.04),
]

# Fallen bodies at rest on a projected collider, under explicit Euler (its first step from rest
# leaves a resting mass exactly on the surface, where a perturbation's sign decides its contact).
RESTING = [
    ("net_sphere_drop", "explicit_euler", 0.67),
    ("net_self_collision", "explicit_euler", 0.74),
    # The ball under the user's sphere: at 1.03 times its limit the wobble on the floor grows for
    # 14 s before the check sees it (the chart's trial of 3 s measured 1.06 times the limit).
    ("softbody_user_sphere", "explicit_euler", 30.0),
]

LIMIT = re.compile(r"times the step's stability limit \(([0-9.eE+-]+) s\)")


def run(binary, scene, integrator, dt, steps):
    return subprocess.run([binary, "sim", str(scene), "--integrator", integrator, "--dt", repr(dt),
                           "--steps", str(steps)], capture_output=True, text=True, timeout=1200)


def main():
    binary, source = sys.argv[1], Path(sys.argv[2])
    rows = RESTING if len(sys.argv) > 3 and sys.argv[3] == "resting" else ROWS
    failures = []
    for name, integrator, duration in rows:
        scene = source / "scenes" / (name + ".json")
        probe = run(binary, scene, integrator, 1.0, 1)
        found = LIMIT.search(probe.stderr)
        if not found:
            failures.append(f"{name} {integrator}: sim at dt = 1 s printed no limit:\n{probe.stderr}")
            continue
        limit = float(found.group(1))
        for factor, expected in ((0.97, 0), (1.03, 4)):
            dt = factor * limit
            steps = math.ceil(duration / dt)
            result = run(binary, scene, integrator, dt, steps)
            verdict = f"{name} {integrator} at {factor} x {limit:.6g} s ({steps} steps): exit {result.returncode}"
            print(verdict + ("" if result.returncode == expected else f", expected {expected}"))
            if result.returncode != expected:
                failures.append(verdict + f", expected {expected}\n{result.stderr[-2000:]}")
    for failure in failures:
        print("FAIL " + failure, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
