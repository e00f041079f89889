"""`check` beside an exercise file that does not compile, as `grade` grades beside one
(lab_grader.py): the file is graded as the released skeleton's (its exercises score 0) and the
lab's other files are graded. When the lab's grading program did not build, this compiles each of
the lab's exercise files that has no fresh object with the build's own command (from CMake's
compile_commands.json) to learn which do not compile and why, puts in the place of each a stub of
its exercise functions that throws NotImplemented, as the skeleton's do (written from the
manifest's declarations: a student tree has no skeleton to copy), and links the lab's grading
program as CMake wrote its link down (grading/<lab>_link.json, link_file.py). Shipped in the
student release; nothing here runs student code."""
import concurrent.futures
import dataclasses
import hashlib
import json
import os
import pathlib
import re
import shlex
import subprocess

from .compile_errors import first_errors
from .errors import GradeError
from .link_file import read_link_file


@dataclasses.dataclass
class Compile:
    """One exercise file's compile, as CMake runs it."""
    argv: list
    directory: pathlib.Path
    source: pathlib.Path
    output: pathlib.Path

    def fresh(self):
        """Its object exists and is newer than the file (a failed compile leaves the old one)."""
        return self.output.is_file() and self.output.stat().st_mtime_ns >= self.source.stat().st_mtime_ns

    def run(self, remember=None):
        """Compile; (exit code, the compiler's text). With `remember` (a folder), a compile that
        failed is remembered there by the file's content and the command, and the same file
        is not compiled again to learn the same errors (check runs after each edit of another
        file, each time after make has just failed on this one)."""
        argv = [*self.argv, "-fdiagnostics-color=never"]
        key = hashlib.sha256(json.dumps(argv).encode() + b"\0" + self.source.read_bytes()).hexdigest()
        known = pathlib.Path(remember) / f"{self.source.name}.{key[:32]}.failed" if remember else None
        if known is not None and known.is_file():
            return 1, known.read_text()
        run = subprocess.run(argv, cwd=self.directory, capture_output=True, text=True, errors="replace")
        if known is not None and run.returncode != 0:
            for old in known.parent.glob(f"{self.source.name}.*.failed"):
                old.unlink()
            known.write_text(run.stdout + run.stderr)
        return run.returncode, run.stdout + run.stderr

    def of(self, source, output):
        """The same compile of another file into another object (no dependency file)."""
        argv, skip = [], False
        for arg in self.argv:
            if skip:
                skip = False
            elif arg in ("-MT", "-MF", "-MQ"):
                skip = True
            elif arg in ("-MD", "-MMD"):
                continue
            elif arg == str(self.output) or (not os.path.isabs(arg) and self.directory / arg == self.output):
                argv.append(str(output))
            elif arg == str(self.source) or (not os.path.isabs(arg) and self.directory / arg == self.source):
                argv.append(str(source))
            else:
                argv.append(arg)
        return Compile(argv, self.directory, pathlib.Path(source), pathlib.Path(output))


def exercise_compiles(build, lab, tree="student"):
    """{exercise file: its Compile} of lab `lab` in a build (the compile commands of
    springlab_<lab>_student_objects, or _solution_objects for the reference); {} when the build
    has no compile_commands.json."""
    commands = pathlib.Path(build) / "compile_commands.json"
    if not commands.is_file():
        return {}
    target = f"springlab_{lab}_{'student' if tree == 'student' else 'solution'}_objects.dir/"
    found = {}
    for entry in json.loads(commands.read_text()):
        command = entry.get("command", "")
        argv = entry.get("arguments") or shlex.split(command)
        if target not in " ".join(argv) or "-o" not in argv:
            continue
        directory = pathlib.Path(entry.get("directory", "."))
        source = pathlib.Path(entry["file"])
        found[source.name] = Compile(argv, directory, directory / source, directory / argv[argv.index("-o") + 1])
    return found


def stub_source(manifest, name):
    """The stub of exercise file `name`: each function its exercises declare (the manifest's
    declarations, as the lab's exercises.hpp spells them) throws NotImplemented."""
    lab = manifest["lab"]
    where = f"labs/{manifest['folder']}/{name}, which does not compile"
    bodies = []
    for ex in manifest["exercises"]:
        if ex.get("file") != name:
            continue
        for declaration in ex.get("functions", []):
            bodies.append(f"{declaration} {{\n  throw springlab::NotImplemented(\"{ex['id']}\", \"{ex['title']}\", "
                          f"\"{where}\");\n}}\n")
    return (f"// Written by `./springlab check` in the place of {name}, which does not compile.\n"
            f"#include <springlab/{lab}/exercises.hpp>\n\nnamespace springlab::{lab} {{\n\n"
            + "\n".join(bodies) + f"\n}}  // namespace springlab::{lab}\n")


@dataclasses.dataclass
class Rebuilt:
    binary: pathlib.Path  # the lab's grading program, with stubs in the place of the files below
    broken: dict          # {exercise file that does not compile: the compiler's full text (paths in the tree)}
    undefined: dict = dataclasses.field(default_factory=dict)  # {file that compiles: [its functions the link missed]}


