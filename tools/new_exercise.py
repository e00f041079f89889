#!/usr/bin/env python3
"""Scaffold a new exercise in a lab: every piece an exercise needs, consistent from the start
(the reference scores 100 %, the skeleton 0, labs/ fresh, handout and manifest agree on every
heading, row, total and count), so the course author writes only the physics. What only the
author can write is marked with the placeholder `TODO(author)`, and `./springlab author-check`
fails (FILE:LINE) until none is left.

    tools/new_exercise.py LAB NAME [--title TITLE] [--points N] [--signature "DECLARATION"]

    tools/new_exercise.py rope elastic_energy --title "elastic energy" --points 4 \\
        --signature "double elasticEnergy(const Vec3& x1, const Vec3& x2, double k, double L0)"

LAB is a lab's name (rope, net, softbody) or folder (01_rope, 02_net, 03_softbody); NAME the
snake_case name of the exercise's file. --signature is the C++ declaration (default
`Vec3 <camelName>(const Vec3& x, double k)`): the header, the reference, the stub and both
tests use it from the start, with random inputs for parameters of type double, int, bool, Vec3
and std::vector<Vec3> (any other type gets a placeholder). --points N (default 2) splits N
between the public test (N - N/2) and the hidden one (N/2). Written (<dir> = 01_rope, <lab> = rope):

  framework/labs/<lab>/include/springlab/<lab>/exercises.hpp   + the declaration, after the last exercise
  solutions/<dir>/<NAME>.cpp               the reference, marked BEGIN/END EXERCISE <id>
  tests/<dir>/public/<NAME>_test.cpp       public test <Suite>.<Test>
  tests/<dir>/hidden/<NAME>_test.cpp       hidden test MatchesReference.<Suite> (the lab's
                                           hidden suite, fixture in tests/support/<lab>_fixtures.hpp)
  tests/<dir>/exercises.json               + the exercise and its two tests
  handouts/<dir>.md                        + the section, the grading table's row; the table's
                                           total, "worth N points" and "in N exercises" updated
  labs/<dir>/                              regenerated (tools/make_skeleton.py)

The lab's given code (framework/labs/<lab>/src/) is not touched: to have the simulation use the
function, call it there. See handouts/authoring.md for the whole routine.
"""
import argparse
import json
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tools"))
import handout_check  # noqa: E402
import make_skeleton  # noqa: E402
from springlab_grader import labs  # noqa: E402
from springlab_grader.errors import GradeError  # noqa: E402
from springlab_grader.manifest import ManifestError, load_manifest  # noqa: E402

# Written split so that this tool is not itself a leftover placeholder (tools/author_check.py).
TODO = "TODO" + "(author)"


class ScaffoldError(Exception):
    pass


def find_lab(which):
    """(id, folder) of the lab a user named (its id, or its folder), from the manifests."""
    try:
        lab = labs.find_lab(labs.discover_labs(ROOT), which)
    except GradeError as error:
        raise ScaffoldError(str(error)) from None
    return lab.name, lab.dir


def camel(name, upper):
    text = "".join(w.capitalize() for w in name.split("_"))
    return text if upper else text[0].lower() + text[1:]


def next_id(manifest, folder):
    ids = [ex["id"] for ex in manifest["exercises"]]
    major = ids[0].split(".")[0] if ids else str(int(folder.split("_")[0]))
    minors = [int(i.split(".")[1]) for i in ids if re.match(rf"^{major}\.\d+$", i)]
    return f"{major}.{max(minors, default=0) + 1}"


# ---- the signature: one declaration, read once, used by every generated file -----------------
class Param:
    def __init__(self, text):
        m = re.fullmatch(r"\s*(.+?)\s*\b([A-Za-z_]\w*)\s*", text)
        if not m or "=" in text:
            raise ScaffoldError(f"--signature: cannot read the parameter '{text.strip()}' (write 'TYPE name', "
                                f"no default values)")
        self.decl, self.name = m.group(1), m.group(2)
        self.output = "&" in self.decl and not re.search(r"\bconst\b", self.decl)
        self.type = re.sub(r"\bconst\b|&", "", self.decl).strip()
        self.type = re.sub(r"\s+", " ", self.type)


def split_params(text):
    parts, depth, current = [], 0, ""
    for ch in text:
        depth += ch in "<(["
        depth -= ch in ">)]"
        if ch == "," and depth == 0:
            parts.append(current)
            current = ""
        else:
            current += ch
    if current.strip() and current.strip() != "void":
        parts.append(current)
    return parts


