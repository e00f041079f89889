#!/usr/bin/env python3
"""Each slip a course author can make is caught with FILE:LINE, and `release` refuses the tree:
on a copy of this tree, each slip is made alone, tools/author_check.py must report it where it
is (the file and line named, what the handout says and what the manifest says), `release`
must fail naming it, and the repaired tree must pass both again.

  stale totals          the handout's "worth N points", "in N exercises", the grading table's
                        total row, after the manifest changed
  points mismatch       a test's points changed in the manifest only: heading, table row
  leftover placeholder  a `TODO(author)` in a solution, a test, a header, a handout
  stale skeleton        a solution edited without running tools/make_skeleton.py
  two fixtures          a new hidden test file that declares its own MatchesReference
  "(1 point)"           accepted in a heading (and "(1 points)" too)

    tests/grading/check_author_slips.py --work build/tests/grading/author_slips
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

TODO = "TODO" + "(author)"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--work", required=True)
    args = ap.parse_args()
    work = pathlib.Path(args.work).resolve()
    tree = work / "tree"
    shutil.rmtree(work, ignore_errors=True)
    for rel in release.source_files():
        (tree / rel).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(ROOT / rel, tree / rel)
    # A repository of its own: release.py and author_check.py list the tree's files with git,
    # and the work folder may lie inside this checkout's ignored build folder.
    subprocess.run(["git", "init", "-q", str(tree)], check=True)
    problems = []

    def run(*argv):
        return subprocess.run([sys.executable, *map(str, argv)], capture_output=True, text=True, cwd=tree)

    def check():
        result = run(tree / "tools/author_check.py")
        return result.returncode, result.stdout + result.stderr

    def released():
        out = work / "release"
        shutil.rmtree(out, ignore_errors=True)
        result = run(tree / "tools/release.py", out)
        return result.returncode, result.stdout + result.stderr

    code, text = check()
    if code != 0:
        return fail([f"the unchanged tree does not pass tools/author_check.py:\n{text}"])

    def slip(name, path, change, expected):
        """Make one slip (change: text -> text of `path`), expect each regex of `expected` in
        author_check's output and release's refusal, then undo it."""
        target = tree / path
        before = target.read_text()
        after = change(before)
        if after == before:
            problems.append(f"{name}: the slip changed nothing in {path} (the test is out of date)")
            return
        target.write_text(after)
        code, text = check()
        if code != 1:
            problems.append(f"{name}: author_check exits {code}, expected 1:\n{text}")
        for regex in expected:
            if not re.search(regex, text, re.M):
                problems.append(f"{name}: author_check does not say /{regex}/:\n{text}")
        code, text = released()
        if code == 0 or "not ready for students" not in text:
            problems.append(f"{name}: release did not refuse the tree (exit {code}):\n{text}")
        target.write_text(before)
        print(f"caught: {name}")

    manifest = json.loads((ROOT / "tests/01_rope/exercises.json").read_text())
    total = sum(t["points"] for ex in manifest["exercises"] for t in ex["tests"])
    handout = (ROOT / "handouts/01_rope.md").read_text().splitlines()

    def line_with(text):
        return next(i for i, line in enumerate(handout, start=1) if text in line)

    # Stale totals: the lab's sentences and the table's total say one point less.
    worth_line, table_total = line_with(f"worth **{total} points**"), line_with(f"| **{total}** |")
    slip("stale totals", "handouts/01_rope.md",
         lambda t: t.replace(f"worth **{total} points**", f"worth **{total - 1} points**")
                    .replace(f"| **{total}** |", f"| **{total - 1}** |"),
         [rf"^handouts/01_rope\.md:{worth_line}: 'worth \*\*{total - 1} points\*\*'; the manifest "
          rf"\(tests/01_rope/exercises\.json\) says the lab is worth {total} points",
          rf"^handouts/01_rope\.md:{table_total}: the grading table's total points is '{total - 1}'; .* says '{total}'"])
    count_line = line_with("exercises (section")
    slip("stale count", "handouts/01_rope.md", lambda t: re.sub(r"in (\w+) exercises \(section", "in seven exercises (section", t, 1),
         [rf"^handouts/01_rope\.md:{count_line}: 'in seven exercises'; .* says eight exercises"])

    # Points mismatch: exercise 1.2's hidden test is worth one point more in the manifest only.
    first = manifest["exercises"][1]
    heading = line_with(f"### Exercise {first['id']}:")
    row = line_with(f"| {first['id']} | {first['title']} |")
    slip("points mismatch", "tests/01_rope/exercises.json",
         lambda t: t.replace('{"name": "MatchesReference.GravityAndAirFriction", "points": 1',
                             '{"name": "MatchesReference.GravityAndAirFriction", "points": 2'),
         [rf"^handouts/01_rope\.md:{heading}: exercise 1\.2 is worth 5 points; .* says 6 points",
          rf"^handouts/01_rope\.md:{row}: the grading table's points of exercise 1\.2 is '5'; .* says '6'"])

    # Leftover placeholders, wherever new_exercise.py writes them.
    for path in ("solutions/01_rope/spring_force.cpp", "tests/01_rope/public/spring_force_test.cpp",
                 "framework/labs/rope/include/springlab/rope/exercises.hpp", "handouts/02_net.md"):
        slip(f"placeholder in {path}", path, lambda t: t.replace("\n", f"\n// {TODO}: the formula\n", 1),
             [rf"^{re.escape(path)}:2: placeholder left"])

    # Stale skeleton: a solution edited, labs/ not regenerated.
    solution = "solutions/01_rope/spring_force.cpp"
    slip("stale skeleton", solution, lambda t: t.replace("namespace springlab::rope {", "namespace springlab::rope {\n\n// edited", 1),
         [r"^labs/01_rope/spring_force\.cpp:\d+: stale \(differs from what solutions/01_rope/spring_force\.cpp generates\); "
          r"run tools/make_skeleton\.py 01_rope"])

    # A new hidden file: with its own fixture, caught; with the lab's (by name), fine.
    extra = tree / "tests/01_rope/hidden/extra_test.cpp"
    own = ('#include "rope_fixtures.hpp"\nnamespace springlab::rope {\nnamespace {\n'
           'class MatchesReference : public springlab::testing::Seeded {};\n'
           'TEST_F(MatchesReference, Extra) {}\n}  // namespace\n}  // namespace springlab::rope\n')
    extra.write_text("// placeholder for the slip below\n")
    slip("hidden test with its own fixture", "tests/01_rope/hidden/extra_test.cpp", lambda t: own,
         [r"^tests/01_rope: suite MatchesReference has 2 fixtures.*tests/01_rope/hidden/extra_test\.cpp:5 uses the class "
          r"declared at tests/01_rope/hidden/extra_test\.cpp:4"])
    extra.write_text(own.replace("class MatchesReference : public springlab::testing::Seeded {};\n", ""))
    code, text = check()
    if code != 0:
        problems.append(f"a hidden file using the lab's MatchesReference by name is reported:\n{text}")
    extra.unlink()

    # "(1 point)" is a heading's singular; "(1 points)" is accepted too.
    sys.path.insert(0, str(tree / "tools"))
    import handout_check
    one = {"handout": "handouts/x.md", "points": 1, "exercises": [
        {"id": "9.1", "title": "one", "points": 1, "tests": [{"name": "A.B", "points": 1, "visibility": "visible"}]}]}
    for heading in ("### Exercise 9.1: one (1 point)", "### Exercise 9.1: one (1 points)"):
        page = work / "one.md"
        page.write_text(f"{heading}\n\n| id | title | points | public tests | hidden tests |\n|---|---|---|---|---|\n"
                        "| 9.1 | one | 1 | 1 test, 1 point | 0 tests, 0 points |\n"
                        "| | **total** | **1** | 1 test, 1 point | 0 tests, 0 points |\n\nThe lab is worth 1 point.\n")
        found = handout_check.check_handout(one, page, "m.json")
        if found:
            problems.append(f"'{heading}' is refused: {found}")

    # Repaired: the tree passes and releases again.
    code, text = check()
    if code != 0:
        problems.append(f"the repaired tree does not pass:\n{text}")
    code, text = released()
    if code != 0:
        problems.append(f"the repaired tree does not release:\n{text}")
    return fail(problems)


def fail(problems):
    for problem in problems:
        print(f"PROBLEM: {problem}", file=sys.stderr)
    if not problems:
        print("author slips: each caught with file and line, release refuses each, the repaired tree passes")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
