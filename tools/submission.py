#!/usr/bin/env python3
"""Grade student submissions against this instructor tree: one (`grade`) or a class (`grade-all`).

    tools/submission.py grade SUBMISSION [--out DIR]     a labs/ folder, a folder holding one, or a .zip
    tools/submission.py grade-all DIR [--out DIR]        every folder and .zip directly under DIR

How: a cache build of the framework, the reference "oracle" and the grading tests' objects
(build-grader/, built once and reused) is configured from this tree. For each submission and
each lab, only the student's exercise files (the .cpp files of the released labs/<dir>/) are
compiled (in a sandbox, as `nobody` when root), against the framework's headers, and linked
with the lab's given objects (framework/labs/<name>/, compiled once) and the cached objects
into that lab's grading program; any other file of the submission is ignored and the report
says so; then every grading test runs
in its own sandboxed process (tools/grade.py). A lab that does not compile scores 0 alone.

Labs are discovered from CMakeLists.txt (`springlab_add_lab(NAME rope DIR 01_rope)`) with their
manifest tests/<dir>/exercises.json; nothing here knows a particular lab.

Files the student did not submit are taken from the released skeleton (labs/<dir>/) and the
report says so. A file that includes the instructor's files (solutions/, hidden tests), calls
the reference solution's symbols or redefines the framework's or GoogleTest's is graded as the
skeleton's version of that file, so its exercises score 0, and the report says why.
"""
import argparse
import concurrent.futures
import csv
import dataclasses
import functools
import hashlib
import json
import os
import pathlib
import re
import shlex
import shutil
import stat
import subprocess
import sys
import tempfile
import threading
import time
import zipfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import grade  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parent.parent
SOURCE_SUFFIXES = (".cpp",)  # a lab folder's exercise files; headers are the framework's
MAX_FILE_BYTES = 1 << 20
COMPILE_TIMEOUT = 180.0


class GradeError(Exception):
    """Bad input or a broken instructor tree: a clear message and exit code 2."""


# ---- the labs of this tree -------------------------------------------------------------------
@dataclasses.dataclass
class Lab:
    name: str       # rope
    dir: str        # 01_rope
    manifest: dict

    @property
    def skeleton(self):
        return ROOT / "labs" / self.dir

    @property
    def solution(self):
        return ROOT / "solutions" / self.dir


def discover_labs(root=ROOT):
    """Every lab with a springlab_add_lab line, a grading line and a manifest."""
    line = re.compile(r"^\s*springlab_add_lab\(\s*NAME\s+(\w+)\s+DIR\s+(\w+)\s*\)", re.M)
    grading = (root / "tests" / "CMakeLists.txt").read_text()
    labs = []
    for name, folder in line.findall((root / "CMakeLists.txt").read_text()):
        if not re.search(rf"^\s*springlab_add_grading\(\s*NAME\s+{name}\s+DIR\s+{folder}\s*\)", grading, re.M):
            raise GradeError(f"tests/CMakeLists.txt: no springlab_add_grading(NAME {name} DIR {folder}) line "
                             f"for the lab of CMakeLists.txt")
        try:
            manifest = grade.load_manifest(root / "tests" / folder / "exercises.json")
        except grade.ManifestError as error:
            raise GradeError(str(error)) from None
        labs.append(Lab(name, folder, manifest))
    if not labs:
        raise GradeError(f"{root / 'CMakeLists.txt'}: no springlab_add_lab(...) lines: no labs to grade")
    return labs


def exercises_in(path):
    """Exercise ids marked in a reference source file."""
    if not path.exists():
        return []
    return re.findall(r"^\s*// BEGIN EXERCISE (\S+)\s*$", path.read_text(), re.M)


# ---- the cache build: framework, oracle and test objects, built once -------------------------
@dataclasses.dataclass
class LabBuild:
    compile_argv: list      # compiler and flags, without -I of the lab, -o, -c
    lab_include: str        # the -I of the skeleton folder the flags held
    link_argv: list         # the grading program's link line; STUDENT_LIB and OUTPUT placeholders
    link_dir: pathlib.Path
    given_objects: list     # the lab's given code, archived with the student's exercise objects
    tests_present: set
    oracle_symbols: set     # strong symbols the reference "oracle" defines
    protected_symbols: set  # strong symbols of the framework, GoogleTest and the grading main