class Signature:
    def __init__(self, text):
        m = re.fullmatch(r"\s*(.+?)\s*\b([A-Za-z_]\w*)\s*\((.*)\)\s*;?\s*", text, re.S)
        if not m:
            raise ScaffoldError(f"--signature '{text}': write a C++ declaration, e.g. "
                                f"\"double elasticEnergy(const Vec3& x1, const Vec3& x2, double k)\"")
        self.returns, self.func = re.sub(r"\s+", " ", m.group(1)), m.group(2)
        self.params = [Param(p) for p in split_params(m.group(3))]
        if self.returns.endswith("&"):
            raise ScaffoldError(f"--signature: return a value, not a reference ({self.returns})")
        names = [p.name for p in self.params]
        if len(set(names)) != len(names):
            raise ScaffoldError(f"--signature: a parameter name is used twice ({', '.join(names)})")
        self.text = f"{self.returns} {self.func}({', '.join(f'{p.decl} {p.name}' for p in self.params)})"


# How a test draws a random value of a type, and how it compares two results of it.
RANDOM = {"double": "uniform(0.1, 10)", "float": "static_cast<float>(uniform(0.1, 10))", "int": "integer(1, 10)",
          "bool": "integer(0, 1) == 1", "Vec3": "vec3(-1, 1)", "std::vector<Vec3>": "vec3s(integer(1, 20), -1, 1)"}
ERROR = {"double", "float", "Vec3", "std::vector<Vec3>"}   # relativeError(got, want)
EXACT = {"int", "bool"}                                     # ==
ZERO = {"Vec3": "Vec3::Zero()", "double": "0.0", "float": "0.0f", "int": "0", "bool": "false", "void": ""}


def lab_types(lab):
    """Types the lab's headers declare (they live in the oracle's renamed namespace too)."""
    folder = ROOT / "framework" / "labs" / lab / "include" / "springlab" / lab
    text = "".join(p.read_text() for p in folder.glob("*.hpp"))
    declared = re.findall(r"^\s*(?:struct|class|enum class|enum)\s+(\w+)|^\s*using\s+(\w+)\s*=", text, re.M)
    return {name for pair in declared for name in pair if name}


def reference_type(type_text, lab):
    """The oracle's spelling of a type: ref::T for the lab's own types, T for the framework's."""
    return re.sub(r"\b(\w+)\b", lambda m: f"ref::{m.group(1)}" if m.group(1) in lab_types(lab) else m.group(1),
                  type_text)


def inputs(sig, lab, hidden):
    """Lines declaring each parameter's value (random where the type allows), the student's and
    the reference's argument lists, and the outputs to compare after the call."""
    lines, mine, theirs, outputs = [], [], [], []
    for p in sig.params:
        if p.type in RANDOM and not p.output:
            lines.append(f"const {p.type} {p.name} = {RANDOM[p.type]};")
            mine.append(p.name)
            theirs.append(p.name)
            continue
        ref_type = reference_type(p.type, lab)
        value = f"{{}};  // {TODO}: give {p.name} a random value (the same for both calls)"
        if p.output:
            value = "{};" if p.type in RANDOM else value
            lines.append(f"{p.type} {p.name}{value}")
            mine.append(p.name)
            if hidden:
                lines.append(f"{ref_type} {p.name}Ref{{}};")
                theirs.append(f"{p.name}Ref")
                outputs.append(p)
        else:
            lines.append(f"const {p.type} {p.name}{value}")
            mine.append(p.name)
            if hidden:
                if ref_type != p.type:
                    lines.append(f"const {ref_type} {p.name}Ref{{}};  // {TODO}: the same value as {p.name}")
                    theirs.append(f"{p.name}Ref")
                else:
                    theirs.append(p.name)
    return lines, mine, theirs, outputs


def describe_inputs(sig):
    """The failure message's list of inputs: `"for x = " << describe(x) << ", k = " << describe(k)`."""
    shown = [p for p in sig.params if p.type in ("double", "float", "int", "Vec3") and not p.output]
    if not shown:
        return '"for the drawn inputs"'
    parts = []
    for i, p in enumerate(shown):
        parts.append(f'"{"for " if i == 0 else ", "}{p.name} = " << springlab::testing::describe({p.name})')
    return "\n    << ".join(parts)


