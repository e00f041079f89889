#!/usr/bin/env python3
"""Generate the grader's call layer of a lab from its exercise header.

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

usage: make_call_layer.py LAB HEADER SOLUTIONS_DIR OUT_DIR
"""
import json
import pathlib
import re
import sys

LABEL = "springlab_student_{}"


def strip_comments(text):
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    return re.sub(r"//[^\n]*", "", text)


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


def namespace_body(text, lab):
    start = re.search(rf"namespace\s+springlab::{lab}\s*\{{", text)
    if not start:
        raise SystemExit(f"no `namespace springlab::{lab} {{` in the header")
    depth, i = 1, start.end()
    while depth and i < len(text):
        depth += {"{": 1, "}": -1}.get(text[i], 0)
        i += 1
    return text[start.end():i - 1]


def statements(body):
    """Top-level statements: (text, braced body or None)."""
    out, depth, cur, inner = [], 0, "", ""
    for ch in body:
        if depth == 0 and ch == ";":
            out.append((cur.strip(), inner if inner else None))
            cur, inner = "", ""
            continue
        if ch == "{":
            depth += 1
            if depth == 1:
                continue
        if ch == "}":
            depth -= 1
            if depth == 0:
                continue
        if depth == 0:
            cur += ch
        else:
            inner += ch
    return [s for s in out if s[0]]


class Param:
    def __init__(self, text):
        m = re.match(r"^(?P<type>.+?[\s&*])(?P<name>\w+)$", text.strip())
        if not m:
            raise SystemExit(f"cannot read the parameter `{text}`")
        self.type = " ".join(m["type"].split())
        self.name = m["name"]
        self.written = self.type.endswith("&") and not self.type.startswith("const ")


class Function:
    def __init__(self, ret, name, params):
        self.ret, self.name = " ".join(ret.split()), name
        self.params = [Param(p) for p in split_top(params)] if params.strip() else []

    def signature(self, name, unnamed=False):
        return f"{self.ret} {name}({', '.join(('[[maybe_unused]] ' if unnamed else '') + f'{p.type} {p.name}' for p in self.params)})"

    def args(self):
        return ", ".join(p.name for p in self.params)


def parse(header, lab):
    body = namespace_body(strip_comments(header), lab)
    functions, structs, enums = [], {}, set()
    for text, inner in statements(body):
        flat = " ".join(text.split())
        if inner is not None:
            m = re.match(r"^struct\s+(\w+)\s*(:.*)?$", flat)
            if m:
                fields = None if m.group(2) else struct_fields(inner)
                structs[m.group(1)] = fields
            continue
        m = re.match(r"^enum\s+(class\s+)?(\w+)", flat)
        if m:
            enums.add(m.group(2))
            continue
        m = re.match(r"^(?P<ret>[\w:<>,\s&*]+?)\s+(?P<name>\w+)\s*\((?P<params>.*)\)$", flat)
        if m and not flat.startswith(("using ", "typedef ")):
            functions.append(Function(m["ret"], m["name"], m["params"]))
    return functions, structs, enums


def struct_fields(inner):
    """The field names of a plain struct, or None when it has member functions."""
    fields = []
    for text, block in statements(inner):
        head = " ".join(text.split()).split("=")[0].strip()
        if block is not None or "(" in head or head.startswith(("using ", "static ")):
            return None
        m = re.match(r"^(?P<type>.+?)\s+(?P<name>\w+)$", head)
        if not m:
            return None
        fields.append(m["name"])
    return fields


def names_in(type_text):
    return set(re.findall(r"\b[A-Za-z_]\w*\b", type_text))


def defining_file(solutions, name):
    hits = [f for f in sorted(solutions.glob("*.cpp"))
            if re.search(rf"^[A-Za-z][^;{{}}]*?\b{name}\s*\(", f.read_text(), re.M)]
    return hits


