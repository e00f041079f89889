"""What graders and students read: the terminal summary, report.md, Gradescope results.json,
junit.xml per submission, and a class's gradebook.csv."""
import csv
import json
import pathlib
import sys
import xml.etree.ElementTree as ET

from .failures import sentences as failure_sentences
from .results import split_text


def print_lab(lab, quiet=False, file=sys.stdout, sentences=False, raw=False):
    """The terminal report of a lab. `sentences` (check): each failed test's message as what was
    expected, what came and what to check (failures.sentences), GoogleTest's own text under it
    with `raw`."""
    m = lab.manifest
    for note in lab.notes:
        print(f"  note: {note}".replace("\n", "\n        "), file=file)
    if not quiet:
        for ex in m["exercises"]:
            print(f"  Exercise {ex['id']}: {ex['title']}  {lab.exercise_score(ex):g}/{ex['points']:g}  "
                  f"({split_text(lab.split(ex))})", file=file)
            for r in (r for r in lab.results if r.exercise is ex):
                print(f"    {'PASS' if r.passed else 'FAIL'} {r.score:g}/{r.test['points']:g}  {r.test['name']}"
                      + ("" if r.test["visibility"] == "visible" else f"  ({r.test['visibility']})"), file=file)
                if r.message and not r.passed:
                    message = failure_sentences(r.message, raw=raw) if sentences else r.message
                    print("           " + message.replace("\n", "\n           "), file=file)
    percent = 100.0 * lab.score / lab.max_score if lab.max_score else 0.0
    print(f"{m['title']}: {lab.score:g} / {lab.max_score:g} points ({percent:.1f} %; {split_text(lab.split())})",
          file=file)


def report_markdown(labs, title, seed, notes=()):
    """The student's report; `notes` are the submission's own (a zip's refused entries, links
    refused), every one of which results.json carries too."""
    score, max_score = sum(lab.score for lab in labs), sum(lab.max_score for lab in labs)
    lines = [f"# {title}: {score:g} / {max_score:g} points", "",
             f"Random inputs drawn with SPRINGLAB_SEED={seed} (set it to replay this run).", ""]
    for note in notes:
        lines += ["> **Note**", ">", *(f"> {n}" if n else ">" for n in note.splitlines()), ""]
    if labs:
        lines += ["| lab | points |", "|---|---|"]
        lines += [f"| {lab.manifest['title']} | {lab.score:g} / {lab.max_score:g} |" for lab in labs]
        lines.append("")
    for lab in labs:
        lines += [f"## {lab.manifest['title']}: {lab.score:g} / {lab.max_score:g} points", "",
                  f"Points: {split_text(lab.split())}.", ""]
        for note in lab.notes:
            lines += ["> **Note**", ">", *(f"> {n}" if n else ">" for n in note.splitlines()), ""]
        for ex in lab.manifest["exercises"]:
            lines += [f"### Exercise {ex['id']}: {ex['title']} ({lab.exercise_score(ex):g} / {ex['points']:g} points: "
                      f"{split_text(lab.split(ex))})", ""]
            for r in (r for r in lab.results if r.exercise is ex):
                hidden = "" if r.test["visibility"] == "visible" else " (hidden test)"
                lines.append(f"- {'pass' if r.passed else '**FAIL**'} {r.score:g}/{r.test['points']:g} "
                             f"`{r.test['name']}`{hidden}")
                if r.message and not r.passed:
                    lines += ["", "  ```", *("  " + m for m in r.message.splitlines()), "  ```", ""]
            lines.append("")
    return "\n".join(lines)


def gradescope_results(labs, seconds, seed, notes=()):
    tests = []
    for lab in labs:
        for r in lab.results:
            tests.append(dict(name=f"{r.exercise['id']} {r.test['name']}", number=r.exercise["id"], score=r.score,
                              max_score=r.test["points"], output=r.message or "passed",
                              visibility=r.test["visibility"], tags=[lab.manifest["lab"], f"exercise {r.exercise['id']}"],
                              status="passed" if r.passed else "failed"))
    text = [f"Random inputs: SPRINGLAB_SEED={seed}", *notes]
    for lab in labs:
        text += [f"{lab.manifest['title']}: {lab.score:g} / {lab.max_score:g}", *lab.notes]
    return dict(score=sum(lab.score for lab in labs), max_score=sum(lab.max_score for lab in labs),
                execution_time=round(seconds, 3), output="\n".join(text), visibility="visible",
                stdout_visibility="hidden", tests=tests)


def junit_xml(labs, seconds):
    suites = ET.Element("testsuites", name="springlab", time=f"{seconds:.3f}")
    for lab in labs:
        failures = sum(1 for r in lab.results if not r.passed)
        suite = ET.SubElement(suites, "testsuite", name=lab.manifest["title"], tests=str(len(lab.results)),
                              failures=str(failures), errors="0", time=f"{sum(r.seconds for r in lab.results):.3f}")
        for r in lab.results:
            case = ET.SubElement(suite, "testcase", classname=f"{lab.manifest['lab']}.exercise_{r.exercise['id']}",
                                 name=r.test["name"], time=f"{r.seconds:.3f}")
            ET.SubElement(ET.SubElement(case, "properties"), "property", name="points",
                          value=f"{r.score:g}/{r.test['points']:g}")
            if not r.passed:
                failure = ET.SubElement(case, "failure", message=(r.message.splitlines() or ["failed"])[0][:200])
                failure.text = r.message
    ET.indent(suites)
    return ET.tostring(suites, encoding="unicode", xml_declaration=True) + "\n"


def write_outputs(out, labs, title, seconds, seed, notes=()):
    out = pathlib.Path(out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "report.md").write_text(report_markdown(labs, title, seed, notes))
    (out / "results.json").write_text(json.dumps(gradescope_results(labs, seconds, seed, notes), indent=1) + "\n")
    (out / "junit.xml").write_text(junit_xml(labs, seconds))


def write_submission(graded, out, seed):
    write_outputs(out, graded.labs, f"Grade of {graded.name}", graded.seconds, seed, graded.notes)


def write_gradebook(path, labs, graded_all):
    header = ["student"]
    for lab in labs:
        header += [f"{lab.dir} {ex['id']}" for ex in lab.manifest["exercises"]] + [f"{lab.dir} total"]
    header += ["total", "max", "percent", "notes"]
    with open(path, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(header)
        for name, graded in graded_all:
            row = [name]
            if graded is None:
                writer.writerow(row + [""] * (len(header) - 5) + ["0", str(sum(lab.manifest["points"] for lab in labs)),
                                                                   "0.0", "not graded"])
                continue
            for lab_result in graded.labs:
                row += [f"{lab_result.exercise_score(ex):g}" for ex in lab_result.manifest["exercises"]]
                row.append(f"{lab_result.score:g}")
            notes = [n.splitlines()[0] for lab in graded.labs for n in lab.notes if "does not" in n] + graded.notes
            percent = 100.0 * graded.score / graded.max_score if graded.max_score else 0.0
            row += [f"{graded.score:g}", f"{graded.max_score:g}", f"{percent:.1f}", "; ".join(notes)[:300]]
            writer.writerow(row)
