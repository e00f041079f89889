#!/usr/bin/env python3
"""The course author's invariants, checked in well under a second, each slip reported as
FILE:LINE and what to do:

  skeleton   labs/<dir>/ is what tools/make_skeleton.py generates from solutions/<dir>/, the
             framework's exercises.hpp and the manifest (first differing line named)
  handout    handouts/<dir>.md states the manifest's points: headings, grading table, totals,
             "worth N points", "in N exercises" (tools/handout_check.py)
  todo       no `TODO(author)` placeholder left anywhere in the tree (new_exercise.py writes them;
             a mention in backticks, as on this line, is documentation and allowed)
  fixtures   each GoogleTest suite of a lab has one fixture class across the lab's test files
             (two make GoogleTest fail every test of the suite)

    tools/author_check.py                 every lab; exit 1 if anything is wrong
    tools/author_check.py rope            one lab's skeleton, handout and fixtures (and the tree's TODOs)
    tools/author_check.py --warn          print the problems as warnings, exit 0 (build and check use it)

`./springlab author-check LAB` runs this, then the lab's tests (handouts/authoring.md).
"""
import argparse
import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tools"))
import handout_check  # noqa: E402
import make_skeleton  # noqa: E402
from springlab_grader import labs  # noqa: E402
from springlab_grader.errors import GradeError  # noqa: E402
from springlab_grader.manifest import ManifestError, load_manifest  # noqa: E402

# Written split so that this file is not itself a leftover placeholder.
TODO_MARK = "TODO" + "(author)"
SKIP_DIRS = {".git", "out", "__pycache__", ".cache"}
TEXT_SUFFIXES = {".cpp", ".hpp", ".h", ".md", ".json", ".txt", ".py", ".cmake", ".sh", ".in", ""}


def labs_of_tree():
    """The labs of the tree, one per manifest (tests/NN_<id>/exercises.json)."""
    try:
        return labs.discover_labs(ROOT)
    except GradeError as error:
        raise SystemExit(f"author_check: {error}") from None


def pick_labs(names):
    """The labs named (by id, or an older spelling: folder, lab<number>); every lab without names."""
    every = labs_of_tree()
    try:
        return [labs.find_lab(every, which) for which in names] or every
    except GradeError as error:
        raise SystemExit(f"author_check: {error}") from None


def rel(path):
    path = pathlib.Path(path)
    return path.relative_to(ROOT) if path.is_absolute() and path.is_relative_to(ROOT) else path


# ---- skeleton: labs/<dir>/ as generated ------------------------------------------------------
def skeleton_problems(lab):
    try:
        wanted = make_skeleton.generate(lab.dir)
    except make_skeleton.SkeletonError as error:
        return [f"{error} (tools/make_skeleton.py cannot generate labs/{lab.dir})"]
    fix = f"run tools/make_skeleton.py {lab.dir} and commit labs/{lab.dir}/"
    problems = []
    for path, text in wanted.items():
        if not path.exists():
            problems.append(f"{rel(path)}: missing; {fix}")
            continue
        have = path.read_text().splitlines()
        want = text.splitlines()
        if have == want and path.read_text() == text:
            continue
        line = next((i + 1 for i, (a, b) in enumerate(zip(have, want)) if a != b), min(len(have), len(want)) + 1)
        source = "solutions/" + lab.dir + "/" + path.name if path.suffix == ".cpp" else (
            "the manifest" if path.name == "README.md" else f"framework/labs/{lab.name}/.../exercises.hpp")
        problems.append(f"{rel(path)}:{line}: stale (differs from what {source} generates); {fix}")
    folder = ROOT / "labs" / lab.dir
    if folder.exists():
        for path in sorted(p for p in folder.rglob("*") if p.is_file() and p not in wanted):
            problems.append(f"{rel(path)}: not generated from solutions/{lab.dir}/; {fix} (it deletes it)")
    return problems


# ---- handout: what it says about points -------------------------------------------------------
def handout_problems(lab):
    manifest_path = ROOT / "tests" / lab.dir / "exercises.json"
    try:
        manifest = load_manifest(manifest_path)
    except ManifestError as error:
        return [str(error)]
    return handout_check.check_handout(manifest, ROOT / manifest["handout"], rel(manifest_path),
                                       shown=rel(ROOT / manifest["handout"]))


