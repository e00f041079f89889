"""One result, every platform: besides Gradescope's results.json (reports.py), PrairieLearn's
external grader results and GitHub Classroom's autograding result.

PrairieLearn (external grader): the student's files are in /grade/student, the grader writes
/grade/results/results.json: {"gradable", "score" in [0, 1], "message", "output", "tests":
[{"name", "description", "points", "max_points", "output", "message"}]}. A grader that cannot
grade says so with "gradable": false, which PrairieLearn does not count as a submission.

GitHub Classroom (autograding-grading-reporter): each runner step sets its output `result` to
the base64 of {"version": 1, "status": "pass"|"fail"|"error", "max_score", "tests": [{"name",
"status", "score", "message", ...}]}; the reporter sums the tests' scores against the
max_scores (integer points) and posts the total."""
import base64
import json

from .results import split_text


def prairielearn_results(labs, notes=(), seed=None):
    tests = []
    for lab in labs:
        for r in lab.results:
            tests.append({"name": f"{r.exercise['id']} {r.test['name']}",
                          "description": f"{lab.manifest['title']}, exercise {r.exercise['id']}: "
                                         f"{r.exercise['title']}" + ("" if r.test["visibility"] == "visible"
                                                                     else " (hidden test)"),
                          "points": r.score, "max_points": r.test["points"],
                          "message": "passed" if r.passed else (r.message.splitlines() or ["failed"])[0],
                          "output": r.message or "passed"})
    score, max_score = sum(lab.score for lab in labs), sum(lab.max_score for lab in labs)
    text = ([f"Random inputs: SPRINGLAB_SEED={seed}"] if seed is not None else []) + list(notes)
    for lab in labs:
        text += [f"{lab.manifest['title']}: {lab.score:g} / {lab.max_score:g} ({split_text(lab.split())})", *lab.notes]
    return {"gradable": True, "score": score / max_score if max_score else 0.0,
            "message": f"{score:g} / {max_score:g} points", "output": "\n".join(text), "tests": tests}


def prairielearn_failure(message):
    """The grader itself could not grade: not counted against the student."""
    return {"gradable": False, "score": 0.0, "message": message, "output": message, "tests": []}


def classroom_result(lab):
    """One lab's public tests as the Classroom reporter reads them (integer points); hidden
    tests stay with the instructor (grade-all of the cloned repositories)."""
    public = [r for r in lab.results if r.test["visibility"] == "visible"]
    tests = [{"name": f"{r.exercise['id']} {r.test['name']}", "status": "pass" if r.passed else "fail",
              "score": int(r.score), "message": None if r.passed else r.message,
              "test_code": f"./springlab check {lab.manifest['lab']}", "filename": "", "line_no": 0,
              "duration": round(r.seconds * 1000)} for r in public]
    max_score = int(sum(r.test["points"] for r in public))
    return {"version": 1, "status": "pass" if all(r.passed for r in public) else "fail",
            "max_score": max_score, "tests": tests}


def classroom_error(manifest, message):
    """A lab that could not run (it does not build): every public point lost, with the reason."""
    public = [t for ex in manifest["exercises"] for t in ex["tests"] if t["visibility"] == "visible"]
    return {"version": 1, "status": "error", "max_score": int(sum(t["points"] for t in public)),
            "tests": [{"name": f"{manifest['title']}", "status": "error", "score": 0, "message": message}]}


def classroom_output_line(result):
    """The line a step appends to $GITHUB_OUTPUT: result=<base64 JSON>."""
    return "result=" + base64.b64encode(json.dumps(result).encode()).decode() + "\n"
