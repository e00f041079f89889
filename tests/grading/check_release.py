#!/usr/bin/env python3
"""The student release: written by tools/release.py, it holds nothing of the reference, has
the lab layout (each labs/<dir>/ holds only the exercise .cpp stubs, the generated copy of
exercises.hpp and README.md; each lab's given code is in framework/labs/<name>/), builds
cleanly (warnings are errors) on its own, and its public tests all fail on the skeleton while
the framework's tests pass. Its README.md is the student README (tools/templates/README.student.md),
not the instructor's, and names every lab's handout and lab folder.

    tests/grading/check_release.py --work build/tests/grading/release     (run by ctest)
"""
import argparse
import os
import pathlib
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import submission  # noqa: E402


def leaks(tree):
    """Everything of the instructor's that must not be in the release."""
    problems = []
    files = [p for p in tree.rglob("*") if p.is_file() and "build" not in p.relative_to(tree).parts]
    for p in files:
        rel = p.relative_to(tree).as_posix()
        if rel.startswith("solutions/") or "/hidden/" in rel or rel.startswith("tests/grading/"):
            problems.append(f"{rel}: instructor-only file in the release")
    # The reference's exercise bodies: no return line of one, and no two consecutive lines of
    # one, may appear in any released file (single short lines, like `for (...)`, may).
    singles, pairs = set(), set()
    for path in (ROOT / "solutions").rglob("*"):
        if not path.is_file():
            continue
        inside, previous = False, None
        for line in path.read_text().splitlines():
            line = line.strip()
            if re.match(r"^// BEGIN EXERCISE", line):
                inside, previous = True, None
            elif re.match(r"^// END EXERCISE", line):
                inside = False
            elif inside and line and not line.startswith("//") and line != "}":
                if line.startswith("return") and len(line) >= 25:
                    singles.add(line)
                if previous:
                    pairs.add((previous, line))
                previous = line
    for p in files:
        text = p.read_text(errors="replace")
        if "BEGIN EXERCISE" in text and p.suffix in (".cpp", ".hpp"):
            problems.append(f"{p.relative_to(tree)}: holds an exercise marker")
        lines = [line.strip() for line in text.splitlines() if line.strip() and not line.strip().startswith("//")]
        for a, b in zip(lines, lines[1:] + [""]):
            if a in singles or (a, b) in pairs:
                problems.append(f"{p.relative_to(tree)}: holds the reference's answer: {a}")
    return problems


def readme(tree, labs):
    """The released README is the one written for students."""
    problems = []
    released = tree / "README.md"
    student = ROOT / "tools" / "templates" / "README.student.md"
    if not released.is_file():
        return ["README.md: missing from the release"]
    text = released.read_text()
    if text != student.read_text():
        problems.append("README.md: not the student README (tools/templates/README.student.md)")
    if text == (ROOT / "README.md").read_text():
        problems.append("README.md: the instructor's README is in the release")
    for word in ("solutions/", "grade-all", "autograder", "new-exercise", ".ci/"):
        if word in text:
            problems.append(f"README.md: mentions the instructor's {word}")
    for lab in labs:
        for name in (f"handouts/{lab.dir}.md", f"labs/{lab.dir}/"):
            if name not in text:
                problems.append(f"README.md: does not lead to {name}")
    if (tree / "tools" / "templates").exists():
        problems.append("tools/templates/: shipped (its README is the release's README.md)")
    return problems


