#!/usr/bin/env python3
"""Run one lab's grading tests (`./springlab check`), each in its own sandboxed process, and score them.

Points come from the lab's manifest (tests/<lab>/exercises.json), the one place they are
declared. Each test runs alone in a fresh process, launched exactly as `grade` launches a
worker (tools/springlab_grader/judged_run.py launch_worker): the same command line, the same
environment, the test's name on standard input, in bubblewrap where it works here (else as a
plain process in a private folder), as the worker user when the grader is root, with limits
on time, CPU, memory, stack, file size and open files. A test scores only if the grading
main (tests/support/grading_main.cpp) reports it passed on the channel descriptor, after the
test returned, and the process exits 0: a crash, a hang, exit(0) inside an exercise or printed
fake GoogleTest output score 0. This is the student's check, not a verdict: the program holds
their own code (`grade` decides with a judge that runs none of it).

    tools/grade.py --binary build/tests/rope_grading_student --manifest tests/01_rope/exercises.json
    tools/grade.py ... --expect-percent 100        exit 1 unless the score is exactly 100 %
    tools/grade.py ... --out DIR                   also write report.md, results.json, junit.xml
    tools/grade.py ... --after-failed-build LOG    the binary's build failed (its log: LOG): grade
                                                   beside the exercise files that do not compile
    tools/grade.py ... --verbose                   the compiler's and GoogleTest's full text too
    tools/grade.py --manifest M --check-handout H  check every points statement of the handout
                                                   (tools/handout_check.py)

The grader itself is the package tools/springlab_grader/; this is its command line (and
tools/new_exercise.py reads manifests through it: load_manifest, ManifestError).
"""
import argparse
import os
import pathlib
import re
import shutil
import sys
import tempfile
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from springlab_grader.call_check import REPLACED  # noqa: E402
from springlab_grader.compile_errors import NOT_COMPILING, NOT_DEFINED, files_with_errors, first_errors, not_compiling_note, not_defined_note, summary  # noqa: E402
from springlab_grader.errors import GradeError  # noqa: E402
from springlab_grader.gtest_runner import check_binary_against_manifest, draw_seed, grade_binary  # noqa: E402
from springlab_grader.judged_run import bubblewrap, go_without_bubblewrap, starts_in_bubblewrap  # noqa: E402
from springlab_grader.manifest import ManifestError, load_manifest  # noqa: E402
from springlab_grader.reports import print_lab, write_outputs  # noqa: E402
from springlab_grader.platforms import classroom_error, classroom_output_line, classroom_result  # noqa: E402
from springlab_grader.results import LabResult, TestResult  # noqa: E402
from springlab_grader.sandbox import TIMEOUT, Sandbox  # noqa: E402
from springlab_grader.student_build import rebuild  # noqa: E402
from springlab_grader.student_check import exercises_by_file, forbidden_call_notes  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--binary", help="grading test executable")
    ap.add_argument("--manifest", required=True, help="tests/<lab>/exercises.json")
    ap.add_argument("--timeout", type=float, default=TIMEOUT, help=f"seconds per test (default {TIMEOUT:g})")
    ap.add_argument("--memory-limit-mb", type=int, default=4096, help="address space per test; 0 = none")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="tests run at once (default: cores)")
    ap.add_argument("--seed", type=int, help="seed for random inputs (default: drawn and printed)")
    ap.add_argument("--expect-percent", type=float, help="exit 1 unless the score is this percentage")
    ap.add_argument("--out", help="folder for report.md, results.json and junit.xml")
    ap.add_argument("--check-handout", help="check the handout's headings against the manifest and exit")
    ap.add_argument("--quiet", action="store_true", help="print only the summary")
    ap.add_argument("--after-failed-build", metavar="LOG",
                    help="the build of --binary failed (LOG: its output): grade as `grade` does beside exercise "
                         "files that do not compile, each graded as the skeleton's (student_build.py)")
    ap.add_argument("--verbose", action="store_true",
                    help="under each summary, the compiler's full text and GoogleTest's own failure text")
    ap.add_argument("--again", default="tools/grade.py ...",
                    help="the command that runs this check again (said with --verbose where full texts are left out)")
    ap.add_argument("--classroom", metavar="FILE",
                    help="also append this lab's public result for GitHub Classroom's reporter to FILE "
                         "($GITHUB_OUTPUT): result=<base64 JSON>; a program that is missing (the lab does not "
                         "build) gives an error result worth the lab's public points")
    ap.add_argument("--seccomp", help="the program that writes the workers' seccomp filter (default: "
                                      "springlab_worker_seccomp beside the binary, if built)")
    args = ap.parse_args()

    try:
        manifest = load_manifest(args.manifest)
    except ManifestError as error:
        print(error, file=sys.stderr)
        return 2
    if args.check_handout:
        # Headings, the grading table and its total, "worth N points", "in N exercises": each
        # disagreement as FILE:LINE, what the handout says and what the manifest says.
        from handout_check import check_handout
        problems = check_handout(manifest, args.check_handout, args.manifest)
        for p in problems:
            print(p, file=sys.stderr)
        print("handout agrees with the manifest" if not problems else f"{len(problems)} problem(s)")
        return 1 if problems else 0
    if not args.binary:
        ap.error("--binary is required")
    binary = str(pathlib.Path(args.binary).resolve())  # tests run in their own folders
    # Where the full texts left out of the report are: the compiler's also in the build's log.
    args.full_text = f"{args.again} --verbose"
    args.compiler_text = args.full_text + (f", or {rel(args.after_failed_build)}" if args.after_failed_build else "")
    tree = pathlib.Path(args.manifest).resolve().parents[2]
    # The build failed: each exercise file that does not compile (or does not define its
    # functions as declared) is graded as the skeleton's. The call check reads the objects of
    # the build's program (`built`).
    built, broken, undefined = binary, {}, {}
    if args.after_failed_build:
        rebuilt = after_failed_build(binary, manifest, tree, args)
        if rebuilt is None:
            return 2
        binary, broken, undefined = str(rebuilt.binary), rebuilt.broken, rebuilt.undefined
    # The workers' seccomp filter, as `grade` gives it (built beside the grading programs).
    seccomp = args.seccomp or str(pathlib.Path(binary).with_name("springlab_worker_seccomp"))
    if not os.access(binary, os.X_OK):
        print(f"{binary}: no such test program (was the lab built?)", file=sys.stderr)
        if args.classroom:
            with open(args.classroom, "a") as out:
                out.write(classroom_output_line(classroom_error(
                    manifest, "the lab does not build: see the build step's compiler errors")))
        return 2
    sandbox = Sandbox(timeout=args.timeout, memory_mb=args.memory_limit_mb)
    shown = binary
    reachable = tempfile.TemporaryDirectory(prefix="springlab-binary-")
    if sandbox.identity():
        # The sandbox user may not reach the build folder (a checkout under /root): a copy.
        os.chmod(reachable.name, 0o711)
        copy = pathlib.Path(reachable.name) / pathlib.Path(binary).name
        shutil.copy2(binary, copy)
        os.chmod(copy, 0o755)
        binary = str(copy)
    try:
        present = check_binary_against_manifest(binary, manifest, args.manifest, sandbox,
                                                student_build=not (pathlib.Path(args.manifest).resolve().parents[2] / "solutions").exists())
    except ManifestError as error:
        print(error, file=sys.stderr)
        return 2

    # A student's build that needs files outside /usr (its compiler's libraries) cannot start in
    # bubblewrap: its tests then run as plain processes, as on a machine without bubblewrap.
    if bubblewrap() and not starts_in_bubblewrap(binary, sandbox, seccomp):
        print(f"note: {shown} does not start inside bubblewrap (libraries outside /usr?): its tests run "
              f"as plain processes", file=sys.stderr)
        go_without_bubblewrap()
    seed = draw_seed(args.seed)
    print(f"{manifest['title']}: grading {shown} (SPRINGLAB_SEED={seed})")
    started = time.monotonic()
    # A file that does not compile or define its functions: its exercises' tests are not run,
    # and fail with grade's words.
    exercises = exercises_by_file(tree, manifest["folder"])
    stubbed = {ex_id: NOT_COMPILING.format(name=name) for name in broken for ex_id in exercises.get(name, [])}
    stubbed.update({ex_id: NOT_DEFINED.format(name=name) for name in undefined for ex_id in exercises.get(name, [])})
    run = {t["name"] for ex in manifest["exercises"] if ex["id"] not in stubbed for t in ex["tests"]}
    results = grade_binary(binary, manifest, seed, sandbox, args.jobs, present, seccomp=seccomp, only=run)
    results += [TestResult(ex, t, False, stubbed[ex["id"]], 0.0)
                for ex in manifest["exercises"] if ex["id"] in stubbed for t in ex["tests"]
                if t["name"] in present or t["visibility"] == "visible"]
    order = {t["name"]: i for i, t in enumerate(t for ex in manifest["exercises"] for t in ex["tests"])}
    results.sort(key=lambda r: order[r.test["name"]])
    notes = [not_compiling_note(name, exercises.get(name, []), compile_summary(broken[name], name, manifest, tree),
                                f"The compiler's full text:\n{text}" if args.verbose else
                                f"The compiler's full text: {args.compiler_text}")
             for name, text in sorted(broken.items())]
    notes += [not_defined_note(name, functions) for name, functions in sorted(undefined.items())]
    # The call check `grade` makes: a file that calls what exercise code may not scores as the
    # skeleton's there, so here too, with the same sentence.
    flagged = forbidden_call_notes(built, tree, manifest["lab"], skip=set(broken) | set(undefined))
    lost = {ex_id: name for name, (_, ids) in flagged.items() for ex_id in ids}
    for r in results:
        if r.exercise["id"] in lost:
            r.passed, r.message = False, REPLACED.format(name=lost[r.exercise["id"]])
    lab = LabResult(manifest, results, notes + [note for note, _ in flagged.values()], seed=seed,
                    seconds=time.monotonic() - started)
    # Failures as sentences (what was expected, what came, what to check), GoogleTest's own
    # text with --verbose.
    print_lab(lab, quiet=args.quiet, sentences=True, raw=args.verbose)
    if not args.quiet and not args.verbose and any(not r.passed and r.message for r in lab.results):
        print(f"(GoogleTest's own text of each failure: {args.full_text})")
    if args.out:
        write_outputs(args.out, [lab], manifest["title"], lab.seconds, seed)
    if args.classroom:
        with open(args.classroom, "a") as out:
            out.write(classroom_output_line(classroom_result(lab)))
    percent = 100.0 * lab.score / lab.max_score if lab.max_score else 0.0
    if args.expect_percent is not None and abs(percent - args.expect_percent) > 1e-9:
        print(f"expected {args.expect_percent:g} %, got {percent:.1f} %", file=sys.stderr)
        return 1
    return 0