def hidden_body(sig, lab, values):
    lines, mine, theirs, outputs = inputs(sig, lab, hidden=True)
    call, ref_call = f"{sig.func}({', '.join(mine)})", f"ref::{sig.func}({', '.join(theirs)})"
    what = f'"{values["title"]} differs from the reference "\n    << {describe_inputs(sig)} << " " << seedText()'
    checks = []
    if sig.returns == "void":
        lines += [f"{call};", f"{ref_call};"]
    elif sig.returns in ERROR:
        lines += [f"const {sig.returns} got = {call};", f"const {sig.returns} want = {ref_call};"]
        checks.append(f"ASSERT_LT(relativeError(got, want), kTolerance)\n    << {what};")
    elif sig.returns in EXACT:
        lines += [f"const {sig.returns} got = {call};", f"const {sig.returns} want = {ref_call};"]
        checks.append(f"ASSERT_TRUE(got == want)\n    << {what};")
    else:
        lines += [f"const auto got = {call};", f"const auto want = {ref_call};",
                  f"// {TODO}: compare got and want field by field (relativeError for numbers and vectors)",
                  "(void)got;", "(void)want;"]
    for p in outputs:
        if p.type in ERROR:
            checks.append(f"ASSERT_LT(relativeError({p.name}, {p.name}Ref), kTolerance)\n    << {what};")
        else:
            checks.append(f"// {TODO}: compare the output {p.name} with {p.name}Ref")
    if sig.returns == "void" and not outputs:
        checks.append(f"// {TODO}: compare what {sig.func} changed with what ref::{sig.func} changed")
    return lines + checks


def public_body(sig, lab, values):
    lines, mine, _, _ = inputs(sig, lab, hidden=False)
    call = f"{sig.func}({', '.join(mine)})"
    default = values["default_signature"]
    if default:
        lines += [f"const Vec3 f = {call};",
                  "ASSERT_LT((f + k * x).norm(), 1e-9 * std::max(1.0, f.norm()))",
                  f'    << "{TODO}: say in physics what is wrong, never the expected number " << seedText();']
    elif sig.returns in ("double", "float"):
        lines += [f"const double got = {call};",
                  f"// {TODO}: a check of the physics (a known case, a symmetry, a conservation law)",
                  'ASSERT_TRUE(std::isfinite(got)) << "not a finite number " << seedText();']
    elif sig.returns == "Vec3":
        lines += [f"const Vec3 got = {call};",
                  f"// {TODO}: a check of the physics (a known case, a symmetry, a conservation law)",
                  'ASSERT_TRUE(got.allFinite()) << "not finite " << seedText();']
    elif sig.returns == "void":
        lines += [f"{call};", f"// {TODO}: a check of the physics on what {sig.func} changed"]
    else:
        lines += [f"const auto got = {call};", f"// {TODO}: a check of the physics on got", "(void)got;"]
    return lines


def indent(lines, spaces):
    pad = " " * spaces
    return "\n".join(pad + line.replace("\n", "\n" + pad) if line else "" for line in lines)


