#!/usr/bin/env python3
"""What a lab's handout says about points, against the manifest (tests/<dir>/exercises.json),
the one place points are declared. Read from the handout:

  - each exercise heading   `### Exercise 1.9: elastic energy (4 points)`   ("1 point" too)
  - the grading table       `| id | title | points | public tests | hidden tests |`, a row per
                            exercise (`| 1.9 | elastic energy | 4 | 1 test, 2 points | 1 test, 2 points |`)
                            and its total row (`| | **total** | **54** | ... | ... |`)
  - every "worth N points" sentence (the lab's total, or an exercise's when the sentence names one)
  - every "in N exercises" count, and "N from the public tests" / "N from hidden tests"
  - each "`Suite.Test` (N points)" that names a test of the manifest

Each disagreement is reported as `FILE:LINE: the handout says X; the manifest (PATH) says Y`.
tools/new_exercise.py uses sync_totals() to rewrite the lab-wide numbers after adding a row.

    tools/handout_check.py tests/01_rope/exercises.json handouts/01_rope.md
"""
import pathlib
import re
import sys

NUMBER_WORDS = ["zero", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten",
                "eleven", "twelve", "thirteen", "fourteen", "fifteen", "sixteen", "seventeen", "eighteen",
                "nineteen", "twenty"]
NUM = r"\d+(?:\.\d+)?"
HEADING = re.compile(rf"^### Exercise (\S+): (.*?) \(({NUM}) points?\)\s*$")
ANY_HEADING = re.compile(r"^### Exercise (\S+?):?\s")
WORTH = re.compile(rf"worth\s+\**({NUM})\s+points?\**")
IN_EXERCISES = re.compile(r"\bin\s+(\w+)\s+exercises\b")
FROM_PUBLIC = re.compile(rf"\b({NUM})\s+(?:points\s+)?from\s+(?:the\s+)?public\s+tests\b")
FROM_HIDDEN = re.compile(rf"\b({NUM})\s+(?:points\s+)?from\s+(?:the\s+)?hidden\s+tests\b")
TEST_POINTS = re.compile(rf"`(\w+\.\w+)`\s+\(({NUM})\s+points?[:)]")
TABLE_HEADER = re.compile(r"^\|\s*id\s*\|\s*title\s*\|\s*points\s*\|", re.I)
TESTS_CELL = re.compile(rf"^(\d+)\s+tests?,\s+({NUM})\s+points?$")


def fmt(x):
    return f"{x:g}"


def points_text(n):
    return f"{fmt(n)} point" if n == 1 else f"{fmt(n)} points"


def tests_text(count, points):
    return f"{count} test{'' if count == 1 else 's'}, {points_text(points)}"


def count_word(n):
    return NUMBER_WORDS[n] if n < len(NUMBER_WORDS) else str(n)


def parse_count(word):
    word = word.lower()
    if word.isdigit():
        return int(word)
    return NUMBER_WORDS.index(word) if word in NUMBER_WORDS else None


def split_tests(ex):
    """(count, points) of an exercise's visible tests and of its other (hidden) tests."""
    public = [t for t in ex["tests"] if t["visibility"] == "visible"]
    hidden = [t for t in ex["tests"] if t["visibility"] != "visible"]
    return (len(public), sum(t["points"] for t in public)), (len(hidden), sum(t["points"] for t in hidden))


def totals(manifest):
    pub = [split_tests(ex)[0] for ex in manifest["exercises"]]
    hid = [split_tests(ex)[1] for ex in manifest["exercises"]]
    return (sum(c for c, _ in pub), sum(p for _, p in pub)), (sum(c for c, _ in hid), sum(p for _, p in hid))


def line_of(text, offset):
    return text.count("\n", 0, offset) + 1


def table_cells(line):
    return [c.strip() for c in line.strip().strip("|").split("|")]


def find_table(lines):
    """(index of the header line, column names, [(index, cells)] of the rows) or None."""
    for i, line in enumerate(lines):
        if TABLE_HEADER.match(line):
            columns = [c.lower() for c in table_cells(line)]
            rows, j = [], i + 2
            while j < len(lines) and lines[j].startswith("|"):
                rows.append((j, table_cells(lines[j])))
                j += 1
            return i, columns, rows
    return None


