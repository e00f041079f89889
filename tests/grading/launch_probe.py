#!/usr/bin/env python3
"""`check` and `grade` launch student code the same way: a probe test (tests/support/
launch_probe.cpp) records what its process sees (command line, environment, standard input
after the test's name, folder, user, PID namespace, open descriptors, limits), once as a
`grade` worker (judged_run.run_judged, beside a stand-in judge) and once as a `check` test
(gtest_runner.run_test, what tools/grade.py runs), and the two views must be identical, with
bubblewrap (where it works here) and without it (as on a student's laptop). Also: a program
that cannot start in bubblewrap is told apart (tools/grade.py then checks without it).

    launch_probe.py --worker PROBE_WITH_WORKER_MAIN --check PROBE_WITH_GRADING_MAIN [--seccomp PROGRAM]
"""
import argparse
import json
import os
import pathlib
import shutil
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
from springlab_grader import gtest_runner, judged_run  # noqa: E402
from springlab_grader.sandbox import Sandbox  # noqa: E402

TEST = "LaunchProbe.RecordsWhatItsProcessSees"
SEED = 7
MARK = "LAUNCH-VIEW "

# The stand-in judge: it drains the worker's trace and reports nothing (the probe's view
# comes in the worker's output, where its failure is printed).
JUDGE = """import json, os, sys
fd = int(os.environ["SPRINGLAB_CALL_TRACE_FD"])
while os.read(fd, 65536):
    pass
path = [a for a in sys.argv if a.startswith("--springlab-report=")][0].split("=", 1)[1]
with open(path, "w") as out:
    out.write(json.dumps({"tests": []}))
"""


def view_in(text, where):
    for line in text.splitlines():
        if MARK in line:
            return json.loads(line[line.index(MARK) + len(MARK):])
    raise SystemExit(f"launch_probe: no {MARK.strip()} line in the {where}:\n{text}")


def without_private_folder(view):
    """Without bubblewrap the program's folder (its cwd, HOME and TMPDIR) is a fresh temporary
    folder per launch: the same place by role, another name each time."""
    folder = view["cwd"]
    text = json.dumps(view)
    return json.loads(text.replace(json.dumps(folder)[1:-1], "<private folder>")) if folder != "/tmp" else view


def views(worker, check, judge, sandbox, seccomp):
    graded = judged_run.run_judged(str(judge), str(worker), TEST, sandbox, {"SPRINGLAB_SEED": str(SEED)},
                                   seccomp=seccomp)
    checked = gtest_runner.run_test(str(check), TEST, SEED, sandbox, seccomp=seccomp)
    return (without_private_folder(view_in(graded.worker.output, "grade worker's output")),
            without_private_folder(view_in(checked.message, "check's failure message")))


def problems(mode, worker_view, check_view):
    found = []
    if worker_view != check_view:
        for key in sorted(set(worker_view) | set(check_view)):
            if worker_view.get(key) != check_view.get(key):
                found.append(f"{mode}: {key} differs: grade worker {worker_view.get(key)!r}, "
                             f"check {check_view.get(key)!r}")
    # bubblewrap's --chdir also sets PWD.
    expected_env = {*judged_run.WORKER_ENV, "SPRINGLAB_SEED", "SPRINGLAB_CALL_TRACE_FD",
                    *(["PWD"] if mode == "bubblewrap" else [])}
    for name, view in (("grade worker", worker_view), ("check", check_view)):
        if view["argv"] != [judged_run.PROGRAM_NAME, *judged_run.WORKER_ARGS]:
            found.append(f"{mode}: the {name}'s command line is {view['argv']}")
        names = {entry.split("=", 1)[0] for entry in view["environment"]}
        if names != expected_env:
            found.append(f"{mode}: the {name}'s environment has {sorted(names)}, not {sorted(expected_env)}")
        if any("LaunchProbe" in s or "gtest_filter" in s for s in view["argv"] + view["environment"]):
            found.append(f"{mode}: the {name}'s command line or environment names the test")
        if view["stdin_after_the_name"] != "":
            found.append(f"{mode}: the {name}'s standard input holds more than the test's name")
        if view["descriptors"] != {"0": "pipe", "1": "file", "2": "file", str(judged_run.CHANNEL_FD): "pipe"}:
            found.append(f"{mode}: the {name}'s open descriptors are {view['descriptors']}")
    return found


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--worker", required=True, help="the probe linked with worker_main.cpp")
    ap.add_argument("--check", required=True, help="the probe linked with grading_main.cpp")
    ap.add_argument("--seccomp", default="", help="the program that writes the workers' seccomp filter")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory(prefix="springlab-launch-probe-") as folder:
        # The worker user (root graders) reaches the programs as tools/grade.py's copy does.
        os.chmod(folder, 0o711)
        worker, check, judge = (pathlib.Path(folder) / n for n in ("worker", "check", "judge"))
        shutil.copy2(args.worker, worker)
        shutil.copy2(args.check, check)
        # The judge runs as an unprivileged user of its own: its interpreter must be one that
        # user can run (Debian's, not one under root's private home, as pyenv's is).
        interpreter = "/usr/bin/python3" if os.access("/usr/bin/python3", os.X_OK) else sys.executable
        judge.write_text(f"#!{interpreter}\n{JUDGE}")
        for program in (worker, check, judge):
            os.chmod(program, 0o755)
        sandbox = Sandbox(timeout=30)
        found, modes = [], []
        if judged_run.bubblewrap():
            modes.append("bubblewrap")
            # A program that needs a file outside /usr (here its interpreter) does not start in
            # bubblewrap, and tools/grade.py then checks without it; the probe does start.
            outside = pathlib.Path(folder) / "interpreter"
            outside.symlink_to(sys.executable)
            needy = pathlib.Path(folder) / "needs_outside"
            needy.write_text(f"#!{outside}\nimport sys\nsys.exit(2)\n")
            os.chmod(needy, 0o755)
            if judged_run.starts_in_bubblewrap(needy, sandbox):
                found.append("bubblewrap: a program whose interpreter is outside /usr seems to start there")
            if not judged_run.starts_in_bubblewrap(check, sandbox):
                found.append("bubblewrap: the check's probe does not start there")
            seen = views(worker, check, judge, sandbox, args.seccomp or None)
            found += problems("bubblewrap", *seen)
        # Without bubblewrap (a student's laptop, a container without user namespaces).
        real = judged_run.bubblewrap
        judged_run.bubblewrap = lambda: None
        try:
            modes.append("plain process")
            seen = views(worker, check, judge, sandbox, args.seccomp or None)
            found += problems("plain process", *seen)
        finally:
            judged_run.bubblewrap = real
    for line in found:
        print(line, file=sys.stderr)
    if found:
        return 1
    print(f"check and grade launch the test the same way ({', '.join(modes)}); what it saw in the last:\n"
          f"{json.dumps(seen[-1])}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