def rel(path):
    """A path as the student typed it: relative to the current folder when inside it."""
    path = pathlib.Path(path).resolve()
    return str(path.relative_to(pathlib.Path.cwd())) if path.is_relative_to(pathlib.Path.cwd()) else str(path)


def compile_summary(text, name, manifest, tree):
    """The first error of exercise file `name`, placed in it, and its hint (compile_errors.py)."""
    path = f"labs/{manifest['folder']}/{name}"
    return summary(text, lambda where: where == path or where.endswith("/" + path), root=tree)


def after_failed_build(binary, manifest, tree, args):
    """The lab's grading program rebuilt beside the exercise files that do not compile (a
    student_build.Rebuilt), or None after saying why there is none: the build failed elsewhere."""
    log = pathlib.Path(args.after_failed_build)
    text = log.read_text(errors="replace") if log.is_file() else ""
    # The build's paths relative to the tree (ccache's base folder makes them relative to the
    # build folder: ../labs/...), as the student sees the tree.
    build = pathlib.Path(binary).parent.parent
    text = text.replace(str(tree) + "/", "")
    text = re.sub(rf"(?m)(^|\s){re.escape(os.path.relpath(tree, build))}/", r"\1", text)
    try:
        rebuilt = rebuild(build, manifest, tree, args.jobs)
    except GradeError as error:
        print(f"springlab: {error}", file=sys.stderr)
        rebuilt = None
    if rebuilt is not None and rebuilt.binary is not None:
        for files, what in ((rebuilt.broken, "not compile"), (rebuilt.undefined, "not define its functions as "
                                                                                     "exercises.hpp declares them")):
            if files:
                names = ", ".join(f"labs/{manifest['folder']}/{n}" for n in sorted(files))
                print(f"springlab: {names} {'does' if len(files) == 1 else 'do'} {what}: check grades the lab's other "
                      f"files beside the skeleton's (the note below says why)", file=sys.stderr)
        # An error outside the exercise files (a framework file edited): its last build is used,
        # as the grader uses the framework as shipped; said, not hidden.
        exercise_paths = {f"labs/{manifest['folder']}/{n}" for n in rebuilt.broken}
        for path, line in files_with_errors(text):
            if not any(path.endswith(p) for p in exercise_paths):
                print(f"springlab: the build also failed outside the lab's exercise files: {line}\n"
                      f"springlab: {path} is graded as last built (the grader uses the framework as shipped); "
                      f"the compiler's full text: {args.compiler_text}", file=sys.stderr)
        return rebuilt
    # Not an exercise file of this lab: the build's first error, then where its full text is.
    first = summary(text, lambda where: not where.startswith("/usr/"), root=tree) or first_errors(text, 8).splitlines()
    for line in first:
        print(f"  {line}", file=sys.stderr)
    if args.verbose:
        print(text, file=sys.stderr)
    print(f"springlab: build failed; the compiler's full text: {args.compiler_text}", file=sys.stderr)
    return None


if __name__ == "__main__":
    sys.exit(main())
