"""The labs of this instructor tree: found from CMakeLists.txt (`springlab_add_lab(NAME rope
DIR 01_rope)`) with their manifests; nothing here knows a particular lab."""
import dataclasses
import pathlib
import re

from .errors import GradeError
from .manifest import ManifestError, load_manifest

ROOT = pathlib.Path(__file__).resolve().parents[2]  # the tree this grader belongs to


@dataclasses.dataclass
class Lab:
    name: str       # rope
    dir: str        # 01_rope
    manifest: dict

    @property
    def skeleton(self):
        return ROOT / "labs" / self.dir

    @property
    def solution(self):
        return ROOT / "solutions" / self.dir


def discover_labs(root=ROOT):
    """Every lab with a springlab_add_lab line, a grading line and a manifest."""
    line = re.compile(r"^\s*springlab_add_lab\(\s*NAME\s+(\w+)\s+DIR\s+(\w+)\s*\)", re.M)
    grading = (root / "tests" / "CMakeLists.txt").read_text()
    labs = []
    for name, folder in line.findall((root / "CMakeLists.txt").read_text()):
        if not re.search(rf"^\s*springlab_add_grading\(\s*NAME\s+{name}\s+DIR\s+{folder}\s*\)", grading, re.M):
            raise GradeError(f"tests/CMakeLists.txt: no springlab_add_grading(NAME {name} DIR {folder}) line "
                             f"for the lab of CMakeLists.txt")
        try:
            manifest = load_manifest(root / "tests" / folder / "exercises.json")
        except ManifestError as error:
            raise GradeError(str(error)) from None
        labs.append(Lab(name, folder, manifest))
    if not labs:
        raise GradeError(f"{root / 'CMakeLists.txt'}: no springlab_add_lab(...) lines: no labs to grade")
    return labs


def exercises_in(path):
    """Exercise ids marked in a reference source file."""
    if not path.exists():
        return []
    return re.findall(r"^\s*// BEGIN EXERCISE (\S+)\s*$", path.read_text(), re.M)