class Cache:
    def __init__(self, path, labs, build=True, jobs=2):
        self.path = pathlib.Path(path).resolve()
        self.labs = labs
        if build:
            self.build(jobs)
        commands = self.path / "compile_commands.json"
        if not commands.exists():
            raise GradeError(f"{commands}: missing; is {self.path} a build of this tree "
                             f"(configured with CMAKE_EXPORT_COMPILE_COMMANDS)?")
        self.commands = json.loads(commands.read_text())
        self.objects = self.path / "grader-objects"
        self.objects.mkdir(exist_ok=True)
        os.chmod(self.objects, 0o700)
        self.lab_builds = {}
        self.lock = threading.Lock()

    def build(self, jobs):
        env = dict(os.environ)
        env.setdefault("CCACHE_BASEDIR", str(ROOT))
        if not (self.path / "CMakeCache.txt").exists():
            configure = ["cmake", "-S", str(ROOT), "-B", str(self.path), "-DCMAKE_BUILD_TYPE=Release",
                         "-DSPRINGLAB_BUILD_VIEWER=OFF"]
            if shutil.which("ccache"):
                configure.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
            run = subprocess.run(configure, capture_output=True, text=True, env=env)
            if run.returncode != 0:
                raise GradeError(f"configuring the grading build {self.path} failed:\n{run.stdout}{run.stderr}")
        targets = [t for lab in self.labs for t in ("--target", f"{lab.name}_grading_student")]
        run = subprocess.run(["cmake", "--build", str(self.path), "-j", str(jobs), *targets],
                             capture_output=True, text=True, env=env)
        if run.returncode != 0:
            raise GradeError(f"building the grading build {self.path} failed (the instructor tree does not build):\n"
                             + grade.tail(run.stdout + run.stderr, 40))

    def lab(self, lab, sandbox):
        """What compiling and linking this lab's grading program needs, found once."""
        with self.lock:
            if lab.name not in self.lab_builds:
                self.lab_builds[lab.name] = self._lab_build(lab, sandbox)
            return self.lab_builds[lab.name]

    def _lab_build(self, lab, sandbox):
        target = f"springlab_{lab.name}_student"
        entry = next((c for c in self.commands if f"/{target}_objects.dir/" in c.get("command", "")), None)
        if entry is None:
            raise GradeError(f"{self.path}: no compile command for {target}; was the lab built?")
        argv = shlex.split(entry["command"])
        flags, skip = [], False
        lab_include = None
        for i, arg in enumerate(argv):
            if skip:
                skip = False
                continue
            if arg in ("-o", "-c"):
                skip = True
                continue
            if arg == "-Werror":
                continue  # a warning in student code is reported, never fatal
            if arg.startswith("-I") and pathlib.PurePath(arg[2:]).parts[-2:] == ("labs", lab.dir):
                lab_include = arg
                continue
            flags.append(arg)
        link_dir = self.path / "tests"
        link_txt = link_dir / "CMakeFiles" / f"{lab.name}_grading_student.dir" / "link.txt"
        if not link_txt.exists():
            raise GradeError(f"{link_txt}: missing; was {lab.name}_grading_student built?")
        link, protected_files, oracle = [], [], None
        tokens = shlex.split(link_txt.read_text().strip().splitlines()[-1])
        for i, token in enumerate(tokens):
            if i > 0 and tokens[i - 1] == "-o":
                link.append("OUTPUT")
                continue
            if token.endswith(f"lib{target}.a"):
                link.append("STUDENT_LIB")
                continue
            link.append(token)
            if token.endswith((".a", ".o")) and not token.startswith("-"):
                path = (link_dir / token).resolve()
                if token.endswith(f"libspringlab_{lab.name}_oracle.a"):
                    oracle = path
                else:
                    protected_files.append(path)
        # The lab's given code (framework/labs/<name>/, compiled once): CMake lists its objects.
        listing = self.path / "grading" / f"{lab.name}_given_objects.txt"
        if not listing.exists():
            raise GradeError(f"{listing}: missing; was {self.path} configured from this tree?")
        given = [pathlib.Path(line) for line in listing.read_text().split("\n") if line.strip()]
        protected_files += given
        skeleton_binary = link_dir / f"{lab.name}_grading_student"
        present = set(grade.listed_tests(str(skeleton_binary), sandbox))
        return LabBuild(flags, lab_include or "", link, link_dir, given, present,
                        defined_symbols([oracle]) if oracle else set(), defined_symbols(protected_files))


