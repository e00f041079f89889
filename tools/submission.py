#!/usr/bin/env python3
"""Grade student submissions against this instructor tree: one (`grade`) or a class (`grade-all`).

    tools/submission.py grade SUBMISSION [--out DIR]     a labs/ folder, a whole repository, lab folders,
                                                         or a .zip of any of these
    tools/submission.py grade SUBMISSION --lab rope      that lab only (also: the flat files of that lab)
    tools/submission.py grade-all DIR [--out DIR]        every folder and .zip directly under DIR
    tools/submission.py prairielearn [--grade-root /grade] PrairieLearn's external grader: grades
                                                         /grade/student into /grade/results/results.json

How: a cache build of the framework, the reference "oracle" and the grading tests' objects
(build-grader/, built once and reused) is configured from this tree. For each submission and
each lab, only the student's exercise files (the .cpp files of the released labs/<dir>/) are
compiled in the compiler's sandbox (bubblewrap as `nobody`: the toolchain, copies of the
framework's headers and the submission's own files, nothing else; limits on memory, CPU time
and output: tools/springlab_grader/sealed_compile.py), and linked
with the lab's given objects (framework/labs/<name>/, compiled once) and the cached objects
into a worker program per exercise file; any other file of the submission is ignored and the
report says so. Every grading test then runs twice: in the worker, inside bubblewrap, which
records what the student's functions return, and in the judge, a program without student
code that replays those records and decides (tests/support/call_trace.hpp).

Points follow the exercise: each exercise file is linked into its own grading program with
the reference's other exercise files, and only its exercises' tests run there, so a bug in one
exercise costs that exercise's points alone. A file that does not compile is graded as the
skeleton's (its exercises score 0) and the report shows the compiler's first errors. Each lab
has a time budget in CPU seconds (a multiple of the reference's own CPU time, measured once
and kept in the cache build, plus a floor) and a wall-time limit (--lab-wall-limit); once
either is spent, the remaining tests fail and say which.

A lab is found in a submission as a folder named like it (01_rope) that holds exercise files,
preferably under labs/ (so a whole repository, with or without tests/, works); flat exercise
files go to --lab, else to the lab whose skeleton has those file names. A lab with no files
is reported as not submitted.

Labs are their manifests, tests/NN_<id>/exercises.json (tools/springlab_grader/labs.py);
nothing here knows a particular lab.

Files the student did not submit are taken from the released skeleton (labs/<dir>/) and the
report says so. A file that includes the instructor's files (solutions/, hidden tests), calls
the reference solution's symbols or redefines the framework's or GoogleTest's is graded as the
skeleton's version of that file, so its exercises score 0, and the report says why.

The grader itself is the package tools/springlab_grader/; this is its command line (and
tests/grading/check_release.py and check_new_exercise.py find labs through it: discover_labs).
"""
import argparse
import json
import os
import pathlib
import sys
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from springlab_grader.errors import GradeError  # noqa: E402
from springlab_grader.lab_grader import BUDGET_FACTOR, BUDGET_FLOOR, LAB_WALL_LIMIT, grade_class, start_session  # noqa: E402
from springlab_grader.labs import ROOT, discover_labs  # noqa: E402,F401
from springlab_grader.platforms import prairielearn_failure, prairielearn_results  # noqa: E402
from springlab_grader.reports import print_lab, write_gradebook, write_submission  # noqa: E402
from springlab_grader.sandbox import TIMEOUT  # noqa: E402
from springlab_grader.submission import submissions_in  # noqa: E402


# ---- commands --------------------------------------------------------------------------------
def common_options(ap):
    ap.add_argument("--cache", default=str(ROOT / "build-grader"),
                    help="build folder of the framework and tests, reused across runs (default: build-grader/)")
    ap.add_argument("--no-build", action="store_true", help="use the cache build as it is (do not run cmake)")
    ap.add_argument("--seed", type=int, help="seed of the random test inputs (default: drawn and printed)")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="processes at once (default: cores)")
    ap.add_argument("--timeout", type=float, default=TIMEOUT, help="seconds per test")
    ap.add_argument("--memory-limit-mb", type=int, default=4096, help="address space per test; 0 = none")
    ap.add_argument("--lab", help="grade this lab only (its id: rope): one assignment per lab; flat exercise "
                                  "files are taken as this lab's")
    ap.add_argument("--budget-factor", type=float, default=BUDGET_FACTOR,
                    help=f"a lab's tests may run this many times the reference's own time, plus the floor "
                         f"(default {BUDGET_FACTOR:g}; 0 = no budget)")
    ap.add_argument("--budget-floor", type=float, default=BUDGET_FLOOR,
                    help=f"CPU seconds added to each lab's time budget (default {BUDGET_FLOOR:g})")
    ap.add_argument("--lab-wall-limit", type=float, default=LAB_WALL_LIMIT,
                    help=f"wall-time seconds one lab of one submission may take, compiles, links and tests "
                         f"(default {LAB_WALL_LIMIT:g}: a hostile lab costs at most about five minutes)")
    ap.add_argument("--no-call-check", action="store_true",
                    help="run exercise files that call the test framework, files, the environment or other "
                         "processes instead of grading them as the skeleton's (only to test the sandbox)")


