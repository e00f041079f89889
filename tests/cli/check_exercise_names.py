#!/usr/bin/env python3
"""Names lead: from each lab's manifest (tests/NN_<id>/exercises.json), every exercise's files
are where its name says, so a newcomer finds them without searching:

  skeleton      labs/<folder>/<file>, the stub of the exercise (instructor tree: it still throws
                NotImplemented for it)
  reference     solutions/<folder>/<file>, marked BEGIN EXERCISE <id> (instructor tree)
  public test   tests/<folder>/public/<stem>_test.cpp, holding exactly the exercise's public tests
  caller        the manifest's "caller" FILE:Class::function: the file defines it and calls one
                of the exercise's functions
  declarations  each of the manifest's "functions" is declared so in the lab's exercises.hpp
  handout       the manifest's "section" is a heading of the lab's handout; the handout has an
                "### Exercise <id>: ..." heading, and no other heading numbered like an exercise
                (the physics sections are lettered: 2.a, 2.b)

and the table of handouts/authoring.md ("Where each exercise lives") is the manifests' own.

    check_exercise_names.py ROOT           check; every problem named, exit 1 if any
    check_exercise_names.py ROOT --table   print the table for handouts/authoring.md
"""
import json
import pathlib
import re
import sys

TABLE_HEADING = "### Where each exercise lives"


def manifests(root):
    for path in sorted((root / "tests").glob("[0-9][0-9]_*/exercises.json")):
        yield path, json.loads(path.read_text())


def flat(text):
    """C++ text without comments, in single spaces."""
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    return " ".join(re.sub(r"//[^\n]*", " ", text).split())


def tests_in(path):
    return set(f"{s}.{n}" for s, n in re.findall(r"^TEST(?:_F)?\((\w+), (\w+)\)", path.read_text(), re.M))


def table(root):
    rows = ["| id | skeleton | reference | public test | given caller | handout section |",
            "|---|---|---|---|---|---|"]
    for _, m in manifests(root):
        folder = m["folder"]
        for ex in m["exercises"]:
            stem = ex["file"][:-len(".cpp")]
            caller_file, _, caller_function = ex["caller"].partition(":")
            rows.append(f"| {ex['id']} | `labs/{folder}/{ex['file']}` | `solutions/{folder}/{ex['file']}` | "
                        f"`tests/{folder}/public/{stem}_test.cpp` | `{caller_file.removeprefix('framework/labs/')}`: "
                        f"`{caller_function}` | {m['handout']}: {ex['section']}; Exercise {ex['id']} |")
    return rows


def problems(root):
    found = []
    instructor = (root / "solutions").is_dir()
    for path, m in manifests(root):
        folder, lab = m["folder"], m["lab"]
        where = path.relative_to(root)
        header_path = root / "framework" / "labs" / lab / "include" / "springlab" / lab / "exercises.hpp"
        if not header_path.exists():
            found.append(f"{where}: lab {lab}: no {header_path.relative_to(root)}")
            continue
        header = flat(header_path.read_text())
        handout_path = root / m["handout"]
        headings = {line.lstrip("#").strip() for line in handout_path.read_text().splitlines()
                    if line.startswith("#")} if handout_path.exists() else set()
        if not headings:
            found.append(f"{where}: handout {m['handout']}: missing")
        for heading in sorted(headings):
            if re.match(r"^\d+\.\d+\b", heading):
                found.append(f"{m['handout']}: heading '{heading}' is numbered like an exercise; letter the "
                             f"sections of the physics ({heading.split('.')[0]}.a, {heading.split('.')[0]}.b, ...)")
        for ex in m["exercises"]:
            name = f"{where}: exercise {ex['id']}"
            stem = ex["file"][:-len(".cpp")]
            skeleton = root / "labs" / folder / ex["file"]
            if not skeleton.exists():
                found.append(f"{name}: no skeleton labs/{folder}/{ex['file']}")
            elif instructor and f'NotImplemented("{ex["id"]}"' not in skeleton.read_text():
                found.append(f"{name}: labs/{folder}/{ex['file']} is not its stub (no NotImplemented(\"{ex['id']}\"))")
            reference = root / "solutions" / folder / ex["file"]
            if instructor and (not reference.exists() or f"// BEGIN EXERCISE {ex['id']}\n" not in reference.read_text()):
                found.append(f"{name}: solutions/{folder}/{ex['file']} does not mark BEGIN EXERCISE {ex['id']}")
            test = root / "tests" / folder / "public" / f"{stem}_test.cpp"
            public = {t["name"] for t in ex["tests"] if t["visibility"] == "visible"}
            if not test.exists():
                found.append(f"{name}: no public test file tests/{folder}/public/{stem}_test.cpp")
            elif tests_in(test) != public:
                found.append(f"{name}: tests/{folder}/public/{stem}_test.cpp holds "
                             f"{sorted(tests_in(test))}, but the exercise's public tests are {sorted(public)}")
            caller_file, _, caller_function = ex["caller"].partition(":")
            caller = root / caller_file
            function = caller_function.split("::")[-1]
            text = flat(caller.read_text()) if caller.exists() else ""
            if not text:
                found.append(f"{name}: caller {ex['caller']}: no file {caller_file}")
            elif not re.search(rf"\b{re.escape(caller_function if '::' in caller_function else function)}\s*\(", text) and \
                    not (re.search(rf"\b(class|struct) {caller_function.split('::')[0]}\b", text)
                         and re.search(rf"\b{function}\s*\(", text)):
                found.append(f"{name}: caller {ex['caller']}: {caller_file} does not define {caller_function}")
            elif not any(re.search(rf"\b{re.escape(d.split('(')[0].split()[-1])}\s*\(", text) for d in ex["functions"]):
                found.append(f"{name}: caller {ex['caller']}: calls none of the exercise's functions")
            for declaration in ex["functions"]:
                if " ".join(declaration.split()) + ";" not in header:
                    found.append(f"{name}: `{declaration}` is not declared so in {header_path.relative_to(root)}")
            if ex["section"] not in headings:
                found.append(f"{name}: section '{ex['section']}' is not a heading of {m['handout']}")
            if not any(h.startswith(f"Exercise {ex['id']}: ") for h in headings):
                found.append(f"{name}: {m['handout']} has no heading 'Exercise {ex['id']}: ...'")
    authoring = root / "handouts" / "authoring.md"
    if authoring.exists():
        text = authoring.read_text().splitlines()
        missing = [row for row in table(root) if row not in text]
        if TABLE_HEADING not in text or missing:
            found.append(f"handouts/authoring.md: the table under '{TABLE_HEADING}' is not the manifests' "
                         f"(first differing row: {missing[0] if missing else 'no heading'}); replace it with the "
                         f"output of tests/cli/check_exercise_names.py . --table")
    return found


def main():
    root = pathlib.Path(sys.argv[1]).resolve()
    if "--table" in sys.argv[2:]:
        print("\n".join(table(root)))
        return 0
    found = problems(root)
    for problem in found:
        print(problem)
    count = sum(len(m["exercises"]) for _, m in manifests(root))
    print(f"{len(found)} problem(s)" if found else f"every exercise's files follow its name ({count} exercises)")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
