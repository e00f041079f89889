#!/usr/bin/env python3
"""Every platform from one result, each tested by reproducing its contract here, as
check_autograder.py does for Gradescope's bundle:

  - PrairieLearn's external grader: the student's files in <root>/student (flat, as its file
    editor and upload leave them), `tools/submission.py prairielearn --grade-root <root>` writes
    <root>/results/results.json with "score" in [0, 1] (the points' share), "tests" with
    points and max_points, and "gradable": false (not counted) when the grader itself fails;
  - GitHub Classroom: the release's .github/workflows/classroom.yml runs each lab's public tests
    with tools/grade.py --classroom "$GITHUB_OUTPUT"; its steps are run here as the runner runs
    them, and their `result` outputs are read as autograding-grading-reporter reads them (the
    env variable <RUNNER>_RESULTS, base64 JSON, the tests' scores summed against max_score).

    tests/grading/check_platforms.py --cache build --work build/tests/grading/platforms
"""
import argparse
import base64
import json
import os
import pathlib
import shutil
import subprocess
import sys

import yaml

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
from springlab_grader.labs import discover_labs  # noqa: E402

LAB = discover_labs()[0]


def prairielearn(cache, work, files, expect_score):
    """Grade `files` as PrairieLearn would; problems found."""
    root = work / f"grade-{expect_score}"
    shutil.rmtree(root, ignore_errors=True)
    (root / "student").mkdir(parents=True)
    (root / "data").mkdir()
    (root / "data" / "data.json").write_text(json.dumps({"submitted_answers": {}, "params": {}}))
    for path in files:
        shutil.copy(path, root / "student" / path.name)
    run = subprocess.run([sys.executable, str(ROOT / "tools" / "submission.py"), "prairielearn", "--grade-root",
                          str(root), "--lab", LAB.name, "--cache", str(cache), "--no-build", "--seed", "7",
                          "--jobs", "2"], text=True, capture_output=True)
    print(run.stdout[-2000:] + run.stderr[-2000:])
    path = root / "results" / "results.json"
    if not path.is_file():
        return [f"PrairieLearn: no {path.relative_to(work)}"]
    data = json.loads(path.read_text())
    problems = []
    if expect_score is None:
        if data.get("gradable") is not False or not data.get("message"):
            problems.append(f"PrairieLearn: a failing grader must leave gradable: false with a message: {data}")
        return problems
    if data.get("gradable") is not True or not 0.0 <= data.get("score", -1) <= 1.0:
        problems.append(f"PrairieLearn: gradable {data.get('gradable')}, score {data.get('score')}")
    tests = data.get("tests", [])
    for t in tests:
        for key, kind in (("name", str), ("points", (int, float)), ("max_points", (int, float)), ("output", str)):
            if not isinstance(t.get(key), kind):
                problems.append(f"PrairieLearn: tests[].{key} missing or not {kind}: {t}")
    points, max_points = sum(t["points"] for t in tests), sum(t["max_points"] for t in tests)
    if max_points != LAB.manifest["points"] or abs(data["score"] - points / max_points) > 1e-9:
        problems.append(f"PrairieLearn: score {data['score']} is not {points}/{max_points} of {LAB.manifest['points']}")
    if abs(data["score"] - expect_score) > 1e-9:
        problems.append(f"PrairieLearn: score {data['score']}, expected {expect_score}")
    return problems


def classroom_steps(workflow):
    """{runner id: its shell script} and the reporter step, from the workflow."""
    steps = workflow["jobs"]["run-autograding-tests"]["steps"]
    runners = {s["id"]: s["run"] for s in steps if "id" in s}
    reporter = next(s for s in steps if str(s.get("uses", "")).startswith("classroom-resources/autograding-grading-reporter"))
    return runners, reporter


