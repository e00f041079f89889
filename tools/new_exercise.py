#!/usr/bin/env python3
"""Scaffold a new exercise in a lab: every piece an exercise needs, consistent from the start
(the reference scores 100 %, the skeleton 0, labs/ fresh, handout and manifest agree), so
the course author only replaces the placeholders marked TODO(author).

    tools/new_exercise.py LAB NAME [--title TITLE]      e.g.  tools/new_exercise.py rope drag_force

LAB is a lab's name (rope) or folder (01_rope); NAME a snake_case function name. Written
(<dir> is the lab's folder, 01_rope; <lab> its name, rope):
  solutions/<dir>/<name>.cpp            the reference, marked BEGIN/END EXERCISE <id>; it
                                        includes <springlab/<lab>/exercises.hpp>
  framework/labs/<lab>/include/springlab/<lab>/exercises.hpp
                                        + the function's declaration, after the last exercise
  tests/<dir>/public/<name>_test.cpp    a public test (1 point)
  tests/<dir>/hidden/<name>_test.cpp    a hidden test against the reference (1 point)
  tests/<dir>/exercises.json            + the exercise and its two tests
  handouts/<dir>.md                     + the exercise's section; the lab's total updated
  labs/<dir>/                           regenerated (tools/make_skeleton.py): the stub, the copy
                                        of exercises.hpp, README.md
The lab's given code (framework/labs/<lab>/src/) is not touched: if the simulation is to use
the new function, call it there yourself. See handouts/authoring.md for the whole routine.
"""
import argparse
import json
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tools"))
import grade  # noqa: E402
import make_skeleton  # noqa: E402


class ScaffoldError(Exception):
    pass


def find_lab(which):
    labs = re.findall(r"^\s*springlab_add_lab\(\s*NAME\s+(\w+)\s+DIR\s+(\w+)\s*\)", (ROOT / "CMakeLists.txt").read_text(),
                      re.M)
    for name, folder in labs:
        if which in (name, folder):
            return name, folder
    raise ScaffoldError(f"no lab '{which}' in CMakeLists.txt; labs: {', '.join(n for n, _ in labs) or 'none'}")


def camel(name, upper):
    words = name.split("_")
    text = "".join(w.capitalize() for w in words)
    return text if upper else text[0].lower() + text[1:]


def next_id(manifest, folder):
    ids = [ex["id"] for ex in manifest["exercises"]]
    major = ids[0].split(".")[0] if ids else str(int(folder.split("_")[0]))
    minors = [int(i.split(".")[1]) for i in ids if re.match(rf"^{major}\.\d+$", i)]
    return f"{major}.{max(minors, default=0) + 1}"


