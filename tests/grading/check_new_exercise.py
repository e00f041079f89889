#!/usr/bin/env python3
"""`springlab new-exercise` on a copy of this tree, once in every lab: every piece is written
where the lab layout wants it (the declaration after the last exercise of the framework's
framework/labs/<name>/include/springlab/<name>/exercises.hpp, the reference in
solutions/<dir>/, tests in tests/<dir>/), the manifest and the
handout agree, labs/ is fresh (its copy of exercises.hpp declares the new function), the
skeleton's stub names the exercise, --signature and --points reach every piece, the
placeholders fail tools/author_check.py at their lines until written, every new file compiles (-fsyntax-only, warnings as errors)
with only the framework's headers on the include path, as CMake builds them, and bad input
gives a clear error.

    tests/grading/check_new_exercise.py --work build/tests/grading/new_exercise
"""
import argparse
import json
import pathlib
import re
import shutil
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import release  # noqa: E402
import submission  # noqa: E402


def scaffold_and_compile(tree, lab, run):
    """new-exercise LAB test_drag in the scratch tree: the pieces agree and compile."""
    problems = []
    header_path = tree / "framework" / "labs" / lab.name / "include" / "springlab" / lab.name / "exercises.hpp"
    last_exercise = max(m.start() for m in re.finditer(r"^// ---- Exercise ", header_path.read_text(), re.M))
    made = run(tree / "tools/new_exercise.py", lab.name, "test_drag", "--title", "test drag")
    print(made.stdout + made.stderr)
    if made.returncode != 0:
        return [f"new-exercise {lab.name} failed"]
    checks = [(tree / "tools/make_skeleton.py", "--check", lab.dir),
              (tree / "tools/grade.py", "--manifest", tree / "tests" / lab.dir / "exercises.json",
               "--check-handout", tree / "handouts" / f"{lab.dir}.md")]
    for check in checks:
        result = run(*check)
        if result.returncode != 0:
            problems.append(f"{' '.join(map(str, check))}: {result.stdout}{result.stderr}")
    stub = (tree / "labs" / lab.dir / "test_drag.cpp").read_text()
    if "throw springlab::NotImplemented" not in stub or "TODO exercise" not in stub:
        problems.append(f"the skeleton of the new exercise has no TODO and stub:\n{stub}")
    given = tree / "framework" / "labs" / lab.name / "include"
    headers = {h: given / "springlab" / lab.name / f"{h}.hpp" for h in ("exercises", lab.name)}
    declared = headers["exercises"].read_text().find("Vec3 testDrag(")
    if declared < last_exercise:
        problems.append(f"{headers['exercises'].relative_to(tree)}: testDrag is not declared after the last exercise")
    if "testDrag(" not in (tree / "labs" / lab.dir / "exercises.hpp").read_text():
        problems.append(f"labs/{lab.dir}/exercises.hpp: the generated copy does not declare testDrag")
    # Only exercise files in the lab folders: nothing else was written to them.
    for folder, allowed in ((tree / "solutions" / lab.dir, {".cpp"}),
                            (tree / "labs" / lab.dir, {".cpp", "exercises.hpp", "README.md"})):
        odd = [p.name for p in folder.iterdir() if p.suffix not in allowed and p.name not in allowed]
        if odd:
            problems.append(f"{folder.relative_to(tree)}: holds {', '.join(sorted(odd))} besides exercise files")
    # --signature and --points: the declaration, reference, stub and tests of a second exercise
    # agree on a signature of the author's; the manifest has the points; the handout agrees.
    made = run(tree / "tools/new_exercise.py", lab.name, "test_energy", "--points", "4", "--signature",
               "double testEnergy(const Vec3& x, double k, const std::vector<Vec3>& points)")
    if made.returncode != 0:
        return problems + [f"new-exercise {lab.name} test_energy --signature failed: {made.stderr}"]
    manifest = json.loads((tree / "tests" / lab.dir / "exercises.json").read_text())
    energy = manifest["exercises"][-1]
    if [t["points"] for t in energy["tests"]] != [2, 2] or energy["tests"][1]["name"] != "MatchesReference.TestEnergy":
        problems.append(f"--points 4: the manifest's tests are {energy['tests']}")
    if "double testEnergy(const Vec3& x, double k, const std::vector<Vec3>& points);" not in headers["exercises"].read_text():
        problems.append("--signature: the framework header does not declare testEnergy as given")
    for check in checks:
        result = run(*check)
        if result.returncode != 0:
            problems.append(f"after --signature: {' '.join(map(str, check))}: {result.stdout}{result.stderr}")
    # Until the author writes them, the placeholders fail the author check, each at its line.
    result = run(tree / "tools/author_check.py", lab.name)
    for path in (f"solutions/{lab.dir}/test_energy.cpp", f"tests/{lab.dir}/public/test_energy_test.cpp",
                 f"framework/labs/{lab.name}/include/springlab/{lab.name}/exercises.hpp", f"handouts/{lab.dir}.md"):
        if result.returncode != 1 or not re.search(rf"^{re.escape(path)}:\d+: placeholder left", result.stderr, re.M):
            problems.append(f"author_check does not report the placeholder in {path}: {result.stderr}")
    # The oracle header as tests/CMakeLists.txt generates it: every header of the lab in one
    # (the exercises first, the given class last), the lab's namespace renamed.
    oracle = tree / "oracle" / lab.name
    oracle.mkdir(parents=True)
    folder = given / "springlab" / lab.name
    middle = sorted(p.stem for p in folder.glob("*.hpp") if p.stem not in ("exercises", lab.name))
    text = ""
    for stem in ["exercises", *middle, lab.name]:
        part = (folder / f"{stem}.hpp").read_text().replace("#pragma once", "")
        part = re.sub(rf"#include <springlab/{lab.name}/[a-z_]+\.hpp>", "", part)
        text += part.replace(f"namespace springlab::{lab.name} ", f"namespace springlab::{lab.name}_reference ")
    (oracle / f"oracle_{lab.name}.hpp").write_text(f"#pragma once\n{text}")
    # Only the framework's headers (and the tests' support) on the include path, as CMake does.
    flags = ["-std=c++20", "-fsyntax-only", "-Wall", "-Wextra", "-Wpedantic", "-Wshadow", "-Wconversion",
             "-Wno-sign-conversion", "-Werror", "-Wno-unused-parameter", "-Wno-unknown-pragmas",
             f"-I{tree / 'framework/include'}", f"-I{given}", "-isystem", "/usr/include/eigen3",
             f"-I{tree / 'tests/support'}", f"-I{oracle}"]
    for source in (f"solutions/{lab.dir}/test_drag.cpp", f"labs/{lab.dir}/test_drag.cpp",
                   f"tests/{lab.dir}/public/test_drag_test.cpp", f"tests/{lab.dir}/hidden/test_drag_test.cpp",
                   f"solutions/{lab.dir}/test_energy.cpp", f"labs/{lab.dir}/test_energy.cpp",
                   f"tests/{lab.dir}/public/test_energy_test.cpp", f"tests/{lab.dir}/hidden/test_energy_test.cpp"):
        result = subprocess.run(["c++", *flags, str(tree / source)], capture_output=True, text=True)
        if result.returncode != 0:
            problems.append(f"{source} does not compile:\n{result.stderr[-3000:]}")
    return problems


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--work", required=True)
    args = ap.parse_args()
    tree = pathlib.Path(args.work).resolve() / "tree"
    shutil.rmtree(tree, ignore_errors=True)
    for rel in release.source_files():
        (tree / rel).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(ROOT / rel, tree / rel)
    labs = submission.discover_labs()
    problems = []

    def run(*argv):
        return subprocess.run([sys.executable, *map(str, argv)], capture_output=True, text=True, cwd=tree)

    # One new exercise in every lab: each lab's exercise header ends its exercises differently.
    for lab in labs:
        problems += scaffold_and_compile(tree, lab, run)
    lab = labs[0]
    # Bad input: a clear message and exit code 2.
    for argv, words in ((("no_such_lab", "x_force"), "no lab 'no_such_lab'"),
                        ((lab.name, "Bad-Name"), "snake_case"),
                        ((lab.name, "test_drag"), "already exists")):
        result = run(tree / "tools/new_exercise.py", *argv)
        if result.returncode != 2 or words not in result.stderr:
            problems.append(f"new-exercise {' '.join(argv)}: exit {result.returncode}, {result.stderr.strip()}")
    for problem in problems:
        print(f"PROBLEM: {problem}", file=sys.stderr)
    if not problems:
        print(f"new-exercise: scaffold consistent and compiles in {len(labs)} labs, bad input refused")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
