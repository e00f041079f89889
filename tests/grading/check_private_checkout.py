#!/usr/bin/env python3
"""Grading runs wherever the instructor's checkout is, a private home folder (mode 700, as on
Ubuntu 21.04+, Fedora and most lab machines) included: the sandbox users never open the
checkout; what they must read or run is staged (tools/springlab_grader/staging.py).

The tree is copied into a folder of mode 700; its grading build (build-grader/, configured
and built there by the grader, ccache keeping it short) grades Lab 1's reference (100 %) and
its skeleton (0 %), and a traceback or a permission error fails the test.

    tests/grading/check_private_checkout.py --work build/tests/grading/private_checkout
"""
import argparse
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import release  # noqa: E402


def grade(tree, submission, expect, work):
    env = dict(os.environ, CCACHE_BASEDIR=str(tree))  # the copy's compiles hit the original's cache
    run = subprocess.run([sys.executable, str(tree / "tools" / "submission.py"), "grade", str(submission), "--lab",
                          "rope", "--cache", str(tree / "build-grader"), "--jobs", "2", "--seed", "7", "--quiet",
                          "--expect-percent", str(expect), "--out", str(work / f"out-{expect}")],
                         text=True, capture_output=True, env=env)
    print(run.stdout[-3000:] + run.stderr[-3000:])
    problems = []
    if run.returncode != 0:
        problems.append(f"grading {submission.name} in a mode-700 checkout: exit {run.returncode}, expected {expect} %")
    for word in ("Traceback", "Permission denied", "PermissionError"):
        if word in run.stdout + run.stderr:
            problems.append(f"grading {submission.name} in a mode-700 checkout printed '{word}'")
    return problems


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--work", required=True, help="scratch folder for the reports")
    args = ap.parse_args()
    work = pathlib.Path(args.work).resolve()
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    private = pathlib.Path(tempfile.mkdtemp(prefix="springlab-private-home-"))
    try:
        private.chmod(0o700)
        tree = private / "springlab"
        for rel in release.source_files():
            target = tree / rel
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(ROOT / rel, target)
        problems = grade(tree, tree / "solutions", 100, work) + grade(tree, tree / "labs", 0, work)
        if private.stat().st_mode & 0o077:
            problems.append("the private folder was opened to other users")
    finally:
        shutil.rmtree(private, ignore_errors=True)
    for problem in problems:
        print(f"PROBLEM: {problem}", file=sys.stderr)
    if not problems:
        print("grading in a mode-700 checkout: the reference scores 100 %, the skeleton 0 %")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