def setup(args):
    return start_session(args.cache, build=not args.no_build, jobs=args.jobs, seed=args.seed,
                         timeout=args.timeout, memory_mb=args.memory_limit_mb, only=args.lab,
                         budget_factor=args.budget_factor, budget_floor=args.budget_floor,
                         call_check=not args.no_call_check, lab_wall_limit=args.lab_wall_limit)


def cmd_grade(args):
    if not pathlib.Path(args.submission).exists():
        raise GradeError(f"{args.submission}: no such file or folder")
    session = setup(args)
    seed = session.seed
    out = pathlib.Path(args.out or ROOT / "out" / "grades" / pathlib.Path(args.submission).resolve().name)
    graded = session.grade(args.submission, args.jobs)
    print(f"Grade of {args.submission} (SPRINGLAB_SEED={seed})")
    for note in graded.notes:
        print(f"  note: {note}")
    for lab in graded.labs:
        print_lab(lab, quiet=args.quiet)
        if lab.timing:
            print(f"  ({lab.seconds:.1f} s: compiling {lab.timing.get('compile', 0):.1f} s "
                  f"({lab.timing.get('compile_cpu', 0):.1f} s of CPU), "
                  f"{lab.timing.get('links', 0)} links {lab.timing.get('link', 0):.1f} s, "
                  f"tests {lab.timing.get('test', 0):.1f} s)")
    percent = 100.0 * graded.score / graded.max_score if graded.max_score else 0.0
    print(f"Total: {graded.score:g} / {graded.max_score:g} points ({percent:.1f} %) in {graded.seconds:.1f} s")
    write_submission(graded, out, seed)
    print(f"report: {out / 'report.md'}, Gradescope: {out / 'results.json'}, JUnit: {out / 'junit.xml'}")
    if args.expect_percent is not None and abs(percent - args.expect_percent) > 1e-9:
        print(f"expected {args.expect_percent:g} %, got {percent:.1f} %", file=sys.stderr)
        return 1
    return 0


def cmd_grade_all(args):
    entries = submissions_in(args.folder)
    session = setup(args)
    out = pathlib.Path(args.out or ROOT / "out" / "grades" / pathlib.Path(args.folder).resolve().name)
    out.mkdir(parents=True, exist_ok=True)
    session.prepare()  # find each lab's build once, before the workers start
    print(f"grading {len(entries)} submissions from {args.folder}, {args.jobs} at once (SPRINGLAB_SEED={session.seed})",
          file=sys.stderr)
    started = time.monotonic()
    graded_all = grade_class(session, entries, out, args.jobs)
    graded_labs = [lab for lab in session.labs if session.only is None or session.only in (lab.name, lab.dir)]
    write_gradebook(out / "gradebook.csv", graded_labs, graded_all)
    print(f"gradebook: {out / 'gradebook.csv'} ({len(entries)} students, {time.monotonic() - started:.1f} s); "
          f"reports in {out}/<student>/")
    return 0


def cmd_prairielearn(args):
    """PrairieLearn's external grader: grade <root>/student, always leave <root>/results/results.json."""
    root = pathlib.Path(args.grade_root)
    results = root / "results"
    results.mkdir(parents=True, exist_ok=True)
    try:
        session = setup(args)
        graded = session.grade(root / "student", args.jobs, name="submission")
        data = prairielearn_results(graded.labs, graded.notes, session.seed)
        code = 0
    except GradeError as error:
        data, code = prairielearn_failure(f"The grader could not grade this submission: {error}"), 2
    except Exception as error:  # noqa: BLE001 - the grader itself broke: still a results.json
        data, code = prairielearn_failure(f"The grader failed ({type(error).__name__}: {error}); ask your "
                                          f"instructor"), 2
    (results / "results.json").write_text(json.dumps(data, indent=1) + "\n")
    print(f"{data['message']}: {results / 'results.json'}")
    return code


def main():
    ap = argparse.ArgumentParser(prog="springlab", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="command", required=True)
    one = sub.add_parser("grade", help="grade one submission")
    one.add_argument("submission", help="a labs/ folder, a folder holding one, or a .zip")
    one.add_argument("--out", help="folder for report.md, results.json, junit.xml (default: out/grades/<name>/)")
    one.add_argument("--quiet", action="store_true", help="print only the totals")
    one.add_argument("--expect-percent", type=float, help="exit 1 unless the total is this percentage (for CI)")
    common_options(one)
    many = sub.add_parser("grade-all", help="grade every submission folder or .zip under a folder")
    many.add_argument("folder")
    many.add_argument("--out", help="folder for gradebook.csv and the reports (default: out/grades/<folder>/)")
    common_options(many)
    learn = sub.add_parser("prairielearn", help="PrairieLearn's external grader: grade GRADE_ROOT/student into "
                                                "GRADE_ROOT/results/results.json")
    learn.add_argument("--grade-root", default="/grade", help="PrairieLearn's folder (default /grade)")
    common_options(learn)
    prepare = sub.add_parser("prepare", help="build the grading cache only (the autograder's setup.sh)")
    common_options(prepare)
    args = ap.parse_args()
    try:
        if args.command == "prepare":
            session = setup(args)
            session.prepare()
            print(f"grading cache ready in {session.cache.path}: {', '.join(lab.dir for lab in session.labs)}")
            return 0
        if args.command == "prairielearn":
            return cmd_prairielearn(args)
        return cmd_grade(args) if args.command == "grade" else cmd_grade_all(args)
    except GradeError as error:
        print(f"springlab grade: {error}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
