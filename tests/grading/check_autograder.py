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
    # Hostile submissions through the bundle score exactly their honest control (the
    # reference with the attacked exercise not done): the verdict is the judge's there too.
    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
    import sabotage  # noqa: PLC0415
    made = work / "hostile"
    sabotage.make(made, [], args.cache)
    outcomes = {}
    for student in ("_control", "code_before_main", "reads_own_memory", "overrides_gtest"):
        shutil.rmtree(root / "submission", ignore_errors=True)
        shutil.copytree(made / student, root / "submission")
        code, results = run_autograder(root, f"--cache {args.cache} --no-build --seed 7 --quiet --lab "
                                             f"{sabotage.TARGET_LAB}")
        if code != 0 or results is None:
            problems.append(f"grading {student} through run_autograder: exit {code}, results {str(results)[:300]}")
            continue
        outcomes[student] = {t["name"]: t["status"] for t in results["tests"]}
    for student, got in outcomes.items():
        if student != "_control" and got != outcomes.get("_control"):
            changed = sorted(n for n in got if got[n] != outcomes.get("_control", {}).get(n))
            problems.append(f"{student} through the bundle differs from its control in {changed[:4]}")
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