def bare(cell):
    return cell.replace("*", "").strip()


def sentence_exercise(text, offset):
    """The exercise id a sentence names before `offset`, if any ("Exercise 2.10 is worth ...")."""
    start = max(text.rfind(". ", 0, offset), text.rfind(".\n", 0, offset), text.rfind("\n\n", 0, offset)) + 1
    named = re.findall(r"[Ee]xercise (\d+\.\d+)", text[start:offset])
    return named[-1] if named else None


def check_handout(manifest, handout_path, manifest_path=None, shown=None):
    """Every place the handout states points or counts that disagrees with the manifest
    (`shown`: the handout's name in the messages, default its path)."""
    try:
        text = pathlib.Path(handout_path).read_text()
    except OSError as error:
        return [f"{shown or handout_path}: cannot read: {error.strerror}"]
    path = shown or pathlib.Path(handout_path)
    mpath = manifest_path or manifest.get("handout", "the manifest").replace("handouts/", "tests/").replace(
        ".md", "/exercises.json")
    lines = text.splitlines()
    problems = []

    def say(number, what, wanted):
        problems.append(f"{path}:{number}: {what}; the manifest ({mpath}) says {wanted}")

    exercises = {ex["id"]: ex for ex in manifest["exercises"]}
    (pub_count, pub_points), (hid_count, hid_points) = totals(manifest)

    # Exercise headings: one per exercise, title and points as in the manifest.
    seen, last_heading = {}, 1
    for number, line in enumerate(lines, start=1):
        m = HEADING.match(line)
        if not m:
            if ANY_HEADING.match(line):
                problems.append(f"{path}:{number}: '{line}' does not end with '(N points)' or '(1 point)'")
            continue
        ex_id, title, points = m.group(1), m.group(2), float(m.group(3))
        last_heading = number
        if ex_id not in exercises:
            say(number, f"heading of exercise {ex_id}", f"no exercise {ex_id}")
            continue
        seen[ex_id] = number
        ex = exercises[ex_id]
        if title != ex["title"]:
            say(number, f"exercise {ex_id} is titled '{title}'", f"'{ex['title']}'")
        if points != ex["points"]:
            say(number, f"exercise {ex_id} is worth {points_text(points)}", points_text(ex["points"]))
    for ex_id, ex in exercises.items():
        if ex_id not in seen:
            say(last_heading, f"no heading for exercise {ex_id} (expected '### Exercise {ex_id}: {ex['title']} "
                f"({points_text(ex['points'])})' among the exercise headings)", f"exercise {ex_id}")

    # The grading table: a row per exercise, and the total row.
    table = find_table(lines)
    if table is None:
        problems.append(f"{path}: no grading table ('| id | title | points | public tests | hidden tests |')")
    else:
        header, columns, rows = table
        col = {name: columns.index(name) for name in ("id", "title", "points", "public tests", "hidden tests")
               if name in columns}
        in_table, total_row = set(), None
        for index, cells in rows:
            number = index + 1
            cell = lambda name: bare(cells[col[name]]) if name in col and col[name] < len(cells) else ""  # noqa: E731
            ex_id = cell("id")
            if not ex_id:
                if "total" in cell("title").lower():
                    total_row = number
                    expected = {"points": fmt(manifest["points"]), "public tests": tests_text(pub_count, pub_points),
                                "hidden tests": tests_text(hid_count, hid_points)}
                    for name, wanted in expected.items():
                        if name in col and cell(name) != wanted:
                            say(number, f"the grading table's total {name} is '{cell(name)}'", f"'{wanted}'")
                continue
            if ex_id not in exercises:
                say(number, f"the grading table has a row for exercise {ex_id}", f"no exercise {ex_id}")
                continue
            in_table.add(ex_id)
            ex = exercises[ex_id]
            (pc, pp), (hc, hp) = split_tests(ex)
            expected = {"title": ex["title"], "points": fmt(ex["points"]), "public tests": tests_text(pc, pp),
                        "hidden tests": tests_text(hc, hp)}
            for name, wanted in expected.items():
                if name in col and cell(name) != wanted:
                    say(number, f"the grading table's {name} of exercise {ex_id} is '{cell(name)}'", f"'{wanted}'")
        for ex_id in exercises:
            if ex_id not in in_table:
                say(total_row or header + 1, f"the grading table has no row for exercise {ex_id}",
                    f"exercise {ex_id} ({points_text(exercises[ex_id]['points'])})")
        if total_row is None:
            say(header + 1, "the grading table has no total row ('| | **total** | ...')",
                f"a total of {points_text(manifest['points'])}")

    # Sentences: "worth N points", "in N exercises", "N from the public/hidden tests".
    for m in WORTH.finditer(text):
        said = float(m.group(1))
        ex_id = sentence_exercise(text, m.start())
        if ex_id in exercises:
            if said != exercises[ex_id]["points"]:
                say(line_of(text, m.start()), f"'{m.group(0)}' (exercise {ex_id})", points_text(exercises[ex_id]["points"]))
        elif said != manifest["points"]:
            say(line_of(text, m.start()), f"'{m.group(0)}'", f"the lab is worth {points_text(manifest['points'])}")
    for m in IN_EXERCISES.finditer(text):
        said = parse_count(m.group(1))
        if said is not None and said != len(exercises):
            say(line_of(text, m.start()), f"'{m.group(0)}'", f"{count_word(len(exercises))} exercises")
    for regex, wanted, kind in ((FROM_PUBLIC, pub_points, "public"), (FROM_HIDDEN, hid_points, "hidden")):
        for m in regex.finditer(text):
            if float(m.group(1)) != wanted:
                say(line_of(text, m.start()), f"'{' '.join(m.group(0).split())}'",
                    f"{points_text(wanted)} from the {kind} tests")

    # "`Suite.Test` (N points)": the test's own points.
    points_of = {t["name"]: t["points"] for ex in manifest["exercises"] for t in ex["tests"]}
    for m in TEST_POINTS.finditer(text):
        name, said = m.group(1), float(m.group(2))
        if name in points_of and said != points_of[name]:
            say(line_of(text, m.start()), f"`{name}` is worth {points_text(said)}", points_text(points_of[name]))
    return problems


