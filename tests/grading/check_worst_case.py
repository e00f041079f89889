#!/usr/bin/env python3
"""The worst a submission can cost a grading slot: one lab takes at most its wall-time limit
(--lab-wall-limit, default 270 s) plus one test's time limit, whatever its code does. Here
every exercise file of Lab 1 sleeps just under the per-test time limit when its program starts
(a static initialiser: every test process of every file waits, spending no CPU time), which
without the limit would hold the slot for tests x limit (about 40 x 5 s). Graded with a 20 s
wall-time limit (after a first run that fills the object cache, itself bounded by a 90 s
limit), the lab must end within the limit plus one test's time and the links, and the report
must name the limit for the tests it stopped or never started.

    tests/grading/check_worst_case.py --cache build --work build/tests/grading/worst_case
"""
import argparse
import json
import pathlib
import shutil
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]
LAB = "01_rope"
TIMEOUT = 5.0
SLEEPER = """#include <chrono>
#include <thread>
namespace {
// Every process of this file's tests waits just under the per-test time limit, computing nothing.
const bool kSlept = [] {
  std::this_thread::sleep_for(std::chrono::milliseconds(@MS@));
  return true;
}();
}  // namespace
"""
SLACK = 20.0  # seconds for what comes after the limit: the links of what compiled, the reports


def grade(submission, out, cache, limit):
    start = time.monotonic()
    run = subprocess.run([sys.executable, str(ROOT / "tools" / "submission.py"), "grade", str(submission), "--lab", LAB,
                          "--cache", str(cache), "--no-build", "--seed", "7", "--jobs", "1", "--timeout", str(TIMEOUT),
                          "--lab-wall-limit", str(limit), "--quiet", "--out", str(out)], text=True, capture_output=True)
    print(run.stdout[-1500:] + run.stderr[-1500:])
    return run.returncode, time.monotonic() - start


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cache", required=True)
    ap.add_argument("--work", required=True)
    args = ap.parse_args()
    work = pathlib.Path(args.work).resolve()
    shutil.rmtree(work, ignore_errors=True)
    submission = work / "sleeper" / "labs" / LAB
    shutil.copytree(ROOT / "solutions" / LAB, submission)
    for source in submission.glob("*.cpp"):
        source.write_text(SLEEPER.replace("@MS@", str(int(TIMEOUT * 1000) - 300)) + source.read_text())
    problems = []
    for limit in (90.0, 20.0):
        code, seconds = grade(submission.parents[1], work / f"out-{limit:g}", pathlib.Path(args.cache).resolve(), limit)
        print(f"lab wall-time limit {limit:g} s: graded in {seconds:.1f} s")
        if code != 0:
            problems.append(f"grading with a {limit:g} s limit failed (exit {code})")
        if seconds > limit + TIMEOUT + SLACK:
            problems.append(f"with a {limit:g} s limit the lab took {seconds:.1f} s, more than the limit, one test and "
                            f"{SLACK:g} s")
    results = json.loads((work / "out-20" / "results.json").read_text())
    stopped = [t for t in results["tests"] if "wall-time limit" in t["output"]]
    if not stopped:
        problems.append("no test of the sleeping lab names the wall-time limit")
    if any(t["status"] == "passed" for t in stopped):
        problems.append("a test stopped by the wall-time limit scored")
    for problem in problems:
        print(f"PROBLEM: {problem}", file=sys.stderr)
    if not problems:
        print(f"a lab that sleeps in every test ends within its wall-time limit ({len(stopped)} tests stopped or not "
              f"run, each naming the limit)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