def scaffold(which, name, title):
    if not re.fullmatch(r"[a-z][a-z0-9]*(_[a-z0-9]+)*", name):
        raise ScaffoldError(f"NAME '{name}': use snake_case letters and digits, e.g. drag_force")
    lab, folder = find_lab(which)
    manifest_path = ROOT / "tests" / folder / "exercises.json"
    handout_path = ROOT / "handouts" / f"{folder}.md"
    header_path = exercises_header(lab)
    for path in (manifest_path, handout_path, header_path, ROOT / "solutions" / folder):
        if not path.exists():
            raise ScaffoldError(f"{path}: missing; every lab has it")
    try:
        manifest = grade.load_manifest(manifest_path)
    except grade.ManifestError as error:
        raise ScaffoldError(str(error)) from None
    ex_id = next_id(manifest, folder)
    func, suite = camel(name, False), camel(name, True)
    title = title or name.replace("_", " ")
    files = {
        ROOT / "solutions" / folder / f"{name}.cpp": SOLUTION,
        ROOT / "tests" / folder / "public" / f"{name}_test.cpp": PUBLIC,
        ROOT / "tests" / folder / "hidden" / f"{name}_test.cpp": HIDDEN,
    }
    for path in files:
        if path.exists():
            raise ScaffoldError(f"{path}: already exists; pick another NAME")
    if any(t["name"].split(".")[0] == suite for ex in manifest["exercises"] for t in ex["tests"]):
        raise ScaffoldError(f"{manifest_path}: a test suite named {suite} exists already; pick another NAME")
    values = dict(lab=lab, folder=folder, id=ex_id, func=func, suite=suite, title=title, file=f"{name}.cpp")

    # The declaration goes where the framework's exercise header ends its exercises: after the
    # last "// ---- Exercise" block, before the next "// ---- " block or the end of the lab's
    # namespace, whichever comes first.
    header = header_path.read_text()
    declaration = DECLARATION.format(**values, rule="-" * max(4, 80 - len(f"// ---- Exercise {ex_id}: {title} ")))
    marker = declaration_point(header, lab)
    if marker < 0:
        raise ScaffoldError(f"{header_path.relative_to(ROOT)}: cannot find where to declare {func} (no "
                            f"'}}  // namespace springlab::{lab}' line)")
    new_header = header[:marker] + declaration + "\n" + header[marker:]

    # The manifest: one more exercise, written in the file's own compact style.
    text = manifest_path.read_text()
    entry = (f',\n    {{"id": "{ex_id}", "title": {json.dumps(title)}, "tests": [\n'
             f'      {{"name": "{suite}.MatchesItsDefinition", "points": 1, "visibility": "visible"}},\n'
             f'      {{"name": "MatchesReference{suite}.OnRandomInputs", "points": 1, "visibility": "hidden"}}\n'
             f'    ]}}')
    new_text, count = re.subn(r"(\]\s*\})(\s*\]\s*\}\s*)$", lambda m: m.group(1) + entry + m.group(2), text)
    if count != 1:
        raise ScaffoldError(f"{manifest_path}: cannot find the end of the exercises list to append to")
    json.loads(new_text)

    # The handout: the section after the last exercise's, and the lab's new total.
    handout = handout_path.read_text()
    old_total, new_total = manifest["points"], manifest["points"] + 2
    headings = [m for m in re.finditer(r"^### Exercise .*$", handout, re.M)]
    after = re.search(r"^## ", handout[headings[-1].end():], re.M) if headings else None
    at = headings[-1].end() + after.start() if after else len(handout)
    section = HANDOUT.format(**values)
    new_handout = handout[:at] + section + "\n" + handout[at:]
    new_handout = new_handout.replace(f"**{old_total:g} points**", f"**{new_total:g} points**")
    if f"{new_total:g} points" not in new_handout:
        new_handout = new_handout.replace(f"{old_total:g} points", f"{new_total:g} points", 1)

    for path, template in files.items():
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(template.format(**values))
    header_path.write_text(new_header)
    manifest_path.write_text(new_text)
    handout_path.write_text(new_handout)
    try:
        generated = make_skeleton.generate(folder)
    except make_skeleton.SkeletonError as error:
        raise ScaffoldError(f"regenerating labs/{folder}: {error}") from None
    changed = []
    for path, body in generated.items():
        if not path.exists() or path.read_text() != body:
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(body)
            changed.append(path)
    return ex_id, [*files, header_path, manifest_path, handout_path, *changed]


def declaration_point(header, lab):
    """Where a new exercise's declaration goes in the lab's exercise header: the offset of the
    line that follows the last exercise's block, or -1."""
    end = header.rfind(f"}}  // namespace springlab::{lab}")
    if end < 0:
        return -1
    exercises = list(re.finditer(r"^// ---- Exercise .*$", header[:end], re.M))
    if not exercises:
        return end
    after = re.search(r"^// ---- ", header[exercises[-1].end():end], re.M)
    return exercises[-1].end() + after.start() if after else end


def exercises_header(lab):
    """The framework's header that declares a lab's exercises (the student's contract)."""
    return ROOT / "framework" / "labs" / lab / "include" / "springlab" / lab / "exercises.hpp"


