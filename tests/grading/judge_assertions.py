#!/usr/bin/env python3
"""A student's function that returns a container of the wrong size fails its tests with a
clear message, not undefined behaviour in the grader's judge: the judge checks the indices of
what it replays (call_trace.hpp checkReplayedIndices) before any code uses them.

The submission is Lab 1's reference (flat files, --lab rope) with buildRope (exercise 1.7)
returning its positions cleared: size 0, but the memory still holds the right values. In
the worker, the student's own process, the test's `pos[0]` reads that memory and the test
passes; the judge replays an empty vector of positions beside springs that join masses 0
and 1. So:
  - BuildRope.FirstMassIsFixedAtTheConnectionPoint fails, and its message says a spring's
    mass lies past the masses the call gave back;
  - no exercise but 1.7 loses a point.

    tests/grading/judge_assertions.py --cache build --work build/tests/grading/judge_assertions
"""
import argparse
import json
import pathlib
import shutil
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
TEST = "BuildRope.FirstMassIsFixedAtTheConnectionPoint"
EXERCISE = "1.7"
RETURN = "  return rope;\n  // END EXERCISE 1.7"
WRONG_SIZE = ("  // The positions' memory stays (capacity n), their size is 0.\n"
              "  rope.pos.clear();\n" + RETURN)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cache", required=True, help="a build of this tree with Lab 1's grading programs built")
    ap.add_argument("--work", required=True, help="scratch folder for the submission and its report")
    args = ap.parse_args()
    work = pathlib.Path(args.work).resolve()
    shutil.rmtree(work, ignore_errors=True)
    submission = work / "wrong_size"
    shutil.copytree(ROOT / "solutions" / "01_rope", submission)
    source = submission / "build_rope.cpp"
    text = source.read_text()
    if RETURN not in text:
        raise SystemExit(f"judge_assertions.py: {source.name} no longer ends exercise 1.7 with `return rope;`")
    source.write_text(text.replace(RETURN, WRONG_SIZE))

    run = subprocess.run([sys.executable, str(ROOT / "tools" / "submission.py"), "grade", str(submission), "--lab", "rope",
                          "--out", str(work / "out"), "--cache", args.cache, "--no-build", "--seed", "2024", "--quiet",
                          "--jobs", "2"], text=True, capture_output=True)
    print(run.stdout + run.stderr)
    if run.returncode != 0:
        raise SystemExit(f"judge_assertions.py: grade failed with exit code {run.returncode}")
    results = json.loads((work / "out" / "results.json").read_text())
    problems = []
    for test in results["tests"]:
        name, exercise = test["name"].split(" ", 1)[1], test["tags"][1].split(" ", 1)[1]
        passed = test["status"] == "passed"
        if exercise != EXERCISE and not passed:
            problems.append(f"{name} (exercise {exercise}) failed: only exercise {EXERCISE} may lose points")
        if name == TEST:
            message = test.get("output", "")
            print(f"{TEST}: {message}")
            if "cannot use what your code gave back" not in message or "but the call has 0 masses" not in message:
                problems.append(f"{TEST}: the message does not say the springs' masses lie past the returned "
                                f"positions: {message!r}")
    if not any(t["name"].split(" ", 1)[1] == TEST for t in results["tests"]):
        problems.append(f"{TEST} is not in the results")
    for line in problems:
        print(line, file=sys.stderr)
    if problems:
        return 1
    print(f"a wrong-sized return fails exercise {EXERCISE} only, with the index past the end named")
    return 0


if __name__ == "__main__":
    sys.exit(main())