def defined_symbols(files):
    """Global symbols the files define strongly (weak ones, inline functions, may repeat)."""
    files = [str(f) for f in files if f]
    if not files:
        return set()
    run = subprocess.run(["nm", "-g", "--defined-only", "-P", *files], capture_output=True, text=True)
    return {parts[0] for parts in (line.split() for line in run.stdout.splitlines())
            if len(parts) >= 2 and parts[1] in "TDBRG" and not parts[0].endswith(":")}


def undefined_symbols(obj):
    run = subprocess.run(["nm", "-u", "-P", str(obj)], capture_output=True, text=True)
    return {line.split()[0] for line in run.stdout.splitlines() if line.strip()}


def demangle(symbols):
    run = subprocess.run(["c++filt"], input="\n".join(sorted(symbols)), capture_output=True, text=True)
    return run.stdout.split("\n")[:len(symbols)] if run.returncode == 0 else sorted(symbols)


# ---- reading a submission --------------------------------------------------------------------
def safe_extract(archive, into, notes):
    """Extract the regular files of a zip that stay inside `into`; skip and note the others."""
    try:
        zf = zipfile.ZipFile(archive)
    except (zipfile.BadZipFile, OSError) as error:
        raise GradeError(f"{archive}: not a readable zip file ({error})") from None
    total = 0
    with zf:
        for info in zf.infolist()[:5000]:
            name = info.filename
            kind = (info.external_attr >> 16) & 0o170000
            parts = pathlib.PurePosixPath(name.replace("\\", "/")).parts
            if name.startswith(("/", "\\")) or re.match(r"^[A-Za-z]:", name) or ".." in parts:
                notes.append(f"skipped zip entry '{name}': its path leads outside the submission")
                continue
            if kind == stat.S_IFLNK:
                notes.append(f"skipped zip entry '{name}': symbolic links are not accepted")
                continue
            if info.is_dir() or not parts:
                continue
            if info.file_size > MAX_FILE_BYTES or total + info.file_size > 50 * MAX_FILE_BYTES:
                notes.append(f"skipped zip entry '{name}': too large ({info.file_size} bytes)")
                continue
            target = into.joinpath(*parts)
            target.parent.mkdir(parents=True, exist_ok=True)
            with zf.open(info) as source:
                data = source.read(MAX_FILE_BYTES + 1)
            total += len(data)
            target.write_bytes(data[:MAX_FILE_BYTES])


def find_lab_folder(root, lab):
    """The submission's folder for a lab: a folder named like the lab (01_rope), the shallowest,
    else the submission's top folder when it holds files of the lab's skeleton."""
    best = None
    for dirpath, dirnames, _ in os.walk(root):
        depth = len(pathlib.Path(dirpath).relative_to(root).parts)
        dirnames[:] = [d for d in dirnames if not d.startswith((".", "__MACOSX")) and depth < 5]
        if lab.dir in dirnames:
            candidate = pathlib.Path(dirpath) / lab.dir
            if best is None or len(candidate.parts) < len(best.parts):
                best = candidate
    if best is not None:
        return best
    skeleton_names = {p.name for p in lab.skeleton.iterdir() if p.suffix in (".cpp",)}
    if any((root / n).is_file() for n in skeleton_names):
        return root
    return None


def collect_sources(folder, notes, label, skeleton):
    """The submitted exercise files of a lab folder (the .cpp files of the released skeleton
    folder); any other file that differs from the release is noted and ignored."""
    exercise_files = {p.name for p in skeleton.iterdir() if p.suffix in SOURCE_SUFFIXES}
    files, ignored = {}, []
    for path in sorted(folder.iterdir()):
        if path.name not in exercise_files:
            released = skeleton / path.name
            if path.is_file() and not path.is_symlink() and not (
                    released.is_file() and released.read_bytes() == path.read_bytes()):
                ignored.append(path.name)
            continue
        if path.is_symlink():
            notes.append(f"{label}/{path.name}: a symbolic link, ignored (submit the file itself)")
            continue
        if not path.is_file():
            continue
        if path.stat().st_size > MAX_FILE_BYTES:
            notes.append(f"{label}/{path.name}: larger than {MAX_FILE_BYTES} bytes, ignored")
            continue
        files[path.name] = path.read_bytes()
    if ignored:
        notes.append(f"{label}: not graded (only the exercise files are compiled, against the framework's "
                     f"headers and given code): {', '.join(ignored)}")
    return files