def classroom(cache, work):
    problems = []
    template = ROOT / "tools" / "templates" / "classroom.yml"
    workflow = yaml.safe_load(template.read_text())
    runners, reporter = classroom_steps(workflow)
    names = [r.strip() for r in reporter["with"]["runners"].split(",")]
    if names != list(runners):
        problems.append(f"Classroom: the reporter's runners {names} are not the steps {list(runners)}")
    for name in names:
        if reporter["env"].get(f"{name.upper()}_RESULTS") != f"${{{{steps.{name}.outputs.result}}}}":
            problems.append(f"Classroom: the reporter does not read {name.upper()}_RESULTS from step {name}")
    labs = discover_labs()
    if len(runners) != len(labs) or any(f"tests/{lab.dir}/exercises.json" not in script
                                         for lab, script in zip(labs, runners.values())):
        problems.append("Classroom: one step per lab, in order, each with its manifest")
    # The steps as the runner runs them (the build folder is the grading build here), then the
    # reporter's reading of their outputs.
    totals = {}
    for name, script in runners.items():
        output = work / f"github_output_{name}"
        output.write_text("")
        script = "\n".join(line for line in script.splitlines() if not line.startswith("cmake --build"))
        run = subprocess.run(["bash", "-c", script.replace("build/tests/", f"{cache}/tests/")], cwd=ROOT, text=True,
                             capture_output=True, env=dict(os.environ, GITHUB_OUTPUT=str(output)))
        print(run.stdout[-1500:] + run.stderr[-1500:])
        lines = [line for line in output.read_text().splitlines() if line.startswith("result=")]
        if len(lines) != 1:
            problems.append(f"Classroom: step {name} set {len(lines)} result outputs")
            continue
        data = json.loads(base64.b64decode(lines[0][len("result="):]))
        if data.get("version") != 1 or data.get("status") not in ("pass", "fail", "error"):
            problems.append(f"Classroom: step {name}: version {data.get('version')}, status {data.get('status')}")
        if not isinstance(data.get("max_score"), int) or not all(isinstance(t.get("score"), int) for t in data["tests"]):
            problems.append(f"Classroom: step {name}: points are not integers")
        totals[name] = (sum(t["score"] for t in data["tests"]), data["max_score"])
    for (name, (score, max_score)), lab in zip(totals.items(), labs):
        public = sum(t["points"] for ex in lab.manifest["exercises"] for t in ex["tests"] if t["visibility"] == "visible")
        if max_score != public:
            problems.append(f"Classroom: {name} is worth {max_score}, the lab's public points are {public}")
        built = (cache / "tests" / f"{lab.name}_grading_student").exists()
        if score != 0:  # the grading build's student program is the skeleton's; an unbuilt lab errors
            problems.append(f"Classroom: {name} scores {score} on the skeleton ({'built' if built else 'not built'})")
    # The reference's public tests: full public points through the same step.
    script = runners[names[0]].replace(f"{LAB.name}_grading_student", f"{LAB.name}_grading_reference")
    output = work / "github_output_reference"
    output.write_text("")
    script = "\n".join(line for line in script.splitlines() if not line.startswith("cmake --build"))
    subprocess.run(["bash", "-c", script.replace("build/tests/", f"{cache}/tests/")], cwd=ROOT, capture_output=True,
                   env=dict(os.environ, GITHUB_OUTPUT=str(output)))
    data = json.loads(base64.b64decode(output.read_text().split("result=", 1)[1]))
    if sum(t["score"] for t in data["tests"]) != data["max_score"] or data["status"] != "pass":
        problems.append(f"Classroom: the reference scores {sum(t['score'] for t in data['tests'])}/{data['max_score']}")
    # The release carries the workflow.
    import release  # noqa: PLC0415
    out = work / "release"
    release.release(out, force=True)
    shipped = out / ".github" / "workflows" / "classroom.yml"
    if not shipped.is_file() or shipped.read_text() != template.read_text():
        problems.append("Classroom: the release has no .github/workflows/classroom.yml")
    return problems


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cache", required=True, help="a build of this tree with Lab 1's grading programs built")
    ap.add_argument("--work", required=True)
    args = ap.parse_args()
    cache = pathlib.Path(args.cache).resolve()
    work = pathlib.Path(args.work).resolve()
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    problems = prairielearn(cache, work, sorted(LAB.solution.glob("*.cpp")), 1.0)
    problems += prairielearn(cache, work, sorted(LAB.skeleton.glob("*.cpp")), 0.0)
    problems += prairielearn(pathlib.Path("/nonexistent-springlab-cache"), work, sorted(LAB.solution.glob("*.cpp")), None)
    problems += classroom(cache, work)
    for problem in problems:
        print(f"PROBLEM: {problem}", file=sys.stderr)
    if not problems:
        print("PrairieLearn and GitHub Classroom: each contract reproduced, the reference full, the skeleton 0")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
