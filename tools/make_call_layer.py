#!/usr/bin/env python3
"""Generate the grader's call layer of a lab from its manifest (tests/<dir>/exercises.json).

A graded test runs twice (tests/support/call_trace.hpp): in the sandboxed worker, with the
student's exercise file, and in the judge, which holds no student code. For each exercise file
F this writes, into OUT/:

  F.record.cpp   worker: the exercise functions of F, each calling the student's function
                 (renamed in the student's object to springlab_student_<name>) and recording
                 what it returned and wrote;
  F.forward.cpp  worker: the same functions in the oracle's namespace (<lab>_reference), calling
                 the student's too, so the worker's hidden tests compare the student with
                 itself and take the same path as the judge's (the worker holds no reference
                 of F);
  F.replay.cpp   judge: the exercise functions of F, each reading the worker's next record;
  values.hpp     put/get of the lab's own types that exercises return or write;
  functions.json {"F.cpp": [names]}: what the grader renames in the student's object.

The manifest declares it all: each exercise's "file" and "functions" (declarations as the lab's
exercises.hpp spells them) and the lab's "values" (each struct an exercise gives back, with its
fields in order). No C++ is parsed: the generated files include the lab's header, so a
declaration that drifts from it stops the build (the record, forward and replay definitions
then define other functions than the tests call, and the link fails), and a struct whose fields
are not the manifest's stops it too (values.hpp binds them all: a structured binding of another
count does not compile).

usage: make_call_layer.py MANIFEST OUT_DIR
"""
import json
import pathlib
import re
import sys

LABEL = "springlab_student_{}"
DECLARATION = re.compile(r"^(?P<ret>[^()]+?)\s+(?P<name>[A-Za-z_]\w*)\((?P<params>.*)\)$")


def split_top(text, sep=","):
    """Split at separators outside (), <>, {} and []."""
    parts, depth, cur = [], 0, ""
    for ch in text:
        if ch in "(<{[":
            depth += 1
        elif ch in ")>}]":
            depth -= 1
        if ch == sep and depth == 0:
            parts.append(cur)
            cur = ""
        else:
            cur += ch
    if cur.strip():
        parts.append(cur)
    return [p.strip() for p in parts]


class Param:
    def __init__(self, text, where):
        m = re.match(r"^(?P<type>.+?[\s&*])(?P<name>\w+)$", text.strip())
        if not m:
            raise SystemExit(f"{where}: cannot read the parameter `{text}` (TYPE NAME)")
        self.type = " ".join(m["type"].split())
        self.name = m["name"]
        self.written = self.type.endswith("&") and not self.type.startswith("const ")


class Function:
    """One exercise function, from its declaration in the manifest: RETURN NAME(TYPE NAME, ...)."""

    def __init__(self, declaration, where):
        m = DECLARATION.match(" ".join(declaration.split()))
        if not m:
            raise SystemExit(f"{where}: `{declaration}` is not a declaration RETURN NAME(PARAMETERS)")
        self.ret, self.name = m["ret"], m["name"]
        self.params = [Param(p, where) for p in split_top(m["params"])] if m["params"].strip() else []

    def signature(self, name, unnamed=False):
        return f"{self.ret} {name}({', '.join(('[[maybe_unused]] ' if unnamed else '') + f'{p.type} {p.name}' for p in self.params)})"

    def args(self):
        return ", ".join(p.name for p in self.params)


def read_manifest(path):
    """(lab id, {file: [Function]}, {struct: [fields]}) from a lab's manifest."""
    data = json.loads(pathlib.Path(path).read_text())
    by_file = {}
    for i, exercise in enumerate(data["exercises"]):
        where = f"{path}: exercises[{i}].functions"
        by_file[exercise["file"]] = [Function(d, where) for d in exercise["functions"]]
    return data["lab"], by_file, data.get("values", {})


# The worker's forward files call the student's function (in springlab::<lab>) with the oracle's
# arguments (in springlab::<lab>_reference): the same types from one header text, so each
# argument is read as the parameter's type at its own address, and the result back likewise.
FORWARD_HELPERS = """namespace {
template <class To, class From>
To& sameLayout(From& value) {
  return *reinterpret_cast<std::remove_reference_t<To>*>(&value);
}
template <class To, class From>
const To& sameLayout(const From& value) {
  return *reinterpret_cast<const std::remove_cvref_t<To>*>(&value);
}
template <class Result, class R, class... Params, class... Args>
Result forwardCall(R (*student)(Params...), Args&&... args) {
  if constexpr (std::is_void_v<R>) {
    student(sameLayout<Params>(args)...);
  } else {
    R result = student(sameLayout<Params>(args)...);
    return sameLayout<Result>(result);
  }
}
}  // namespace
"""