# ---- grading one lab of one submission -------------------------------------------------------
class LabGrader:
    def __init__(self, cache, lab, work, sandbox, compile_sandbox, jobs, seed):
        self.cache, self.lab, self.work, self.jobs, self.seed = cache, lab, work, jobs, seed
        self.sandbox, self.compile_sandbox = sandbox, compile_sandbox
        self.build = cache.lab(lab, sandbox)
        self.notes = []

    def grade(self, submitted):
        """Compile, check, link and test; a LabResult whatever the student's code does."""
        lab, notes = self.lab, self.notes
        skeleton = {p.name: p.read_bytes() for p in lab.skeleton.iterdir() if p.suffix in SOURCE_SUFFIXES}
        if not submitted:
            return grade.failed_lab(lab.manifest, f"no files of {lab.dir} in the submission",
                                    [f"the submission has no folder or files for {lab.dir}: every test scores 0"])
        files = dict(skeleton)
        files.update(submitted)
        missing = sorted(set(skeleton) - set(submitted))
        if missing:
            notes.append(f"missing from the submission, taken from the released skeleton (their exercises "
                         f"score 0): {', '.join(missing)}")

        # Compile; a file that reaches for the instructor's code is graded as the skeleton's.
        objects, errors = self.compile_all(files)
        if errors:
            return grade.failed_lab(lab.manifest, f"{lab.dir} does not compile; see the note above",
                                    notes + [f"{lab.dir} does not compile, so every test of this lab scores 0. "
                                             f"The compiler's first errors:\n{errors}"])
        replaced = self.find_cheats(files, objects)
        if replaced:
            for name in replaced:
                if name in skeleton:
                    files[name] = skeleton[name]
                else:
                    del files[name]
            objects, errors = self.compile_all(files)
            if errors:
                return grade.failed_lab(lab.manifest, "does not compile with the skeleton's files", notes + [errors])

        binary, errors = self.link(objects)
        if errors:
            return grade.failed_lab(lab.manifest, f"{lab.dir} does not link; see the note above",
                                    notes + [f"{lab.dir} compiles but does not link, so every test of this lab "
                                             f"scores 0. The linker's first errors:\n{errors}"])
        started = time.monotonic()
        results = grade.grade_binary(str(binary), lab.manifest, self.seed, self.sandbox, self.jobs,
                                     present=self.build.tests_present)
        return grade.LabResult(lab.manifest, results, notes, self.seed, time.monotonic() - started)

    # -- compiling
    def compile_all(self, files):
        src, obj = self.work / "src", self.work / "obj"
        for folder in (src, obj):
            shutil.rmtree(folder, ignore_errors=True)
            folder.mkdir(parents=True)
        for name, data in files.items():
            (src / name).write_bytes(data)
        ids = self.compile_sandbox.identity()
        for path in [src, *src.iterdir()]:
            os.chmod(path, 0o755 if path.is_dir() else 0o644)
        if ids:
            os.chown(obj, *ids)
        headers = b"".join(hashlib.sha256(files[n]).digest() for n in sorted(files) if not n.endswith(".cpp"))
        sources = sorted(n for n in files if n.endswith(".cpp"))
        with concurrent.futures.ThreadPoolExecutor(max_workers=self.jobs) as pool:
            outcomes = list(pool.map(lambda n: self.compile_one(n, files[n], headers), sources))
        errors = [e for _, e in outcomes if e]
        if errors:
            return None, "\n".join(errors)
        return [o for o, _ in outcomes], None

    def compile_one(self, name, data, headers):
        """Compile src/<name> to an object, or reuse the same compile of an earlier submission."""
        flags = self.build.compile_argv + ["-Isrc"]
        # The key covers the instructor's headers too: an object compiled against an older
        # Simulation (another vtable) must never be linked with the new framework.
        headers += include_digest(tuple(flags))
        key = hashlib.sha256(json.dumps(flags).encode() + b"\0" + name.encode() + b"\0" + data + headers).hexdigest()
        cached = self.cache.objects / f"{key}.o"
        deps_cached = self.cache.objects / f"{key}.d"
        private = self.work / "objects"  # the grader's copies, out of the sandbox user's reach
        private.mkdir(exist_ok=True)
        if cached.exists() and deps_cached.exists():
            shutil.copyfile(cached, private / f"{name}.o")
            shutil.copyfile(deps_cached, private / f"{name}.d")
            return private / f"{name}.o", None
        argv = flags + ["-fdiagnostics-color=never", "-MD", "-MF", f"obj/{name}.d",
                        "-o", f"obj/{name}.o", "-c", f"src/{name}"]
        run = grade.run_sandboxed(argv, self.compile_sandbox, cwd=self.work)
        if run.returncode is None:
            return None, f"{name}: compiling took longer than {self.compile_sandbox.timeout:g} s"
        if run.returncode != 0:
            outside = self.outside_includes(flags, name)
            if outside:
                return None, f"{name} includes {outside}, a file outside the submission and the framework"
            return None, first_errors(run.output)
        if run.output.strip():
            self.notes.append(f"{name}: the compiler warns:\n{grade.tail(run.output, 12)}")
        # Copy out of the sandbox user's folder before anything reads it.
        shutil.copyfile(self.work / "obj" / f"{name}.o", private / f"{name}.o")
        shutil.copyfile(self.work / "obj" / f"{name}.d", private / f"{name}.d")
        for source, target in ((private / f"{name}.o", cached), (private / f"{name}.d", deps_cached)):
            temporary = target.with_name(f"{target.name}.{os.getpid()}.{threading.get_ident()}")
            shutil.copyfile(source, temporary)
            os.replace(temporary, target)  # whole or absent, for graders running side by side
        return private / f"{name}.o", None

    # -- the checks
    def allowed_folders(self):
        """The submission's own files, the include folders of the lab's flags, the system's."""
        allowed = [(self.work / "src").resolve(), pathlib.Path("/usr")]
        allowed += [pathlib.Path(f[2:] if f.startswith("-I") else f).resolve()
                    for i, f in enumerate(self.build.compile_argv)
                    if f.startswith("-I") or (i > 0 and self.build.compile_argv[i - 1] == "-isystem")]
        return allowed

    def outside_includes(self, flags, name):
        """The first file a source includes from outside the allowed folders (names only:
        the compiler's error messages could quote such a file)."""
        run = subprocess.run(flags + ["-M", "-MG", f"src/{name}"], cwd=self.work, capture_output=True, text=True)
        allowed = self.allowed_folders()
        for dep in parse_depfile(run.stdout):
            path = pathlib.Path(dep)
            resolved = (self.work / path).resolve() if not path.is_absolute() else path.resolve()
            if not any(resolved.is_relative_to(folder) for folder in allowed):
                return dep
        return None

    def find_cheats(self, files, objects):
        """Files to grade as the skeleton's: they include the instructor's files, call the
        reference solution, or redefine the framework's, GoogleTest's or the grader's symbols."""
        allowed = self.allowed_folders()
        flagged = {}
        for obj in objects:
            name = obj.name[:-2]
            deps = obj.with_suffix(".d")
            for dep in parse_depfile(deps.read_text()) if deps.exists() else []:
                path = pathlib.Path(dep)
                resolved = (self.work / path).resolve() if not path.is_absolute() else path.resolve()
                inside = any(resolved.is_relative_to(folder) for folder in allowed)
                if not inside:
                    flagged.setdefault(name, f"includes {dep}, a file outside the submission and the framework")
                    break
            used = undefined_symbols(obj) & self.build.oracle_symbols
            if used:
                flagged.setdefault(name, "calls the reference solution (" + ", ".join(demangle(used)[:3]) + ")")
            defined = defined_symbols([obj]) & self.build.protected_symbols
            if defined:
                flagged.setdefault(name, "redefines symbols of the framework, GoogleTest or the grader ("
                                   + ", ".join(demangle(defined)[:3]) + ")")
        for name, why in flagged.items():
            lost = exercises_in(self.lab.solution / name)
            what = f"exercise {', '.join(lost)} scores 0" if lost else "it was left out"
            self.notes.append(f"{name} {why}: it is graded as the released skeleton's {name}, so {what}"
                              if name in {p.name for p in self.lab.skeleton.iterdir()} else
                              f"{name} {why}: it was left out of the build")
        return sorted(flagged)

    # -- linking
    def link(self, objects):
        bin_dir = self.work / "bin"
        shutil.rmtree(bin_dir, ignore_errors=True)
        bin_dir.mkdir()
        library = bin_dir / f"libstudent_{self.lab.name}.a"
        members = [*map(str, objects), *map(str, self.build.given_objects)]
        run = subprocess.run(["ar", "rcs", str(library), *members], capture_output=True, text=True)
        if run.returncode != 0:
            return None, run.stderr
        binary = bin_dir / f"{self.lab.name}_grading"
        argv = [str(library) if a == "STUDENT_LIB" else str(binary) if a == "OUTPUT" else a
                for a in self.build.link_argv]
        run = subprocess.run(argv, cwd=self.build.link_dir, capture_output=True, text=True)
        if run.returncode != 0:
            return None, first_errors(run.stdout + run.stderr)
        os.chmod(bin_dir, 0o755)
        os.chmod(binary, 0o755)
        return binary, None


