#!/usr/bin/env python3
"""Fairness of the grader: points follow the exercise, and every submission shape is graded.

Each submission is the reference (solutions/) with one thing changed; it must lose exactly the
points of the exercise at fault, test by test against the reference's own outcomes:

    sign_bug_3_1        Lab 3's spring forces with the wrong sign (4-point exercise 3.1): only
                        3.1's tests may fail (they did cascade into 14 points)
    sign_bug_3_3        Lab 3's volume with the wrong sign (exercise 3.3): only 3.3's tests
    compile_error_2_4   Lab 2's wind.cpp does not compile: only exercise 2.4's tests fail, and
                        the report names the file and shows the compiler's errors
    defines_other_exercise  Lab 1's spring_force.cpp also defines explicit Euler's step: the
                        file is graded as the skeleton's (1.1 and 1.4, not done, score 0)
    whole_repository    a student's clone: the tree (framework/, tests/, ...) with the reference
                        copied into labs/: full marks (tests/01_rope is not taken for a lab)
    whole_repository.zip  the same, zipped under a top folder
Graded on their own: the flat exercise files of Lab 1 with --lab rope (that lab only, full
marks) and without --lab (matched to Lab 1; the other labs "not submitted", not compiled).

    tests/grading/fairness.py --cache build --work build/tests/grading/fairness     (run by ctest)
"""
import argparse
import json
import pathlib
import shutil
import subprocess
import sys
import time
import zipfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
from springlab_grader.labs import discover_labs, exercises_in  # noqa: E402

# (lab dir, exercise file, exact text to replace, replacement)
SIGN_BUGS = {
    "sign_bug_3_1": ("03_softbody", "spring_forces.cpp", "    f[s.mass1] += f1;\n    f[s.mass2] -= f1;",
                     "    f[s.mass1] -= f1;\n    f[s.mass2] += f1;"),
    "sign_bug_3_3": ("03_softbody", "volume.cpp", "  return v / 6.0;", "  return -v / 6.0;"),
}
COMPILE_ERROR = ("02_net", "wind.cpp")


def exercise_of(lab_dir, name):
    ids = sorted(set(exercises_in(ROOT / "solutions" / lab_dir / name)))
    if len(ids) != 1:
        raise SystemExit(f"fairness.py: solutions/{lab_dir}/{name} should hold one exercise, holds {ids}")
    return ids[0]


def make(folder):
    """Write the class; {student: (lab dir, the exercises that must lose points there)}."""
    shutil.rmtree(folder, ignore_errors=True)
    folder.mkdir(parents=True)
    expect = {}

    def reference_copy(student):
        target = folder / student / "labs"
        shutil.copytree(ROOT / "solutions", target)
        return target

    for student, (lab, name, old, new) in SIGN_BUGS.items():
        path = reference_copy(student) / lab / name
        text = path.read_text()
        if old not in text:
            raise SystemExit(f"fairness.py: solutions/{lab}/{name} no longer has the line to break; update SIGN_BUGS")
        path.write_text(text.replace(old, new, 1))
        expect[student] = (lab, {exercise_of(lab, name)})
    lab, name = COMPILE_ERROR
    path = reference_copy("compile_error_2_4") / lab / name
    path.write_text(path.read_text() + "\nthis line is not C++;\n")
    expect["compile_error_2_4"] = (lab, {exercise_of(lab, name)})
    # A cheat: Lab 1's spring_force.cpp also defines explicit Euler's step (left undone in its
    # own file), so its program would take the student's 1.4 instead of the reference's. The
    # file is graded as the skeleton's: 1.1 and 1.4 score 0, nothing else changes.
    folder_1 = reference_copy("defines_other_exercise") / "01_rope"
    shutil.copy(ROOT / "labs" / "01_rope" / "explicit_euler.cpp", folder_1 / "explicit_euler.cpp")
    text = (folder_1 / "spring_force.cpp").read_text()
    marker = "}  // namespace springlab::rope"
    if marker not in text:
        raise SystemExit("fairness.py: solutions/01_rope/spring_force.cpp changed shape; update defines_other_exercise")
    (folder_1 / "spring_force.cpp").write_text(text.replace(marker, (
        "PhasePoint explicitEulerStep(const PhasePoint& s, const Vec3& a, double dt) {\n"
        "  return {s.pos + s.vel * dt, s.vel + a * dt};\n}\n" + marker), 1))
    expect["defines_other_exercise"] = ("01_rope", {exercise_of("01_rope", "spring_force.cpp"),
                                                    exercise_of("01_rope", "explicit_euler.cpp")})

    # A student's clone: the tree without solutions/ and build folders, the reference in labs/.
    repo = folder / "whole_repository"
    for part in ("framework", "tests", "labs", "handouts", "scenes", "cmake"):
        if (ROOT / part).is_dir():
            shutil.copytree(ROOT / part, repo / part)
    for part in ("CMakeLists.txt", "README.md", "springlab"):
        if (ROOT / part).is_file():
            shutil.copy(ROOT / part, repo / part)
    for lab_folder in (ROOT / "solutions").iterdir():
        for source in lab_folder.glob("*.cpp"):
            shutil.copy(source, repo / "labs" / lab_folder.name / source.name)
    expect["whole_repository"] = (None, set())
    with zipfile.ZipFile(folder / "whole_repository_zip.zip", "w") as zf:
        for path in sorted(repo.rglob("*")):
            if path.is_file() and "tests" not in path.relative_to(repo).parts[:1]:
                zf.write(path, f"springlab-main/{path.relative_to(repo)}")
    expect["whole_repository_zip"] = (None, set())
    return expect


