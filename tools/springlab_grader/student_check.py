"""The call check of `check` (tools/grade.py), the same as `grade`'s (call_check.py): the
exercise objects of a student's own build are read for calls exercise code never needs, and a
file that makes one is reported with the sentence `grade` prints, its exercises' tests failed
as `grade` fails them. So a student learns the rule from `check`, never from a lost grade."""
import pathlib
import re

from . import call_check
from .student_build import exercise_compiles

_TABLE_ROW = re.compile(r"^\|\s*(\d+\.\d+)\s*\|[^|]*\|\s*`([^`]+\.cpp)`\s*\|", re.M)


def exercise_objects(binary):
    """{exercise file: its object} of the lab a grading program of a build was linked from
    (<build>/tests/<lab>_grading_<student|reference>: the compile commands of
    springlab_<lab>_student_objects or _solution_objects); {} when they cannot be found."""
    binary = pathlib.Path(binary)
    match = re.fullmatch(r"(\w+)_grading_(student|reference)", binary.name)
    if not match:
        return {}
    compiles = exercise_compiles(binary.parent.parent, match[1], match[2])
    return {name: c.output for name, c in compiles.items() if c.output.is_file()}


def exercises_by_file(tree, lab_dir):
    """{exercise file: [exercise ids]}: from the reference's markers in an instructor tree, else
    from the table of the lab folder's README (tools/make_skeleton.py writes it)."""
    solutions = pathlib.Path(tree) / "solutions" / lab_dir
    if solutions.is_dir():
        from .labs import exercises_in  # the instructor's side only
        return {p.name: exercises_in(p) for p in sorted(solutions.glob("*.cpp"))}
    readme = pathlib.Path(tree) / "labs" / lab_dir / "README.md"
    table = {}
    for exercise, file in _TABLE_ROW.findall(readme.read_text() if readme.is_file() else ""):
        table.setdefault(file, []).append(exercise)
    return table


def forbidden_call_notes(binary, tree, lab_dir, skip=()):
    """{exercise file: (the note grade prints, its exercise ids)} of the files that call what
    exercise code may not (`skip`: files not to read, such as those that did not compile)."""
    objects = {name: obj for name, obj in exercise_objects(binary).items() if name not in skip}
    if not objects:
        return {}
    undefined = call_check.symbols_by_file(list(objects.values()), undefined=True)
    exercises = exercises_by_file(tree, lab_dir)
    flagged = {}
    for name, obj in sorted(objects.items()):
        why = call_check.forbidden_call_reason(undefined[str(obj)])
        if why:
            flagged[name] = (call_check.replaced_note(name, why, exercises.get(name, [])), exercises.get(name, []))
    return flagged