def parse_depfile(text):
    body = text.replace("\\\n", " ")
    _, _, deps = body.partition(": ")
    return [d.replace("\\ ", " ") for d in re.split(r"(?<!\\)\s+", deps.strip()) if d]


def first_errors(output, lines=25):
    """The compiler's first error lines, paths shortened to the file names students know."""
    text = re.sub(r"(^|\s)(?:\S*/)?src/", r"\1", output)
    keep = [line for line in text.splitlines() if line.strip()]
    first = next((i for i, line in enumerate(keep) if "error" in line), 0)
    return "\n".join(keep[max(0, first - 2):first + lines])


# ---- grading one submission ------------------------------------------------------------------
@dataclasses.dataclass
class Graded:
    name: str
    labs: list
    notes: list
    seconds: float

    @property
    def score(self):
        return sum(lab.score for lab in self.labs)

    @property
    def max_score(self):
        return sum(lab.max_score for lab in self.labs)


@functools.lru_cache(maxsize=None)
def include_digest(flags):
    """A digest of every header in the compile's include folders inside the project tree."""
    digest = hashlib.sha256()
    for flag in flags:
        if not flag.startswith("-I"):
            continue
        folder = pathlib.Path(flag[2:])
        if not folder.is_absolute() or not folder.is_dir() or folder == pathlib.Path("/usr/include"):
            continue
        for header in sorted(folder.rglob("*")):
            if header.is_file() and header.suffix in (".hpp", ".h", ".hh", ".inl"):
                digest.update(str(header).encode() + b"\0" + header.read_bytes())
    return digest.digest()