def generate(manifest, out):
    lab, by_file, values = read_manifest(manifest)
    functions = [f for fs in by_file.values() for f in fs]
    names = [f.name for f in functions]
    duplicated = sorted({n for n in names if names.count(n) > 1})
    if duplicated:
        raise SystemExit(f"{manifest}: exercise functions declared twice ({', '.join(duplicated)}): the call "
                         f"layer needs one function per name, in one exercise")
    ids = {f.name: i for i, f in enumerate(functions)}
    out.mkdir(parents=True, exist_ok=True)
    banner = f"// Generated by tools/make_call_layer.py from {pathlib.Path(manifest).name} of the {lab} lab: do not edit.\n"
    include = f"#include <springlab/{lab}/exercises.hpp>\n"

    values_text = [banner, "#pragma once\n", include, '#include "call_trace.hpp"\n\n', f"namespace springlab::{lab} {{\n"]
    for t in values:
        values_text.append(f"void put(trace::Writer& w, const {t}& v);\nvoid get(trace::Reader& r, {t}& v);\n")
    for t, fields in values.items():
        # Every field, in order: the binding does not compile if {t} has other fields than these.
        binding = f"  [[maybe_unused]] auto& [{', '.join(f'field{i}' for i in range(len(fields)))}] = v;\n"
        values_text.append(f"inline void put(trace::Writer& w, const {t}& v) {{\n  using trace::put;\n{binding}"
                           + "".join(f"  put(w, v.{x});\n" for x in fields) + "}\n")
        values_text.append(f"inline void get(trace::Reader& r, {t}& v) {{\n  using trace::get;\n{binding}"
                           + "".join(f"  get(r, v.{x});\n" for x in fields) + "}\n")
        # The judge looks into the struct for indices and points (trace::checkReplayedIndices).
        values_text.append(f"template <class F>\nvoid forEachField(const {t}& v, F&& f) {{\n"
                           + "".join(f"  f(v.{x});\n" for x in fields) + "}\n")
    values_text.append(f"}}  // namespace springlab::{lab}\n")
    write(out / "values.hpp", "".join(values_text))

    def student_declarations(fs):
        return "".join(f"{f.signature('student_' + f.name)} asm(\"{LABEL.format(f.name)}\");\n" for f in fs)

    # Every exercise file gets its three files, even one without functions, so that the build
    # knows the outputs from the file names alone.
    for file, fs in sorted(by_file.items()):
        stem = file[:-len(".cpp")]
        # Worker: record.
        text = [banner, include, '#include "values.hpp"\n\n', f"namespace springlab::{lab} {{\n\n",
                "// The student's functions: the grader renames them in the student's object.\n",
                student_declarations(fs), "\n"]
        for f in fs:
            written = [p.name for p in f.params if p.written]
            call = f"student_{f.name}({f.args()})"
            if f.ret == "void":
                rec = "[&](trace::Writer& w) {\n    using trace::put;\n" + "".join(f"    put(w, {n});\n" for n in written) + "  }"
                lam = f"[&]() {{ {call}; }}"
            else:
                rec = ("[&](trace::Writer& w, const auto& result) {\n    using trace::put;\n    put(w, result);\n"
                       + "".join(f"    put(w, {n});\n" for n in written) + "  }")
                lam = f"[&]() -> {f.ret} {{ return {call}; }}"
            text.append(f"{f.signature(f.name)} {{\n  return trace::recorded({ids[f.name]}u, {lam},\n  {rec});\n}}\n\n")
        text.append(f"}}  // namespace springlab::{lab}\n")
        write(out / f"{stem}.record.cpp", "".join(text))

        # Worker: the oracle's namespace forwards to the student's functions.
        ref = f"{lab}_reference"

        text = [banner, "// The types of both namespaces come from one header text, so they share their layout.\n",
                f'#include "oracle_{lab}.hpp"\n', include, "#include <type_traits>\n\n", FORWARD_HELPERS, "\n",
                f"namespace springlab::{lab} {{\n", student_declarations(fs), f"}}  // namespace springlab::{lab}\n\n",
                f"namespace springlab::{ref} {{\n\n"]
        for f in fs:
            call = f"forwardCall<{f.ret}>(&::springlab::{lab}::student_{f.name}{''.join(', ' + p.name for p in f.params)})"
            text.append(f"{f.signature(f.name)} {{ {'' if f.ret == 'void' else 'return '}{call}; }}\n\n")
        text.append(f"}}  // namespace springlab::{ref}\n")
        write(out / f"{stem}.forward.cpp", "".join(text))

        # Judge: replay.
        text = [banner, include, '#include "values.hpp"\n\n', f"namespace springlab::{lab} {{\n\n"]
        for f in fs:
            body = [f"  trace::replayCall({ids[f.name]}u, \"{f.name}\");\n", "  using trace::get;\n",
                    "  [[maybe_unused]] trace::Reader& r = trace::Reader::instance();\n"]
            if f.ret != "void":
                body.append(f"  {f.ret} result{{}};\n  get(r, result);\n")
            body += [f"  get(r, {p.name});\n" for p in f.params if p.written]
            checked = (["result"] if f.ret != "void" else []) + [p.name for p in f.params]
            if checked:
                body.append(f"  trace::checkReplayedIndices({', '.join(checked)});\n")
            if f.ret != "void":
                body.append("  return result;\n")
            text.append(f"{f.signature(f.name)} {{\n{''.join(body)}}}\n\n")
        text.append(f"}}  // namespace springlab::{lab}\n")
        write(out / f"{stem}.replay.cpp", "".join(text))

    write(out / "functions.json", json.dumps({f: [x.name for x in fs] for f, fs in sorted(by_file.items())},
                                             indent=1) + "\n")


def write(path, text):
    if not path.exists() or path.read_text() != text:
        path.write_text(text)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    generate(pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2]))