def layout(tree, labs):
    """Each released lab folder holds only what the student writes; the given code is the
    framework's."""
    problems = []
    folders = {lab.dir for lab in labs}
    for p in sorted((tree / "labs").rglob("*")) if (tree / "labs").is_dir() else []:
        rel = p.relative_to(tree / "labs")
        if p.is_file() and (len(rel.parts) != 2 or rel.parts[0] not in folders):
            problems.append(f"labs/{rel.as_posix()}: not in a lab's folder")
    for lab in labs:
        folder = tree / "labs" / lab.dir
        exercise_files = {p.name for p in (ROOT / "solutions" / lab.dir).glob("*.cpp")}
        wanted = exercise_files | {"exercises.hpp", "README.md"}
        present = {p.name for p in folder.iterdir()} if folder.is_dir() else set()
        for name in sorted(present - wanted):
            problems.append(f"labs/{lab.dir}/{name}: not an exercise file, exercises.hpp or README.md "
                            f"(given code belongs in framework/labs/{lab.name}/)")
        for name in sorted(wanted - present):
            problems.append(f"labs/{lab.dir}/{name}: missing from the release")
        for name in sorted(exercise_files & present):
            text = (folder / name).read_text()
            if "TODO exercise" not in text or "springlab::NotImplemented(" not in text:
                problems.append(f"labs/{lab.dir}/{name}: not an exercise stub (no TODO exercise and NotImplemented)")
        given = tree / "framework" / "labs" / lab.name
        headers = [given / "include" / "springlab" / lab.name / f"{h}.hpp" for h in ("exercises", lab.name)]
        for header in headers:
            if not header.is_file():
                problems.append(f"{header.relative_to(tree)}: the lab's given header is missing from the release")
        if not list((given / "src").glob("*.cpp")):
            problems.append(f"framework/labs/{lab.name}/src/: the lab's given code is missing from the release")
        copy = folder / "exercises.hpp"
        if copy.is_file() and headers[0].is_file():
            text = copy.read_text()
            if not text.startswith("// Generated by tools/make_skeleton.py") or not text.endswith(headers[0].read_text()):
                problems.append(f"labs/{lab.dir}/exercises.hpp: not the generated copy of "
                                f"{headers[0].relative_to(tree)}")
    return problems


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--work", required=True)
    ap.add_argument("--jobs", type=int, default=2)
    args = ap.parse_args()
    tree = pathlib.Path(args.work).resolve()
    run = subprocess.run([sys.executable, str(ROOT / "tools" / "release.py"), str(tree), "--force"],
                         capture_output=True, text=True)
    print(run.stdout + run.stderr)
    if run.returncode != 0:
        return 1
    problems = leaks(tree) + layout(tree, submission.discover_labs()) + readme(tree, submission.discover_labs())

    # Build it as a student would (no viewer: the same sources build in the instructor tree).
    build = tree / "build"
    env = dict(os.environ, CCACHE_BASEDIR=str(tree))  # relative paths: ccache hits from run to run
    configure = ["cmake", "-S", str(tree), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release", "-DSPRINGLAB_BUILD_VIEWER=OFF"]
    if shutil.which("ccache"):
        configure.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
    for step in (configure, ["cmake", "--build", str(build), "-j", str(args.jobs)]):
        run = subprocess.run(step, capture_output=True, text=True, env=env)
        if run.returncode != 0:
            print(run.stdout[-5000:] + run.stderr[-5000:])
            print(f"PROBLEM: the release does not build: {' '.join(step)}", file=sys.stderr)
            return 1
    junit = build / "ctest.xml"
    subprocess.run(["ctest", "--test-dir", str(build), "-j", str(args.jobs), "--output-junit", str(junit)],
                   capture_output=True, text=True)
    cases = {c.get("name"): c.get("status") for c in ET.parse(junit).getroot().iter("testcase")}
    labs = submission.discover_labs()
    graded = 0
    for name, status in sorted(cases.items()):
        lab_test = any(name.startswith(f"{lab.name}.") and not name.startswith(f"{lab.name}.grading.") for lab in labs)
        graded += lab_test
        if lab_test and status != "fail":
            problems.append(f"public test {name} does not fail on the skeleton ({status})")
        if not lab_test and status != "run":
            problems.append(f"test {name} fails in the release ({status})")
    for lab in labs:
        public = [t["name"] for ex in lab.manifest["exercises"] for t in ex["tests"] if t["visibility"] == "visible"]
        missing = [n for n in public if f"{lab.name}.{n}" not in cases]
        if missing:
            problems.append(f"{lab.dir}: public tests missing from the release's ctest: {', '.join(missing)}")
        hidden = [n for ex in lab.manifest["exercises"] for t in ex["tests"] if t["visibility"] != "visible"
                  for n in [t["name"]] if f"{lab.name}.{n}" in cases]
        if hidden:
            problems.append(f"{lab.dir}: hidden tests in the release: {', '.join(hidden)}")
    # A student's `check` (tools/grade.py on the lab's grading program) runs with the release's
    # own grader modules and scores the skeleton 0.
    for lab in labs[:1]:
        program = build / "tests" / f"{lab.name}_grading_student"
        run = subprocess.run([sys.executable, str(tree / "tools" / "grade.py"), "--binary", str(program),
                              "--manifest", str(tree / "tests" / lab.dir / "exercises.json"), "--quiet", "--seed", "1"],
                             capture_output=True, text=True, cwd=tree)
        if run.returncode != 0 or not re.search(r"\b0 / \d+ points", run.stdout):
            problems.append(f"`check {lab.name}` in the release does not score the skeleton 0 (exit {run.returncode}):\n"
                            + (run.stdout + run.stderr)[-2000:])
    for problem in problems:
        print(f"PROBLEM: {problem}", file=sys.stderr)
    if not problems:
        print(f"release builds; {graded} public tests fail on the skeleton, {len(cases) - graded} other tests pass")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
