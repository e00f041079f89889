"""Checks of a submission's compiled exercise files, run on the trusted side: a file that
includes anything outside the submission and the framework (solutions/, hidden tests), calls
the reference "oracle", or redefines the framework's, GoogleTest's or the grading main's
symbols, or calls what an exercise never needs to (the test framework, files, the environment,
other processes) is graded as the released skeleton's file, and the report says why."""
import pathlib
import re

from .call_check import (FORBIDDEN_CALLS, REPLACED, defined_symbols, demangle, forbidden_call_reason,  # noqa: F401
                         forbidden_calls, replaced_note, symbols_by_file, undefined_symbols)
from .labs import exercises_in


def parse_depfile(text):
    body = text.replace("\\\n", " ")
    _, _, deps = body.partition(": ")
    return [d.replace("\\ ", " ") for d in re.split(r"(?<!\\)\s+", deps.strip()) if d]


def allowed_folders(work, build):
    """The submission's own files, the folders the compiler's sandbox shows (sealed_compile.py)."""
    return [(work / "src").resolve(), *build.sealed.include_folders()]


def find_cheats(objects, work, build, lab, notes, others=None, call_check=True):
    """Files to grade as the skeleton's: they include the instructor's files, call the
    reference solution, or redefine the framework's, GoogleTest's or the grader's symbols.
    `objects` are the compiled files (with their .d files beside them), `build` the lab's
    LabBuild; each finding is added to notes. `others` maps a file's name to the symbols the
    reference's other exercise files define: a file that defines another exercise's function
    (which its grading program takes from the reference) is flagged too, and so is a file that
    calls what FORBIDDEN_CALLS lists (unless `call_check` is off, to test the sandbox)."""
    allowed = allowed_folders(work, build)
    flagged = {}
    defined_in = symbols_by_file(objects)
    undefined_in = symbols_by_file(objects, undefined=True)
    inside_cache = {}

    def inside(dep):
        if dep not in inside_cache:
            path = pathlib.Path(dep)
            resolved = (work / path).resolve() if not path.is_absolute() else path.resolve()
            inside_cache[dep] = any(resolved.is_relative_to(folder) for folder in allowed)
        return inside_cache[dep]

    for obj in objects:
        name = obj.name[:-2]
        deps = obj.with_suffix(".d")
        for dep in parse_depfile(deps.read_text()) if deps.exists() else []:
            if not inside(dep):
                # Its name only: the path may be the grading tree's.
                flagged.setdefault(name, f"includes {pathlib.PurePath(dep).name}, a file outside the submission "
                                         f"and the framework")
                break
        used = undefined_in[str(obj)] & build.oracle_symbols
        if used:
            flagged.setdefault(name, "calls the reference solution (" + ", ".join(demangle(used)[:3]) + ")")
        defined = defined_in[str(obj)] & build.protected_symbols
        if defined:
            flagged.setdefault(name, "redefines symbols of the framework, GoogleTest or the grader ("
                               + ", ".join(demangle(defined)[:3]) + ")")
        reached = forbidden_call_reason(undefined_in[str(obj)]) if call_check else None
        if reached:
            flagged.setdefault(name, reached)
        foreign = defined_in[str(obj)] & (others or {}).get(name, set())
        if foreign:
            flagged.setdefault(name, "defines functions of another exercise file ("
                               + ", ".join(demangle(foreign)[:3]) + "); each exercise is graded in its own file")
    for name, why in flagged.items():
        notes.append(replaced_note(name, why, exercises_in(lab.solution / name),
                                   name in {p.name for p in lab.skeleton.iterdir()}))
    return sorted(flagged)