def scaffold(which, name, title, points=2, signature=None):
    if not re.fullmatch(r"[a-z][a-z0-9]*(_[a-z0-9]+)*", name):
        raise ScaffoldError(f"NAME '{name}': use snake_case letters and digits, e.g. drag_force")
    if points < 1 or points != int(points):
        raise ScaffoldError(f"--points {points}: a whole number of at least 1")
    lab, folder = find_lab(which)
    manifest_path = ROOT / "tests" / folder / "exercises.json"
    handout_path = ROOT / "handouts" / f"{folder}.md"
    header_path = exercises_header(lab)
    for path in (manifest_path, handout_path, header_path, ROOT / "solutions" / folder):
        if not path.exists():
            raise ScaffoldError(f"{path}: missing; every lab has it")
    try:
        manifest = load_manifest(manifest_path)
    except ManifestError as error:
        raise ScaffoldError(str(error)) from None
    ex_id = next_id(manifest, folder)
    suite = camel(name, True)
    sig = Signature(signature or f"Vec3 {camel(name, False)}(const Vec3& x, double k)")
    title = title or name.replace("_", " ")
    hidden_points = points // 2
    public_points = points - hidden_points
    files = {
        ROOT / "solutions" / folder / f"{name}.cpp": SOLUTION,
        ROOT / "tests" / folder / "public" / f"{name}_test.cpp": PUBLIC,
        ROOT / "tests" / folder / "hidden" / f"{name}_test.cpp": HIDDEN,
    }
    for path in files:
        if path.exists():
            raise ScaffoldError(f"{path.relative_to(ROOT)}: already exists; pick another NAME")
    tests = {t["name"] for ex in manifest["exercises"] for t in ex["tests"]}
    if any(t.split(".")[0] == suite for t in tests):
        raise ScaffoldError(f"{manifest_path.relative_to(ROOT)}: a test suite named {suite} exists already; "
                            f"pick another NAME")
    if f"MatchesReference.{suite}" in tests:
        raise ScaffoldError(f"{manifest_path.relative_to(ROOT)}: MatchesReference.{suite} exists already")
    header = header_path.read_text()
    if re.search(rf"\b{sig.func}\s*\(", header):
        raise ScaffoldError(f"{header_path.relative_to(ROOT)}: {sig.func} is declared already; pick another name")
    if any(p.name == "got" or p.name == "want" or p.name.endswith("Ref") for p in sig.params):
        raise ScaffoldError("--signature: the names got, want and *Ref are the tests' own; rename the parameter")

    values = dict(lab=lab, folder=folder, id=ex_id, func=sig.func, suite=suite, title=title, file=f"{name}.cpp",
                  todo=TODO, signature=sig.text, default_signature=signature is None, points=points,
                  public_points=public_points, hidden_points=hidden_points,
                  points_text=handout_check.points_text(points),
                  public_points_text=handout_check.points_text(public_points),
                  hidden_points_text=handout_check.points_text(hidden_points))
    returns = "return -k * x;" if signature is None else (
        f"return {ZERO[sig.returns]};" if sig.returns in ZERO and sig.returns != "void" else
        "" if sig.returns == "void" else "return {};")
    values["body"] = f"  // {TODO}: the reference answer, one short comment above each step.\n" + (
        f"  {returns}\n" if returns else "")
    values["public_body"] = indent(public_body(sig, lab, values), 4)
    values["hidden_body"] = indent(hidden_body(sig, lab, values), 4)
    values["includes"] = "#include <algorithm>\n#include <cmath>\n"

    # The declaration goes after the last "// ---- Exercise" block of the lab's header.
    declaration = DECLARATION.format(**values, rule="-" * max(4, 91 - len(f"// ---- Exercise {ex_id}: {title} ")))
    marker = declaration_point(header, lab)
    if marker < 0:
        raise ScaffoldError(f"{header_path.relative_to(ROOT)}: cannot find where to declare {sig.func} (no "
                            f"'}}  // namespace springlab::{lab}' line)")
    new_header = header[:marker] + declaration + "\n" + header[marker:]

    # The manifest: one more exercise, written in the file's own compact style.
    text = manifest_path.read_text()
    entry = (f',\n    {{"id": "{ex_id}", "title": {json.dumps(title)},\n'
             f'     "file": "{name}.cpp", "section": "{TODO}: the handout\'s physics section (heading text)",\n'
             f'     "caller": "{TODO}: framework/labs/{lab}/src/FILE.cpp:Class::function that calls {sig.func}",\n'
             f'     "functions": [{json.dumps(" ".join(sig.text.split()))}],\n'
             f'     "tests": [\n'
             f'      {{"name": "{suite}.MatchesItsDefinition", "points": {public_points}, "visibility": "visible"}},\n'
             f'      {{"name": "MatchesReference.{suite}", "points": {hidden_points}, "visibility": "hidden"}}\n'
             f'    ]}}')
    new_text, count = re.subn(r"(\]\s*\})(\s*\]\s*\}\s*)$", lambda m: m.group(1) + entry + m.group(2), text)
    if count != 1:
        raise ScaffoldError(f"{manifest_path.relative_to(ROOT)}: cannot find the end of the exercises list")
    json.loads(new_text)
    manifest_path.write_text(new_text)
    new_manifest = load_manifest(manifest_path)

    # The handout: the section after the last exercise's, the table's row, every lab total.
    handout = add_handout_section(handout_path.read_text(), HANDOUT.format(**values))
    row = (f"| {ex_id} | {title} | {points} | {handout_check.tests_text(1, public_points)} | "
           f"{handout_check.tests_text(1, hidden_points)} |")
    handout = add_table_row(handout, row)
    handout = handout_check.sync_totals(handout, new_manifest)

    for path, template in files.items():
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(template.format(**values))
    header_path.write_text(new_header)
    handout_path.write_text(handout)
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
    left = handout_check.check_handout(new_manifest, handout_path.relative_to(ROOT), manifest_path.relative_to(ROOT))
    return ex_id, [*files, header_path, manifest_path, handout_path, *changed], left


