#!/usr/bin/env python3
"""Write the tree a student receives: the framework (with each lab's given code in
framework/labs/<name>/, compiled once), labs/ generated afresh from solutions/ (per lab only
the exercise .cpp stubs, the copy of exercises.hpp and README.md), public tests, handouts,
scenes, the student README and the entry script. Never solutions/, hidden tests, the grader's
own tests and tools, the course author's notes, or the instructor's README: the release's
README.md is tools/templates/README.student.md, written for students.

    tools/release.py OUT            OUT must not exist, or be an empty folder
    tools/release.py OUT --force    replace OUT

What stays out is listed below (INSTRUCTOR_ONLY); tests/grading/check_release.py builds the
result and checks that nothing of the reference leaks into it.
"""
import argparse
import fnmatch
import pathlib
import shutil
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tools"))
import make_skeleton  # noqa: E402

# Paths (relative, glob patterns) that only the instructor's tree has.
INSTRUCTOR_ONLY = [
    "solutions", "solutions/*",        # the reference
    "tests/*/hidden", "tests/*/hidden/*",  # hidden grading tests
    "tests/grading", "tests/grading/*",    # the grader's own tests (sabotage, release, ...)
    "tools/submission.py", "tools/release.py", "tools/autograder.py", "tools/new_exercise.py",
    "tools/author_check.py",           # the course author's invariants (needs solutions/)
    "tools/make_skeleton.py",
    "tools/seed_sweep.py",             # sweeps the reference's grading program over seeds
    # The grader's instructor side: building, cheat checks, submissions, the bundle. A student's
    # `check` needs only the manifest, sandbox, launch (judged_run: `check` starts each test as
    # `grade` starts a worker), test runner, results and reports modules, and the labs module
    # (with its errors), which the `springlab` script reads the labs through (tools/lab_table.py).
    "tools/springlab_grader/build_cache.py", "tools/springlab_grader/integrity.py",
    "tools/springlab_grader/lab_grader.py", "tools/springlab_grader/submission.py",
    "tools/springlab_grader/gradescope.py", "tools/springlab_grader/sealed_compile.py",
    "tools/springlab_grader/README.md",  # how the instructor's grader works, for instructors
    # The judge and worker of graded tests (the call trace between them) and their generator.
    "tools/make_call_layer.py", "tests/support/call_trace*", "tests/support/judge_main.cpp",
    "tests/support/worker_main.cpp",
    "handouts/authoring.md",
    "README.md",                       # the instructor's README: the release gets STUDENT_README
    "tools/templates", "tools/templates/*",
    ".ci", ".ci/*",
    "labs", "labs/*",                  # written afresh from solutions/ instead, so a file
                                       # left in labs/ by hand never ships
]
# The release's README.md: what a student reads first (labs, commands, points, Eigen, help).
STUDENT_README = ROOT / "tools" / "templates" / "README.student.md"
CLASSROOM_WORKFLOW = ROOT / "tools" / "templates" / "classroom.yml"
NEVER_DIRS = ["build*", "out", ".git", "__pycache__", ".cache", ".vscode", ".idea"]
NEVER_FILES = ["*.pyc"]


class ReleaseError(Exception):
    pass


def source_files():
    """The instructor tree's files: git's list when it is a checkout, else a walk."""
    try:
        listed = subprocess.run(["git", "-C", str(ROOT), "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
                                capture_output=True, check=True).stdout.decode().split("\0")
        files = [pathlib.Path(p) for p in listed if p and (ROOT / p).is_file()]
    except (OSError, subprocess.CalledProcessError):
        files = [p.relative_to(ROOT) for p in ROOT.rglob("*") if p.is_file()]
    return sorted(f for f in files
                  if not any(fnmatch.fnmatch(part, pat) for part in f.parts[:-1] for pat in NEVER_DIRS)
                  and not any(fnmatch.fnmatch(f.name, pat) for pat in NEVER_FILES))


def excluded(rel):
    text = rel.as_posix()
    return any(fnmatch.fnmatch(text, pat) for pat in INSTRUCTOR_ONLY)


def release(out, force=False):
    # A slip of the course author never reaches students: a `TODO(author)` placeholder, a
    # handout that disagrees with its manifest, a stale labs/, two fixtures for one suite.
    import author_check
    slips = author_check.problems()
    if slips:
        raise ReleaseError("this tree is not ready for students (tools/author_check.py):\n  " + "\n  ".join(slips))
    out = pathlib.Path(out).resolve()
    inside = out.relative_to(ROOT).parts if out.is_relative_to(ROOT) else None
    if inside is not None and (not inside or not (inside[0] == "out" or inside[0].startswith("build"))):
        raise ReleaseError(f"{out}: write the release outside the instructor tree (or under out/ or build*/)")
    if out.exists():
        if not out.is_dir():
            raise ReleaseError(f"{out}: exists and is not a folder")
        if any(out.iterdir()):
            if not force:
                raise ReleaseError(f"{out}: not empty (use --force to replace it)")
            shutil.rmtree(out)
    written = 0
    for rel in source_files():
        if excluded(rel):
            continue
        target = out / rel
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(ROOT / rel, target)
        written += 1
    if not STUDENT_README.is_file():
        raise ReleaseError(f"{STUDENT_README.relative_to(ROOT)}: the student README is missing")
    shutil.copy2(STUDENT_README, out / "README.md")
    written += 1
    # GitHub Classroom's autograding of the public tests (tests/grading/check_platforms.py).
    (out / ".github" / "workflows").mkdir(parents=True, exist_ok=True)
    shutil.copy2(CLASSROOM_WORKFLOW, out / ".github" / "workflows" / "classroom.yml")
    written += 1
    # labs/: generated now from solutions/, so the release can never hold a stale skeleton.
    labs = sorted(p.name for p in (ROOT / "solutions").iterdir() if p.is_dir())
    try:
        for lab in labs:
            for path, text in make_skeleton.generate(lab).items():
                target = out / path.relative_to(ROOT)
                target.parent.mkdir(parents=True, exist_ok=True)
                target.write_text(text)
                written += 1
    except make_skeleton.SkeletonError as error:
        raise ReleaseError(f"generating labs/: {error}") from None
    # Each lab's given code ships in the framework, or the release cannot build.
    for lab in labs:
        given = out / "framework" / "labs" / make_skeleton.lab_name(lab)
        if not (given / "src").is_dir() or not any(given.rglob("*.hpp")):
            raise ReleaseError(f"{given.relative_to(out)}: lab {lab}'s given code is missing from the release")
    return out, written, labs


def main():
    ap = argparse.ArgumentParser(prog="springlab release", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", help="folder to write the student tree into")
    ap.add_argument("--force", action="store_true", help="replace OUT if it holds files")
    args = ap.parse_args()
    if not (ROOT / "solutions").is_dir():
        print("springlab release: this tree has no solutions/: releases are made from the instructor tree",
              file=sys.stderr)
        return 2
    try:
        out, written, labs = release(args.out, args.force)
    except ReleaseError as error:
        print(f"springlab release: {error}", file=sys.stderr)
        return 2
    print(f"student release written to {out}: {written} files, labs {', '.join(labs)} (exercise stubs in labs/, "
          f"given code in framework/labs/); no solutions/, no hidden tests")
    return 0


if __name__ == "__main__":
    sys.exit(main())