def function_name(declaration):
    """The name a manifest declaration ("Vec3 windForce(const Wind& wind, ...)") declares."""
    return re.search(r"(\w+)\s*\(", declaration)[1]


def undefined_functions(linker_text, manifest):
    """{exercise file: [its functions]} of the exercise functions a failed link did not find
    (a file that compiles but defines another signature than the header declares)."""
    lab = manifest["lab"]
    named = set(re.findall(rf"undefined (?:reference to [`']|symbol: )springlab::{lab}::(\w+)\(", linker_text))
    found = {}
    for ex in manifest["exercises"]:
        for declaration in ex.get("functions", []):
            if function_name(declaration) in named:
                found.setdefault(ex["file"], []).append(function_name(declaration))
    return found


def rebuild(build, manifest, tree, jobs=2):
    """The lab's grading program when some of its exercise files do not compile, or compile but
    do not define their functions as the header declares them: the others' objects with a stub
    of each such file, linked as CMake links the program. A Rebuilt without a binary when every
    exercise file compiles and links (the build failed elsewhere). Raises GradeError when the
    program cannot be linked."""
    build, tree = pathlib.Path(build), pathlib.Path(tree).resolve()
    lab = manifest["lab"]
    compiles = exercise_compiles(build, lab)
    if not compiles:
        raise GradeError(f"{build}/compile_commands.json: no compile of the {lab} lab's exercise files; "
                         f"configure the build again (./springlab build)")
    work = build / "check" / lab
    work.mkdir(parents=True, exist_ok=True)
    stale = [name for name, c in sorted(compiles.items()) if not c.fresh()]
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        outcomes = dict(zip(stale, pool.map(lambda n: compiles[n].run(remember=work), stale)))
    prefix = str(tree) + os.sep
    broken = {name: text.replace(prefix, "") for name, (code, text) in outcomes.items() if code != 0}

    # The link CMake wrote down, with an archive of the exercise objects and the lab's given ones.
    link = read_link_file(build / "grading" / f"{lab}_link.json")
    needed = [*link.test_objects, *link.main_objects, *link.given_objects,
              *(lib for lib in link.libraries if re.search(r"\.(a|so)$", lib) and os.path.isabs(lib))]
    missing = [path for path in needed if not os.path.exists(path)]
    if missing:
        if not broken:
            return Rebuilt(None, {})
        raise GradeError(f"the lab's other parts did not build either (no {os.path.relpath(missing[0], tree)}"
                         f"{f' and {len(missing) - 1} more' if len(missing) > 1 else ''})")
    undefined = {}
    # Twice at most: a link that misses exercise functions of a file stubs that file too.
    for _ in range(2):
        stubbed = set(broken) | set(undefined)
        objects = [stub(compiles[name], manifest, name, work, link.given_objects) if name in stubbed
                   else compiles[name].output
                   for name in sorted(compiles)]
        binary, text = link_program(link, objects, work / f"{lab}_grading_student")
        if binary is not None:
            return Rebuilt(binary, broken, undefined) if stubbed else Rebuilt(None, {})
        more = {f: fs for f, fs in undefined_functions(text, manifest).items() if f not in stubbed}
        if not more:
            break
        undefined.update(more)
    raise GradeError(f"the lab's grading program does not link:\n{first_errors(text.replace(prefix, ''))}")


def stub(compile_, manifest, name, work, newer_than=()):
    """Exercise file `name`'s stub (stub_source), compiled with the file's own command; its object."""
    source, output = work / f"stub_{name}", work / f"stub_{name}.o"
    # Compiled again only when the stub or its command changed, or the lab's headers did (then
    # the lab's given objects, `newer_than`, were compiled again after it).
    text, command = stub_source(manifest, name), compile_.of(source, output)
    stamp = work / f"stub_{name}.command"
    if (source.is_file() and source.read_text() == text and output.is_file() and stamp.is_file()
            and stamp.read_text() == json.dumps(command.argv)
            and all(output.stat().st_mtime_ns >= os.stat(o).st_mtime_ns for o in newer_than)):
        return output
    source.write_text(text)
    stamp.unlink(missing_ok=True)
    code, text = command.run()
    if code == 0:
        stamp.write_text(json.dumps(command.argv))
    else:
        raise GradeError(f"the stub check puts in the place of {name} does not compile (does the lab's "
                         f"exercises.hpp match its manifest?):\n{first_errors(text)}")
    return output


def link_program(link, objects, binary):
    """(the grading program `binary`, "") of these exercise objects with the lab's given ones, or
    (None, the linker's text)."""
    archive = binary.with_name(f"lib{binary.name}.a")
    archive.unlink(missing_ok=True)
    run = subprocess.run(["ar", "qcs", str(archive), *map(str, objects), *link.given_objects],
                         capture_output=True, text=True)
    if run.returncode != 0:
        raise GradeError(f"ar: {run.stderr.strip()}")
    run = subprocess.run(link.argv(archive, binary), cwd=binary.parent, capture_output=True, text=True)
    return (binary, "") if run.returncode == 0 else (None, run.stdout + run.stderr)