# ---- todo: placeholders left by new_exercise.py -----------------------------------------------
def tree_files():
    """git's list when this tree is a checkout of its own, else a walk (a copy of the tree,
    even one inside another checkout's ignored build folder)."""
    try:
        top = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--show-toplevel"], capture_output=True,
                             check=True).stdout.decode().strip()
        if pathlib.Path(top).resolve() == ROOT:
            listed = subprocess.run(["git", "-C", str(ROOT), "ls-files", "-z", "--cached", "--others",
                                     "--exclude-standard"], capture_output=True, check=True).stdout.decode().split("\0")
            return [ROOT / p for p in listed if p]
    except (OSError, subprocess.CalledProcessError):
        pass
    return [p for p in ROOT.rglob("*") if not (set(p.relative_to(ROOT).parts) & SKIP_DIRS)
            and not p.relative_to(ROOT).parts[0].startswith("build")]


def todo_problems():
    problems = []
    for path in tree_files():
        if path.suffix not in TEXT_SUFFIXES or not path.is_file():
            continue
        try:
            text = path.read_text()
        except (OSError, UnicodeDecodeError):
            continue
        if TODO_MARK not in text:
            continue
        for number, line in enumerate(text.splitlines(), start=1):
            at = line.find(TODO_MARK)
            while at >= 0:
                quoted = line[at - 1:at] == "`" and line[at + len(TODO_MARK):at + len(TODO_MARK) + 1] == "`"
                if not quoted:
                    problems.append(f"{rel(path)}:{number}: placeholder left: {line.strip()[:100]}")
                    break
                at = line.find(TODO_MARK, at + 1)
    return problems


# ---- fixtures: one fixture class per test suite -----------------------------------------------
TEST_F = re.compile(r"^\s*TEST_F\(\s*(\w+)\s*,", re.M)
TEST = re.compile(r"^\s*TEST\(\s*(\w+)\s*,", re.M)
CLASS = re.compile(r"^\s*(?:class|struct)\s+(\w+)\s*(?:final\s*)?[:{]", re.M)
ALIAS = re.compile(r"^\s*using\s+(\w+)\s*=\s*([^;]+);", re.M)


def fixture_problems(lab):
    """Each suite's fixture, per file: its own class (file:line), an alias (the type it names),
    the shared one from a header, or ::testing::Test for TEST(). More than one is an error."""
    uses = {}  # suite -> {source: (file, line)}
    for path in sorted((ROOT / "tests" / lab.dir).glob("*/*.cpp")):
        text = path.read_text()
        local = {}
        for m in CLASS.finditer(text):
            local[m.group(1)] = (f"the class declared at {rel(path)}:{text.count(chr(10), 0, m.start()) + 1}", None)
        for m in ALIAS.finditer(text):
            local[m.group(1)] = (m.group(2).split("::")[-1].replace(" ", ""), None)
        for regex, default in ((TEST_F, None), (TEST, "::testing::Test (TEST)")):
            for m in regex.finditer(text):
                suite = m.group(1)
                line = text.count("\n", 0, m.start()) + 1
                if default:
                    source = default
                elif suite in local:
                    source = local[suite][0]
                else:
                    source = f"the shared {suite} (tests/support/{lab.name}_fixtures.hpp)" if suite == "MatchesReference" \
                        else f"the shared {suite} from a header"
                uses.setdefault(suite, {}).setdefault(source, (rel(path), line))
    problems = []
    for suite, sources in uses.items():
        if len(sources) > 1:
            listed = "; ".join(f"{f}:{n} uses {s}" for s, (f, n) in sources.items())
            problems.append(f"tests/{lab.dir}: suite {suite} has {len(sources)} fixtures, and GoogleTest then fails "
                            f"every {suite}.* test: {listed}. Use one; a hidden test joins MatchesReference with "
                            f"#include \"{lab.name}_fixtures.hpp\" and TEST_F(MatchesReference, Name), no fixture of its own")
    return problems


def problems(labs=None, skeleton=True):
    """Every problem of the given labs (default all), and the TODO placeholders of the tree."""
    found = []
    for lab in labs if labs is not None else labs_of_tree():
        if skeleton:
            found += skeleton_problems(lab)
        found += handout_problems(lab)
        found += fixture_problems(lab)
    return found + todo_problems()


def main():
    ap = argparse.ArgumentParser(prog="author_check", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("labs", nargs="*", help="labs to check (rope or 01_rope; default: every lab)")
    ap.add_argument("--warn", action="store_true", help="print problems as warnings and exit 0")
    args = ap.parse_args()
    if not (ROOT / "solutions").is_dir():
        return 0  # a student tree: nothing of the author's to check
    found = problems(pick_labs(args.labs))
    for p in found:
        print(f"springlab: warning: {p}" if args.warn else p, file=sys.stderr)
    if args.warn:
        return 0
    print(f"author check: {len(found)} problem(s)" if found else "author check: skeleton fresh, handouts agree, "
          "no placeholder left, one fixture per suite")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