DECLARATION = """// ---- Exercise {id}: {title} {rule}
// TODO(author): the formula students implement, with units.
Vec3 {func}(const Vec3& x, double k);
"""

SOLUTION = """#include <springlab/{lab}/exercises.hpp>

namespace springlab::{lab} {{

Vec3 {func}(const Vec3& x, double k) {{
  // BEGIN EXERCISE {id}
  // TODO(author): the reference answer, one short comment above each step.
  return -k * x;
  // END EXERCISE {id}
}}

}}  // namespace springlab::{lab}
"""

PUBLIC = """// Exercise {id}: {title}. TODO(author): checks of the physics, each named after it.
#include <gtest/gtest.h>

#include <algorithm>

#include <springlab/{lab}/{lab}.hpp>
#include "seeded.hpp"

namespace springlab::{lab} {{
namespace {{

using {suite} = springlab::testing::Seeded;

TEST_F({suite}, MatchesItsDefinition) {{
  for (int trial = 0; trial < 100; ++trial) {{
    const Vec3 x = vec3(-1, 1);
    const double k = uniform(1, 100);
    const Vec3 f = {func}(x, k);
    ASSERT_LT((f + k * x).norm(), 1e-9 * std::max(1.0, f.norm()))
        << "TODO(author): say in physics what is wrong, never the expected number " << seedText();
  }}
}}

}}  // namespace
}}  // namespace springlab::{lab}
"""

HIDDEN = """// Hidden test of exercise {id}: the student's {func} against the reference on random inputs.
// The message names the inputs, never the reference's answer.
#include <gtest/gtest.h>

#include <springlab/{lab}/{lab}.hpp>
#include "oracle_{lab}.hpp"  // generated by tests/CMakeLists.txt from the framework's lab headers
#include "seeded.hpp"

namespace springlab::{lab} {{
namespace {{

using MatchesReference{suite} = springlab::testing::Seeded;

TEST_F(MatchesReference{suite}, OnRandomInputs) {{
  for (int trial = 0; trial < 500; ++trial) {{
    const Vec3 x = vec3(-2, 2);
    const double k = uniform(1, 1e4);
    ASSERT_LT(springlab::testing::relativeError({func}(x, k), springlab::{lab}_reference::{func}(x, k)), 1e-9)
        << "{title} is wrong for x = (" << x.x() << ", " << x.y() << ", " << x.z() << "), k = " << k << " "
        << seedText();
  }}
}}

}}  // namespace
}}  // namespace springlab::{lab}
"""

HANDOUT = """### Exercise {id}: {title} (2 points)

File `labs/{folder}/{file}`, function `{func}` (declared in `exercises.hpp`). TODO(author): what
to compute, the section of the physics it builds on, and what to watch out for.

Public tests:
- `{suite}.MatchesItsDefinition`: TODO(author): what it checks, in physics terms.

Hidden: `MatchesReference{suite}.OnRandomInputs` (1 point).
"""


def main():
    ap = argparse.ArgumentParser(prog="springlab new-exercise", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("lab", help="the lab's name or folder (rope, 01_rope)")
    ap.add_argument("name", help="snake_case name of the function and its file (drag_force)")
    ap.add_argument("--title", help="the exercise's title in the handout and the reports")
    args = ap.parse_args()
    try:
        ex_id, written = scaffold(args.lab, args.name, args.title)
    except ScaffoldError as error:
        print(f"springlab new-exercise: {error}", file=sys.stderr)
        return 2
    print(f"exercise {ex_id} scaffolded; written or updated:")
    for path in written:
        print(f"  {path.relative_to(ROOT)}")
    lab, _ = find_lab(args.lab)
    print(f"next: replace each TODO(author); if the simulation is to use the function, call it from the lab's "
          f"given code in framework/labs/{lab}/src/; then `./springlab test` (see handouts/authoring.md)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
