#!/usr/bin/env python3
"""Generate the student skeleton labs/ from the reference solutions/ (the single source).

Inside solutions/, each exercise body is marked:

    // BEGIN EXERCISE 1.1
    ...reference code...
    // END EXERCISE 1.1

In labs/ that body becomes a TODO naming the exercise and its handout section, followed by
a stub that compiles and throws springlab::NotImplemented. Lines written `// STUB: code`
inside a block are comments in the reference and become `code` in the skeleton, before the
throw. Files without markers are copied as they are. Titles and handout paths come from
tests/<lab>/exercises.json.

    tools/make_skeleton.py            regenerate labs/ for every lab
    tools/make_skeleton.py --check    exit 1 and name the stale files if labs/ differs
"""
import argparse
import json
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
BEGIN = re.compile(r"^(\s*)// BEGIN EXERCISE (\S+)\s*$")
END = re.compile(r"^\s*// END EXERCISE (\S+)\s*$")
STUB = re.compile(r"^\s*// STUB: ?(.*)$")


class SkeletonError(Exception):
    pass


def load_exercises(lab):
    manifest = ROOT / "tests" / lab / "exercises.json"
    if not manifest.exists():
        raise SkeletonError(f"{manifest}: missing (every lab declares its exercises there)")
    data = json.loads(manifest.read_text())
    return data["handout"], {e["id"]: e for e in data["exercises"]}


def skeleton_of(path, text, handout, exercises):
    """Return the skeleton text of one source file, and the exercise ids it contains."""
    out, seen, block = [], [], None
    for number, line in enumerate(text.splitlines(keepends=True), start=1):
        begin, end = BEGIN.match(line), END.match(line)
        if block is None:
            if end:
                raise SkeletonError(f"{path}:{number}: END EXERCISE without BEGIN")
            if not begin:
                out.append(line)
                continue
            indent, ex_id = begin.group(1), begin.group(2)
            if ex_id not in exercises:
                raise SkeletonError(f"{path}:{number}: exercise {ex_id} is not declared in tests/*/exercises.json")
            block = (indent, ex_id, number, [])
            continue
        indent, ex_id, start, stubs = block
        if begin:
            raise SkeletonError(f"{path}:{number}: BEGIN EXERCISE inside exercise {ex_id} (line {start})")
        if end:
            if end.group(1) != ex_id:
                raise SkeletonError(f"{path}:{number}: END EXERCISE {end.group(1)} closes exercise {ex_id}")
            title = exercises[ex_id]["title"]
            where = f"{handout}, section Exercise {ex_id}"
            out.append(f"{indent}// TODO exercise {ex_id} ({title}): write this part; see {where}.\n")
            out.extend(f"{indent}{s}\n" for s in stubs)
            out.append(f'{indent}throw springlab::NotImplemented("{ex_id}", "{title}", "{where}");\n')
            seen.append(ex_id)
            block = None
            continue
        stub = STUB.match(line)
        if stub:
            stubs.append(stub.group(1))
    if block is not None:
        raise SkeletonError(f"{path}:{block[2]}: exercise {block[1]} is never closed by END EXERCISE")
    return "".join(out), seen


def generate(lab):
    """Map each labs/<lab>/ path to the text it must have."""
    handout, exercises = load_exercises(lab)
    source = ROOT / "solutions" / lab
    files, found = {}, set()
    for path in sorted(p for p in source.rglob("*") if p.is_file()):
        text, seen = skeleton_of(path.relative_to(ROOT), path.read_text(), handout, exercises)
        found.update(seen)
        files[ROOT / "labs" / lab / path.relative_to(source)] = text
    missing = sorted(set(exercises) - found)
    if missing:
        raise SkeletonError(f"solutions/{lab}: exercises declared but never marked: {', '.join(missing)}")
    return files


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--check", action="store_true", help="only check that labs/ is up to date")
    parser.add_argument("labs", nargs="*", help="labs to process (default: every folder of solutions/)")
    args = parser.parse_args()
    labs = args.labs or sorted(p.name for p in (ROOT / "solutions").iterdir() if p.is_dir())
    stale = []
    try:
        for lab in labs:
            wanted = generate(lab)
            present = {p for p in (ROOT / "labs" / lab).rglob("*") if p.is_file()} if (ROOT / "labs" / lab).exists() else set()
            for path, text in wanted.items():
                if not path.exists() or path.read_text() != text:
                    stale.append(path)
                    if not args.check:
                        path.parent.mkdir(parents=True, exist_ok=True)
                        path.write_text(text)
            for path in sorted(present - set(wanted)):
                stale.append(path)
                if not args.check:
                    path.unlink()
    except SkeletonError as error:
        print(f"make_skeleton: {error}", file=sys.stderr)
        return 2
    if args.check and stale:
        print("labs/ is stale; run tools/make_skeleton.py and commit the result. Differs:", file=sys.stderr)
        for path in stale:
            print(f"  {path.relative_to(ROOT)}", file=sys.stderr)
        return 1
    verb = "would update" if args.check else "updated"
    print(f"make_skeleton: {len(stale)} file(s) {verb}" if stale else "make_skeleton: labs/ is up to date")
    return 0


if __name__ == "__main__":
    sys.exit(main())