def grade_submission(submission, cache, labs, seed, jobs, sandbox, compile_sandbox, name=None):
    submission = pathlib.Path(submission)
    if not submission.exists():
        raise GradeError(f"{submission}: no such file or folder")
    started = time.monotonic()
    notes = []
    base = pathlib.Path(tempfile.mkdtemp(prefix="springlab-grade-"))
    os.chmod(base, 0o711)  # the sandbox user may enter known paths, never list them
    try:
        if submission.is_dir():
            root = submission
        elif zipfile.is_zipfile(submission):
            root = base / "unpacked"
            root.mkdir()
            safe_extract(submission, root, notes)
        else:
            raise GradeError(f"{submission}: neither a folder nor a zip file")
        results = []
        found_any = False
        for lab in labs:
            folder = find_lab_folder(root, lab)
            lab_notes = []
            submitted = collect_sources(folder, lab_notes, lab.dir, lab.skeleton) if folder else {}
            found_any |= bool(submitted)
            work = base / lab.dir
            work.mkdir()
            os.chmod(work, 0o711)
            grader = LabGrader(cache, lab, work, sandbox, compile_sandbox, jobs, seed)
            grader.notes.extend(lab_notes)
            results.append(grader.grade(submitted))
        if not found_any:
            notes.append("the submission holds no lab files (" + ", ".join(lab.dir for lab in labs)
                         + "): nothing to grade, every test scores 0")
        return Graded(name or submission.name, results, notes, time.monotonic() - started)
    finally:
        shutil.rmtree(base, ignore_errors=True)