def grade(args, what, out, *extra):
    started = time.monotonic()
    run = subprocess.run([sys.executable, str(ROOT / "tools" / "submission.py"), *what, "--out", str(out),
                          "--cache", args.cache, "--no-build", "--seed", "2024", "--jobs", str(args.jobs), *extra],
                         text=True, capture_output=True)
    print(run.stdout + run.stderr)
    print(f"[{' '.join(what[:1])}: {time.monotonic() - started:.1f} s]")
    if run.returncode != 0:
        raise SystemExit(f"fairness.py: {' '.join(what)} failed with exit code {run.returncode}")


def lab_dir(tag):
    """The folder of the lab a results.json test is tagged with (its tag is the lab's id)."""
    return {lab.id: lab.dir for lab in discover_labs()}.get(tag, tag)


def outcomes(results):
    return {(lab_dir(t["tags"][0]), t["name"].split(" ", 1)[1]): (t["status"], t["tags"][1].split(" ", 1)[1])
            for t in results["tests"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cache", required=True, help="a build of this tree with the grading programs built")
    ap.add_argument("--work", required=True, help="scratch folder for the submissions and their reports")
    ap.add_argument("--jobs", type=int, default=2)
    args = ap.parse_args()
    work = pathlib.Path(args.work).resolve()
    labs = {lab.dir: lab for lab in discover_labs()}
    problems = []

    # The reference's own outcomes at this seed: the yardstick.
    grade(args, ["grade", str(ROOT / "solutions"), "--quiet"], work / "reference")
    reference = json.loads((work / "reference" / "results.json").read_text())
    want = outcomes(reference)
    if reference["score"] != reference["max_score"]:
        problems.append(f"the reference scores {reference['score']}/{reference['max_score']}")

    expect = make(work / "class")
    grade(args, ["grade-all", str(work / "class")], work / "grades")
    for student, (lab, exercises) in expect.items():
        data = json.loads((work / "grades" / student / "results.json").read_text())
        got = outcomes(data)
        if sorted(got) != sorted(want):
            problems.append(f"{student}: results.json does not list the reference's tests")
            continue
        lost = set()
        for key, (status, ex) in got.items():
            at_fault = key[0] == lab and ex in exercises
            if not at_fault and status != want[key][0]:
                problems.append(f"{student}: {key[1]} ({key[0]}, exercise {ex}) is {status}: only exercise(s) "
                                f"{', '.join(sorted(exercises))} of {lab} may lose points")
            if at_fault and status != "passed":
                lost.add(ex)
        if lost != exercises:
            problems.append(f"{student}: exercise(s) {', '.join(sorted(exercises - lost))} lost no points: "
                            f"the fault went unnoticed")
        print(f"{student}: {data['score']:g}/{data['max_score']:g}")
    report = (work / "grades" / "compile_error_2_4" / "report.md").read_text()
    if f"{COMPILE_ERROR[1]} does not compile" not in report or "error" not in report:
        problems.append("compile_error_2_4: the report does not name the file or show the compiler's errors")

    # Flat files of Lab 1: with --lab rope only that lab; without, matched to Lab 1.
    flat = work / "flat_rope"
    shutil.rmtree(flat, ignore_errors=True)
    shutil.copytree(ROOT / "solutions" / "01_rope", flat)
    grade(args, ["grade", str(flat), "--quiet", "--lab", "rope"], work / "flat_lab")
    data = json.loads((work / "flat_lab" / "results.json").read_text())
    if {lab_dir(t["tags"][0]) for t in data["tests"]} != {"01_rope"} or data["score"] != data["max_score"] \
            or data["max_score"] != labs["01_rope"].manifest["points"]:
        problems.append(f"flat files with --lab rope: {data['score']}/{data['max_score']}, expected Lab 1 only, full marks")
    grade(args, ["grade", str(flat), "--quiet"], work / "flat_guess")
    data = json.loads((work / "flat_guess" / "results.json").read_text())
    by_lab = {}
    for t in data["tests"]:
        by_lab.setdefault(lab_dir(t["tags"][0]), []).append(t)
    if sum(t["score"] for t in by_lab.get("01_rope", [])) != labs["01_rope"].manifest["points"]:
        problems.append("flat files without --lab: Lab 1 does not score full marks")
    if any(t["score"] for d, tests in by_lab.items() if d != "01_rope" for t in tests):
        problems.append("flat files without --lab: a lab nobody submitted scores points")
    if "not submitted" not in data["output"] or "does not link" in data["output"]:
        problems.append("flat files without --lab: the other labs are not reported as not submitted")

    for problem in problems:
        print(f"PROBLEM: {problem}", file=sys.stderr)
    if problems:
        return 1
    print(f"{len(expect)} submissions and 2 flat-file gradings: every point follows its exercise")
    return 0


if __name__ == "__main__":
    sys.exit(main())
