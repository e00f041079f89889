#!/usr/bin/env python3
"""The Gradescope bundle: setup.sh and run_autograder at the zip's root, executable; the tree
under springlab/; run_autograder grades a submission into results/results.json, and still
writes a results.json (score 0, with the reason) when the grader itself cannot run.

    tests/grading/check_autograder.py --cache build --work build/tests/grading/autograder
"""
import argparse
import json
import os
import pathlib
import shutil
import stat
import subprocess
import sys
import zipfile

ROOT = pathlib.Path(__file__).resolve().parents[2]


def run_autograder(root, args):
    env = dict(os.environ, SPRINGLAB_AUTOGRADER_ROOT=str(root), SPRINGLAB_AUTOGRADER_ARGS=args)
    run = subprocess.run(["bash", str(root / "source" / "run_autograder")], env=env, capture_output=True, text=True)
    print(run.stdout[-3000:] + run.stderr[-3000:])
    path = root / "results" / "results.json"
    return run.returncode, json.loads(path.read_text()) if path.exists() else None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cache", required=True)
    ap.add_argument("--work", required=True)
    args = ap.parse_args()
    work = pathlib.Path(args.work).resolve()
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    bundle = work / "autograder.zip"
    subprocess.run([sys.executable, str(ROOT / "tools" / "autograder.py"), str(bundle)], check=True)
    problems = []
    with zipfile.ZipFile(bundle) as zf:
        names = zf.namelist()
        for script in ("setup.sh", "run_autograder"):
            if script not in names:
                problems.append(f"{script} is not at the zip's root")
            elif not (zf.getinfo(script).external_attr >> 16) & stat.S_IXUSR:
                problems.append(f"{script} is not executable")
        for needed in ("springlab/springlab", "springlab/tools/submission.py", "springlab/solutions/"):
            if not any(n.startswith(needed) for n in names):
                problems.append(f"the bundle lacks {needed}")
        if any(n.split("/")[1].startswith(("build", "out")) for n in names if n.count("/") > 1):
            problems.append("the bundle holds build output")
        root = work / "autograder"
        zf.extractall(root / "source")
    for script in ("setup.sh", "run_autograder"):
        if subprocess.run(["bash", "-n", str(root / "source" / script)]).returncode != 0:
            problems.append(f"{script} has a shell syntax error")

    # A submission as Gradescope places it: the student's files in /autograder/submission.
    shutil.copytree(ROOT / "solutions", root / "submission" / "labs")
    code, results = run_autograder(root, f"--cache {args.cache} --no-build --seed 7 --quiet")
    if code != 0 or results is None or results["score"] != results["max_score"] or not results["tests"]:
        problems.append(f"grading the reference through run_autograder: exit {code}, results {str(results)[:300]}")
    # The grader cannot run at all: still a results.json, with a zero and the reason.
    code, results = run_autograder(root, "--cache /nonexistent-springlab-cache --no-build")
    if code != 0 or results is None or results["score"] != 0 or "could not grade" not in results["output"]:
        problems.append(f"a failing grader must still leave results.json with score 0: exit {code}, {results}")
    for problem in problems:
        print(f"PROBLEM: {problem}", file=sys.stderr)
    if not problems:
        print("autograder bundle: scripts at the root, grades a submission, reports a grader failure")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