def write_submission(graded, out, seed):
    grade.write_outputs(out, graded.labs, f"Grade of {graded.name}", graded.seconds, seed, graded.notes)


# ---- commands --------------------------------------------------------------------------------
def common_options(ap):
    ap.add_argument("--cache", default=str(ROOT / "build-grader"),
                    help="build folder of the framework and tests, reused across runs (default: build-grader/)")
    ap.add_argument("--no-build", action="store_true", help="use the cache build as it is (do not run cmake)")
    ap.add_argument("--seed", type=int, help="seed of the random test inputs (default: drawn and printed)")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="processes at once (default: cores)")
    ap.add_argument("--timeout", type=float, default=grade.TIMEOUT, help="seconds per test")
    ap.add_argument("--memory-limit-mb", type=int, default=4096, help="address space per test; 0 = none")


def setup(args):
    labs = discover_labs()
    if not (ROOT / "solutions").exists():
        raise GradeError(f"{ROOT}: no solutions/ folder: grading needs the instructor tree, not a student release")
    sandbox = grade.Sandbox(timeout=args.timeout, memory_mb=args.memory_limit_mb)
    compile_sandbox = grade.Sandbox(timeout=COMPILE_TIMEOUT, memory_mb=0, file_mb=256)
    cache = Cache(args.cache, labs, build=not args.no_build, jobs=args.jobs)
    if compile_sandbox.identity():
        # The compiler runs as the sandbox user only if that user can read the framework's
        # headers (not so in a checkout under /root); else as us, with the include check below.
        folders = {f[2:] for lab in labs for f in cache.lab(lab, sandbox).compile_argv if f.startswith("-I")}
        probe = grade.run_sandboxed(["/bin/sh", "-c", " && ".join(f"test -r {shlex.quote(d)} -a -x {shlex.quote(d)}"
                                                                  for d in sorted(folders)) or "true"], compile_sandbox)
        if probe.returncode != 0:
            compile_sandbox.drop_to = None
    return labs, cache, sandbox, compile_sandbox, grade.draw_seed(args.seed)


def cmd_grade(args):
    if not pathlib.Path(args.submission).exists():
        raise GradeError(f"{args.submission}: no such file or folder")
    labs, cache, sandbox, compile_sandbox, seed = setup(args)
    out = pathlib.Path(args.out or ROOT / "out" / "grades" / pathlib.Path(args.submission).resolve().name)
    graded = grade_submission(args.submission, cache, labs, seed, args.jobs, sandbox, compile_sandbox)
    print(f"Grade of {args.submission} (SPRINGLAB_SEED={seed})")
    for note in graded.notes:
        print(f"  note: {note}")
    for lab in graded.labs:
        grade.print_lab(lab, quiet=args.quiet)
    percent = 100.0 * graded.score / graded.max_score if graded.max_score else 0.0
    print(f"Total: {graded.score:g} / {graded.max_score:g} points ({percent:.1f} %) in {graded.seconds:.1f} s")
    write_submission(graded, out, seed)
    print(f"report: {out / 'report.md'}, Gradescope: {out / 'results.json'}, JUnit: {out / 'junit.xml'}")
    if args.expect_percent is not None and abs(percent - args.expect_percent) > 1e-9:
        print(f"expected {args.expect_percent:g} %, got {percent:.1f} %", file=sys.stderr)
        return 1
    return 0


def submissions_in(folder):
    folder = pathlib.Path(folder)
    if not folder.is_dir():
        raise GradeError(f"{folder}: not a folder of submissions")
    entries = [p for p in sorted(folder.iterdir()) if not p.name.startswith(".")
               and (p.is_dir() or (p.is_file() and p.suffix == ".zip"))]
    if not entries:
        raise GradeError(f"{folder}: holds no submission folders or .zip files")
    names = [p.stem if p.is_file() else p.name for p in entries]
    duplicate = sorted({n for n in names if names.count(n) > 1})
    if duplicate:
        raise GradeError(f"{folder}: two submissions for {', '.join(duplicate)} (a folder and a zip?)")
    return list(zip(names, entries))


