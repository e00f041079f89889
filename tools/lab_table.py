#!/usr/bin/env python3
"""The labs of this tree for the `springlab` script, one line each: ID FOLDER scenes/SCENE, in the
order of their folders (from tests/NN_<id>/exercises.json, read by springlab_grader.labs).
A broken manifest is named (file and field) on stderr, exit 2."""
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from springlab_grader.errors import GradeError  # noqa: E402
from springlab_grader.labs import discover_labs  # noqa: E402

try:
    for lab in discover_labs():
        print(lab.name, lab.dir, "scenes/" + lab.manifest["scene"])
except GradeError as error:
    print(f"springlab: {error}", file=sys.stderr)
    sys.exit(2)