def generate(lab, header_path, solutions, out):
    header = header_path.read_text()
    functions, structs, enums = parse(header, lab)
    names = [f.name for f in functions]
    duplicated = sorted({n for n in names if names.count(n) > 1})
    if duplicated:
        raise SystemExit(f"{header_path}: overloaded exercise functions ({', '.join(duplicated)}): the call "
                         f"layer needs one function per name")
    ids = {f.name: i for i, f in enumerate(functions)}
    by_file = {}
    for f in functions:
        files = defining_file(solutions, f.name)
        if not files:
            continue  # a helper the given code defines (net's gridRows), not an exercise
        if len(files) != 1:
            raise SystemExit(f"{header_path}: {f.name} is defined in {len(files)} files of {solutions} "
                             f"({', '.join(p.name for p in files) or 'none'}); each exercise function lives in one")
        by_file.setdefault(files[0].name, []).append(f)

    # The lab's types an exercise gives back, and the lab types inside those.
    lab_types = set(structs) | enums
    needed, todo = [], [t for f in functions for t in names_in(f.ret) | {n for p in f.params if p.written
                                                                             for n in names_in(p.type)}]
    while todo:
        t = todo.pop()
        if t in structs and t not in needed:
            if structs[t] is None:
                raise SystemExit(f"{header_path}: struct {t} is given back by an exercise but its fields cannot "
                                 f"be read (a base class or a member function)")
            needed.append(t)
            body = re.search(rf"struct\s+{t}\s*\{{(.*?)\}};", strip_comments(header), re.S).group(1)
            todo += [n for n in names_in(body)]
    out.mkdir(parents=True, exist_ok=True)
    banner = f"// Generated by tools/make_call_layer.py from {header_path.name} of the {lab} lab: do not edit.\n"
    include = f"#include <springlab/{lab}/exercises.hpp>\n"

    values = [banner, "#pragma once\n", include, '#include "call_trace.hpp"\n\n', f"namespace springlab::{lab} {{\n"]
    for t in needed:
        values.append(f"void put(trace::Writer& w, const {t}& v);\nvoid get(trace::Reader& r, {t}& v);\n")
    for t in needed:
        fields = structs[t]
        values.append(f"inline void put(trace::Writer& w, const {t}& v) {{\n  using trace::put;\n"
                      + "".join(f"  put(w, v.{x});\n" for x in fields) + "}\n")
        values.append(f"inline void get(trace::Reader& r, {t}& v) {{\n  using trace::get;\n"
                      + "".join(f"  get(r, v.{x});\n" for x in fields) + "}\n")
        # The judge looks into the struct for indices and points (trace::checkReplayedIndices).
        values.append(f"template <class F>\nvoid forEachField(const {t}& v, F&& f) {{\n"
                      + "".join(f"  f(v.{x});\n" for x in fields) + "}\n")
    values.append(f"}}  // namespace springlab::{lab}\n")
    write(out / "values.hpp", "".join(values))

    def student_declarations(fs):
        return "".join(f"{f.signature('student_' + f.name)} asm(\"{LABEL.format(f.name)}\");\n" for f in fs)

    # Every exercise file gets its three files, even one without functions, so that the build
    # knows the outputs from the file names alone.
    for source in sorted(solutions.glob("*.cpp")):
        by_file.setdefault(source.name, [])
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

        def cast(type_text, expr):
            if not (names_in(type_text) & lab_types):
                return expr
            base = re.sub(r"^const\s+|\s*&$", "", type_text)
            qualified = re.sub(r"\b(" + "|".join(sorted(lab_types)) + r")\b", rf"::springlab::{lab}::\1", base)
            const = "" if (type_text.endswith("&") and not type_text.startswith("const ")) else "const "
            return f"*reinterpret_cast<{const}{qualified}*>(&{expr})"

        text = [banner, "// The types of both namespaces come from one header text, so they share their layout.\n",
                f'#include "oracle_{lab}.hpp"\n', include, "\n", f"namespace springlab::{lab} {{\n",
                student_declarations(fs), f"}}  // namespace springlab::{lab}\n\n", f"namespace springlab::{ref} {{\n\n"]
        for f in fs:
            call = f"::springlab::{lab}::student_{f.name}({', '.join(cast(p.type, p.name) for p in f.params)})"
            if f.ret == "void":
                text.append(f"{f.signature(f.name)} {{ {call}; }}\n\n")
            elif names_in(f.ret) & lab_types:
                text.append(f"{f.signature(f.name)} {{\n  auto result = {call};\n"
                            f"  return *reinterpret_cast<{f.ret}*>(&result);\n}}\n\n")
            else:
                text.append(f"{f.signature(f.name)} {{ return {call}; }}\n\n")
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
    if len(sys.argv) != 5:
        raise SystemExit(__doc__)
    generate(sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3]), pathlib.Path(sys.argv[4]))