def cmd_grade_all(args):
    entries = submissions_in(args.folder)
    labs, cache, sandbox, compile_sandbox, seed = setup(args)
    out = pathlib.Path(args.out or ROOT / "out" / "grades" / pathlib.Path(args.folder).resolve().name)
    out.mkdir(parents=True, exist_ok=True)
    for lab in labs:  # find each lab's build once, before the workers start
        cache.lab(lab, sandbox)
    print(f"grading {len(entries)} submissions from {args.folder}, {args.jobs} at once (SPRINGLAB_SEED={seed})",
          file=sys.stderr)
    started = time.monotonic()
    done = [0]
    lock = threading.Lock()

    def one(entry):
        name, path = entry
        try:
            graded = grade_submission(path, cache, labs, seed, 1, sandbox, compile_sandbox, name=name)
            write_submission(graded, out / name, seed)
            line = f"{graded.score:g}/{graded.max_score:g}"
        except GradeError as error:
            graded, line = None, f"error: {error}"
        with lock:
            done[0] += 1
            print(f"[{done[0]:{len(str(len(entries)))}}/{len(entries)}] {name}: {line} "
                  f"({time.monotonic() - started:.0f} s)", file=sys.stderr, flush=True)
        return name, graded

    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        graded_all = list(pool.map(one, entries))
    write_gradebook(out / "gradebook.csv", labs, graded_all)
    print(f"gradebook: {out / 'gradebook.csv'} ({len(entries)} students, {time.monotonic() - started:.1f} s); "
          f"reports in {out}/<student>/")
    return 0


def write_gradebook(path, labs, graded_all):
    header = ["student"]
    for lab in labs:
        header += [f"{lab.dir} {ex['id']}" for ex in lab.manifest["exercises"]] + [f"{lab.dir} total"]
    header += ["total", "max", "percent", "notes"]
    with open(path, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(header)
        for name, graded in graded_all:
            row = [name]
            if graded is None:
                writer.writerow(row + [""] * (len(header) - 5) + ["0", str(sum(lab.manifest["points"] for lab in labs)),
                                                                   "0.0", "not graded"])
                continue
            for lab_result in graded.labs:
                row += [f"{lab_result.exercise_score(ex):g}" for ex in lab_result.manifest["exercises"]]
                row.append(f"{lab_result.score:g}")
            notes = [n.splitlines()[0] for lab in graded.labs for n in lab.notes if "does not" in n] + graded.notes
            percent = 100.0 * graded.score / graded.max_score if graded.max_score else 0.0
            row += [f"{graded.score:g}", f"{graded.max_score:g}", f"{percent:.1f}", "; ".join(notes)[:300]]
            writer.writerow(row)


def main():
    ap = argparse.ArgumentParser(prog="springlab", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="command", required=True)
    one = sub.add_parser("grade", help="grade one submission")
    one.add_argument("submission", help="a labs/ folder, a folder holding one, or a .zip")
    one.add_argument("--out", help="folder for report.md, results.json, junit.xml (default: out/grades/<name>/)")
    one.add_argument("--quiet", action="store_true", help="print only the totals")
    one.add_argument("--expect-percent", type=float, help="exit 1 unless the total is this percentage (for CI)")
    common_options(one)
    many = sub.add_parser("grade-all", help="grade every submission folder or .zip under a folder")
    many.add_argument("folder")
    many.add_argument("--out", help="folder for gradebook.csv and the reports (default: out/grades/<folder>/)")
    common_options(many)
    prepare = sub.add_parser("prepare", help="build the grading cache only (the autograder's setup.sh)")
    common_options(prepare)
    args = ap.parse_args()
    try:
        if args.command == "prepare":
            labs, cache, sandbox, _, _ = setup(args)
            for lab in labs:
                cache.lab(lab, sandbox)
            print(f"grading cache ready in {cache.path}: {', '.join(lab.dir for lab in labs)}")
            return 0
        return cmd_grade(args) if args.command == "grade" else cmd_grade_all(args)
    except GradeError as error:
        print(f"springlab grade: {error}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
