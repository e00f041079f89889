#!/usr/bin/env python3
"""`./springlab test`'s summary in a student tree (tools/missing_exercises.py): a lab whose
exercise files still hold the skeleton's stubs lists them; a written exercise is not listed;
a finished lab says so.

    check_missing_exercises.py ROOT

The summary runs on a tree of its own, written from the manifests (tests/NN_<id>/exercises.json):
one stub file per exercise, as tools/make_skeleton.py writes them. So the check does not depend
on the state of ROOT's labs/: it passes in a finished student tree too.
"""
import json
import pathlib
import shutil
import subprocess
import sys
import tempfile

root = pathlib.Path(sys.argv[1])
failures = []


def stub(exercise, handout):
    """An exercise file as the skeleton has it: a function whose body throws NotImplemented."""
    return (f'void exercise() {{\n  throw springlab::NotImplemented("{exercise["id"]}", "{exercise["title"]}", '
            f'"{handout}, Exercise {exercise["id"]}");\n}}\n')


with tempfile.TemporaryDirectory() as tmp:
    tree = pathlib.Path(tmp)
    labs = {}
    for folder in ("01_rope", "02_net"):
        manifest = json.loads((root / "tests" / folder / "exercises.json").read_text())
        labs[folder] = manifest
        (tree / "tests" / folder).mkdir(parents=True)
        shutil.copy(root / "tests" / folder / "exercises.json", tree / "tests" / folder / "exercises.json")
        (tree / "labs" / folder).mkdir(parents=True)
        for exercise in manifest["exercises"]:
            (tree / "labs" / folder / exercise["file"]).write_text(stub(exercise, manifest["handout"]))
    # A student who wrote the first exercise of Lab 1 and nothing else; Lab 2 finished.
    rope = labs["01_rope"]["exercises"]
    written = tree / "labs" / "01_rope" / rope[0]["file"]
    written.write_text(written.read_text().replace("throw springlab::NotImplemented(", "return; // was: throw NotImplemented("))
    for exercise in labs["02_net"]["exercises"]:
        (tree / "labs" / "02_net" / exercise["file"]).write_text("// written\n")
    p = subprocess.run([sys.executable, str(root / "tools" / "missing_exercises.py"), str(tree)],
                       capture_output=True, text=True, timeout=60)
    out = p.stdout
    if p.returncode != 0:
        failures.append(f"exit {p.returncode}\n{p.stderr}")
    second, last = rope[1], rope[-1]
    for needle in (f"{labs['01_rope']['title']}: {len(rope) - 1} missing",
                   f"{second['id']} {second['title']} (labs/01_rope/{second['file']})",
                   f"{last['id']} {last['title']}",
                   f"{labs['02_net']['title']}: none, every exercise is written"):
        if needle not in out:
            failures.append(f"summary lacks {needle!r}")
    if f"{rope[0]['id']} {rope[0]['title']}" in out:
        failures.append(f"the written exercise {rope[0]['id']} is listed as missing")
for f in failures:
    print("FAIL:", f)
print(out if failures else "missing exercises summary: ok")
sys.exit(1 if failures else 0)
