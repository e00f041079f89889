#!/usr/bin/env python3
"""Which exercises of each lab are not written yet: the summary `./springlab test` prints
after ctest in a student tree.

    tools/missing_exercises.py [ROOT]

An exercise is missing while its file in labs/<lab>/ still holds the skeleton's stub, the
line `throw springlab::NotImplemented("ID", "TITLE", ...)` that tools/make_skeleton.py wrote
in place of the body (the same exception the viewer and `sim` name on screen). Prints one
line per lab; exits 0 (it reports, it does not judge).
"""
import json
import pathlib
import re
import sys

STUB = re.compile(r'throw\s+springlab::NotImplemented\(\s*"([^"]+)"\s*,\s*"([^"]*)"')


def id_key(exercise_id):
    return [int(p) if p.isdigit() else p for p in re.split(r"[.]", exercise_id)]


def lab_title(root, lab_dir):
    manifest = root / "tests" / lab_dir.name / "exercises.json"
    try:
        return json.loads(manifest.read_text())["title"]
    except (OSError, ValueError, KeyError):
        return lab_dir.name


def missing(lab_dir):
    """{id: (title, [files])} of the stubs left in the lab's exercise files."""
    found = {}
    for source in sorted(lab_dir.glob("*.cpp")):
        for exercise_id, title in STUB.findall(source.read_text(errors="replace")):
            found.setdefault(exercise_id, (title, []))[1].append(source.name)
    return found


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent)
    labs = sorted(d for d in (root / "labs").glob("0*") if d.is_dir())
    if not labs:
        print(f"missing_exercises: no labs/ folder under {root}", file=sys.stderr)
        return 0
    print("exercises not written yet (their files still throw NotImplemented):")
    for lab_dir in labs:
        stubs = missing(lab_dir)
        title = lab_title(root, lab_dir)
        if not stubs:
            print(f"  {title}: none, every exercise is written")
            continue
        print(f"  {title}: {len(stubs)} missing")
        for exercise_id in sorted(stubs, key=id_key):
            name, files = stubs[exercise_id]
            print(f"    {exercise_id} {name} (labs/{lab_dir.name}/{', '.join(sorted(set(files)))})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
