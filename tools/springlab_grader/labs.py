"""The labs of this tree, one manifest each (tests/<folder>/exercises.json): the lab's id, folder,
title, handout and scene, and per exercise its file, functions, caller, handout section and
tests with points. CMake (cmake/SpringlabLab.cmake), the `springlab` script (through
tools/lab_table.py) and the grader all read these files; nothing here knows a particular lab.

A lab is named by its id (`rope`): the scenes' "lab" key, the framework's folder
(framework/labs/rope), the C++ namespace, the ctest prefix and what users type. Its folder
(`01_rope`) is the id behind the lab's number, for labs/, solutions/, tests/ and handouts/.
"""
import dataclasses
import pathlib
import re

from .errors import GradeError
from .manifest import ManifestError, load_manifest

ROOT = pathlib.Path(__file__).resolve().parents[2]  # the tree this grader belongs to
LAB_ID = r"[a-z][a-z0-9_]*"
FOLDER = re.compile(rf"^(\d\d)_({LAB_ID})$")
DECLARATION = re.compile(r"^(?P<ret>[^()]+?)\s+(?P<name>[A-Za-z_]\w*)\((?P<params>.*)\)$")


@dataclasses.dataclass
class Lab:
    name: str       # the id: rope
    dir: str        # the folder: 01_rope
    manifest: dict

    @property
    def id(self):
        return self.name

    @property
    def number(self):
        return int(self.dir[:2])

    @property
    def skeleton(self):
        return ROOT / "labs" / self.dir

    @property
    def solution(self):
        return ROOT / "solutions" / self.dir

    def exercise_of_file(self, file_name):
        """The exercise whose file is file_name (build_net.cpp), or None."""
        return next((ex for ex in self.manifest["exercises"] if ex["file"] == file_name), None)

    def names(self):
        """What a user may type for this lab: the id first, then the folder and lab<number>
        (older spellings, still accepted)."""
        return [self.name, self.dir, f"lab{self.number}"]


def check_layout(data, path):
    """The manifest's layout fields (the points and tests are manifest.load_manifest's): errors
    name the file and the field."""
    def need(obj, key, kind, where=""):
        if not isinstance(obj, dict) or not isinstance(obj.get(key), kind):
            what = "missing" if not isinstance(obj, dict) or key not in obj else f"must be a {kind.__name__}"
            raise GradeError(f"{path}: {where}{key}: {what}")
        return obj[key]

    folder = need(data, "folder", str)
    match = FOLDER.match(folder)
    if not match:
        raise GradeError(f"{path}: folder: '{folder}' is not NN_id (two digits, an underscore, the lab's id)")
    if folder != path.parent.name:
        raise GradeError(f"{path}: folder: '{folder}', but the manifest is in tests/{path.parent.name}/")
    if need(data, "lab", str) != match[2]:
        raise GradeError(f"{path}: lab: '{data['lab']}' is not the id in the folder's name ('{match[2]}')")
    for key in ("handout", "scene"):
        need(data, key, str)
    # The labs whose exercises this lab's scenes run too (the rope's integrators); optional.
    builds_on = data.get("builds_on", [])
    if not (isinstance(builds_on, list) and all(isinstance(b, str) and re.fullmatch(LAB_ID, b) for b in builds_on)):
        raise GradeError(f"{path}: builds_on: must be a list of lab ids ([\"rope\"])")
    for type_name, fields in need(data, "values", dict).items():
        if not (isinstance(fields, list) and fields and all(isinstance(f, str) for f in fields)):
            raise GradeError(f"{path}: values.{type_name}: must be the list of the struct's fields")
    files = set()
    for i, ex in enumerate(need(data, "exercises", list)):
        where = f"exercises[{i}]."
        file = need(ex, "file", str, where)
        if not file.endswith(".cpp") or "/" in file:
            raise GradeError(f"{path}: {where}file: '{file}' is not a file name ending in .cpp")
        if file in files:
            raise GradeError(f"{path}: {where}file: {file} belongs to two exercises; one file per exercise")
        files.add(file)
        for key in ("section", "caller"):
            need(ex, key, str, where)
        for j, declaration in enumerate(need(ex, "functions", list, where)):
            if not isinstance(declaration, str) or not DECLARATION.match(" ".join(declaration.split())):
                raise GradeError(f"{path}: {where}functions[{j}]: not a declaration `RETURN NAME(PARAMETERS)`")


def discover_labs(root=ROOT):
    """Every lab of the tree: one per tests/NN_<id>/exercises.json, in the order of the folders."""
    labs = []
    for path in sorted((root / "tests").glob("*/exercises.json")):
        if not FOLDER.match(path.parent.name):
            continue
        try:
            manifest = load_manifest(path)
        except ManifestError as error:
            raise GradeError(str(error)) from None
        check_layout(manifest, path)
        labs.append(Lab(manifest["lab"], manifest["folder"], manifest))
    if not labs:
        raise GradeError(f"{root / 'tests'}: no NN_<lab>/exercises.json manifests: no labs")
    ids = [lab.name for lab in labs]
    for lab in labs:
        for base in lab.manifest.get("builds_on", []):
            if base not in ids or base == lab.name:
                raise GradeError(f"{root / 'tests' / lab.dir / 'exercises.json'}: builds_on: '{base}' is not "
                                 f"another lab's id ({', '.join(ids)})")
    return labs


def find_lab(labs, which):
    """The lab a user named (its id, or the folder or lab<number>), or a GradeError listing the ids."""
    for lab in labs:
        if which in lab.names():
            return lab
    raise GradeError(f"no lab '{which}'; labs: {', '.join(lab.name for lab in labs)}")


def exercises_in(path):
    """Exercise ids marked in a reference source file."""
    if not path.exists():
        return []
    return re.findall(r"^\s*// BEGIN EXERCISE (\S+)\s*$", path.read_text(), re.M)