def add_handout_section(handout, section):
    """The section goes after the last exercise's (before the next `## ` heading)."""
    headings = list(re.finditer(r"^### Exercise .*$", handout, re.M))
    after = re.search(r"^## ", handout[headings[-1].end():], re.M) if headings else None
    at = headings[-1].end() + after.start() if after else len(handout)
    return handout[:at] + section + "\n" + handout[at:]


def add_table_row(handout, row):
    """The grading table's new row goes after its last exercise row (before the total row)."""
    lines = handout.split("\n")
    table = handout_check.find_table(lines)
    if table is None:
        return handout  # the handout check then reports the missing table
    _, columns, rows = table
    exercise_rows = [i for i, cells in rows if cells and handout_check.bare(cells[columns.index("id")])]
    at = (exercise_rows[-1] + 1) if exercise_rows else rows[0][0] if rows else table[0] + 2
    lines.insert(at, row)
    return "\n".join(lines)


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
// {todo}: the formula students implement, with units.
{signature};
"""

SOLUTION = """#include <springlab/{lab}/exercises.hpp>

namespace springlab::{lab} {{

{signature} {{
  // BEGIN EXERCISE {id}
{body}  // END EXERCISE {id}
}}

}}  // namespace springlab::{lab}
"""

PUBLIC = """// Exercise {id}: {title}. {todo}: checks of the physics, each test named after it.
#include <gtest/gtest.h>

{includes}
#include <springlab/{lab}/{lab}.hpp>

#include "{lab}_fixtures.hpp"
#include "seeded.hpp"

namespace springlab::{lab} {{
namespace {{

using {suite} = springlab::testing::Seeded;

TEST_F({suite}, MatchesItsDefinition) {{
  for (int trial = 0; trial < 100; ++trial) {{
{public_body}
  }}
}}

}}  // namespace
}}  // namespace springlab::{lab}
"""

HIDDEN = """// Hidden test of exercise {id}: the student's {func} against the reference on random inputs,
// in the lab's hidden suite MatchesReference (its fixture: tests/support/{lab}_fixtures.hpp).
// The message names the inputs, never the reference's answer.
#include <gtest/gtest.h>

{includes}
#include <springlab/{lab}/{lab}.hpp>

#include "oracle_{lab}.hpp"  // generated by tests/CMakeLists.txt from the framework's lab headers
#include "{lab}_fixtures.hpp"

namespace springlab::{lab} {{
namespace {{

namespace ref = springlab::{lab}_reference;
using springlab::testing::relativeError;

TEST_F(MatchesReference, {suite}) {{
  for (int trial = 0; trial < kTrials; ++trial) {{
{hidden_body}
  }}
}}

}}  // namespace
}}  // namespace springlab::{lab}
"""

HANDOUT = """### Exercise {id}: {title} ({points_text})

File `labs/{folder}/{file}`, function `{func}` (declared in `exercises.hpp`). {todo}: what
to compute, the section of the physics it builds on, and what to watch out for.

- `{suite}.MatchesItsDefinition` ({public_points_text}): {todo}: what it checks, in physics terms.

Hidden: `MatchesReference.{suite}` ({hidden_points_text}).
"""


def main():
    ap = argparse.ArgumentParser(prog="springlab new-exercise", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("lab", help="the lab's name or folder (rope, 01_rope)")
    ap.add_argument("name", help="snake_case name of the exercise's file (elastic_energy)")
    ap.add_argument("--title", help="the exercise's title in the handout and the reports (default: NAME in words)")
    ap.add_argument("--points", type=int, default=2, help="the exercise's points, split public N - N/2, hidden N/2 "
                    "(default 2)")
    ap.add_argument("--signature", help="the C++ declaration, e.g. \"double elasticEnergy(const Vec3& x1, "
                    "const Vec3& x2, double k, double L0)\" (default: Vec3 <camelName>(const Vec3& x, double k))")
    args = ap.parse_args()
    try:
        ex_id, written, left = scaffold(args.lab, args.name, args.title, args.points, args.signature)
    except ScaffoldError as error:
        print(f"springlab new-exercise: {error}", file=sys.stderr)
        return 2
    print(f"exercise {ex_id} scaffolded; written or updated:")
    for path in written:
        print(f"  {path.relative_to(ROOT)}")
    for problem in left:
        print(f"springlab new-exercise: fix by hand: {problem}", file=sys.stderr)
    lab, _ = find_lab(args.lab)
    print(f"next: replace each {TODO} (./springlab author-check {lab} lists them with file and line); to have the "
          f"simulation use the function, call it from framework/labs/{lab}/src/; see handouts/authoring.md")
    return 0


if __name__ == "__main__":
    sys.exit(main())
