#!/usr/bin/env python3
"""How long grading takes, in one run: one lab of one submission and a class of 20 (grade-all),
each cold (the object cache emptied: every exercise file compiled in its sandbox) and warm
(the same files again: every compile reused). The class is the reference with a comment naming
each student in every file, so no two students share a compile. Prints a table (seconds).

    tests/grading/measure_grading.py --cache build --work /tmp/measure [--students 20 --jobs 2]
"""
import argparse
import pathlib
import shutil
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]
LAB = "01_rope"


def timed(argv):
    start = time.monotonic()
    run = subprocess.run(argv, text=True, capture_output=True)
    if run.returncode != 0:
        raise SystemExit(f"{' '.join(argv)} failed:\n{run.stdout[-2000:]}{run.stderr[-2000:]}")
    return time.monotonic() - start


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cache", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--students", type=int, default=20)
    ap.add_argument("--jobs", type=int, default=2)
    args = ap.parse_args()
    cache, work = pathlib.Path(args.cache).resolve(), pathlib.Path(args.work).resolve()
    shutil.rmtree(work, ignore_errors=True)
    klass = work / "class"
    for k in range(args.students):
        folder = klass / f"student{k:02d}" / "labs" / LAB
        shutil.copytree(ROOT / "solutions" / LAB, folder)
        for source in folder.glob("*.cpp"):
            source.write_text(source.read_text() + f"// student{k:02d}\n")
    submission = [sys.executable, str(ROOT / "tools" / "submission.py")]
    common = ["--cache", str(cache), "--no-build", "--seed", "7", "--lab", LAB, "--jobs", str(args.jobs)]
    rows = []
    for what, argv in (("one lab (grade)", submission + ["grade", str(klass / "student00"), "--quiet", "--expect-percent",
                                                         "100", "--out", str(work / "one")] + common),
                       (f"class of {args.students} (grade-all)", submission + ["grade-all", str(klass), "--out",
                                                                                str(work / "grades")] + common)):
        shutil.rmtree(cache / "grader-objects", ignore_errors=True)
        cold = timed(argv)
        warm = timed(argv)
        rows.append((what, cold, warm))
    print(f"| what | cold (s) | warm (s) |\n|---|---|---|")
    for what, cold, warm in rows:
        print(f"| {what}, {args.jobs} jobs | {cold:.1f} | {warm:.1f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