def sync_totals(text, manifest):
    """The handout with every lab-wide number (total row, "worth N points" of the lab, "in N
    exercises", "N from the public/hidden tests") rewritten from the manifest. Exercise rows
    and headings are left alone: those the author (or new_exercise.py) writes."""
    (pub_count, pub_points), (hid_count, hid_points) = totals(manifest)
    exercises = {ex["id"] for ex in manifest["exercises"]}

    def worth(m):
        if sentence_exercise(text, m.start()) in exercises:
            return m.group(0)
        stars = "**" if m.group(0).endswith("**") else ""
        return f"worth {stars}{points_text(manifest['points'])}{stars}"

    def count(m):
        return m.group(0) if parse_count(m.group(1)) is None else f"in {count_word(len(exercises))} exercises"

    text = WORTH.sub(worth, text)
    text = IN_EXERCISES.sub(count, text)
    text = FROM_PUBLIC.sub(lambda m: m.group(0).replace(m.group(1), fmt(pub_points), 1), text)
    text = FROM_HIDDEN.sub(lambda m: m.group(0).replace(m.group(1), fmt(hid_points), 1), text)
    lines = text.split("\n")
    table = find_table(lines)
    if table:
        _, columns, rows = table
        for index, cells in rows:
            if "id" in columns and not bare(cells[columns.index("id")]) and "title" in columns \
                    and "total" in bare(cells[columns.index("title")]).lower():
                values = {"points": f"**{fmt(manifest['points'])}**", "public tests": tests_text(pub_count, pub_points),
                          "hidden tests": tests_text(hid_count, hid_points)}
                for name, value in values.items():
                    if name in columns and columns.index(name) < len(cells):
                        cells[columns.index(name)] = value
                lines[index] = "| " + " | ".join(cells) + " |"
                lines[index] = lines[index].replace("|  |", "| |")
    return "\n".join(lines)


def main():
    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
    from springlab_grader.manifest import ManifestError, load_manifest
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    try:
        manifest = load_manifest(sys.argv[1])
    except ManifestError as error:
        print(error, file=sys.stderr)
        return 2
    problems = check_handout(manifest, sys.argv[2], sys.argv[1])
    for p in problems:
        print(p, file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
