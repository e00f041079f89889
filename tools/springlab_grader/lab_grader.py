"""Grading submissions: for one lab of one submission, compile its exercise files in the
sandbox (the object cache skips repeats), replace the files the integrity checks flag by the
skeleton's, archive the objects with the lab's given objects, link the grading program as CMake
wrote it down, and run every test in the sandbox; then whole submissions and whole classes."""
import concurrent.futures
import dataclasses
import hashlib
import os
import pathlib
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import threading
import time

from . import integrity
from .build_cache import Cache
from .errors import GradeError
from .gtest_runner import draw_seed, grade_binary
from .labs import ROOT, discover_labs
from .reports import write_submission
from .results import Graded, LabResult, failed_lab
from .sandbox import TIMEOUT, Sandbox, run_sandboxed, tail
from .submission import SOURCE_SUFFIXES, collect_sources, find_lab_folder, unpack

COMPILE_TIMEOUT = 180.0


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
            return failed_lab(lab.manifest, f"no files of {lab.dir} in the submission",
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
            return failed_lab(lab.manifest, f"{lab.dir} does not compile; see the note above",
                              notes + [f"{lab.dir} does not compile, so every test of this lab scores 0. "
                                       f"The compiler's first errors:\n{errors}"])
        replaced = integrity.find_cheats(objects, self.work, self.build, lab, self.notes)
        if replaced:
            for name in replaced:
                if name in skeleton:
                    files[name] = skeleton[name]
                else:
                    del files[name]
            objects, errors = self.compile_all(files)
            if errors:
                return failed_lab(lab.manifest, "does not compile with the skeleton's files", notes + [errors])

        binary, errors = self.link(objects)
        if errors:
            return failed_lab(lab.manifest, f"{lab.dir} does not link; see the note above",
                              notes + [f"{lab.dir} compiles but does not link, so every test of this lab "
                                       f"scores 0. The linker's first errors:\n{errors}"])
        started = time.monotonic()
        results = grade_binary(str(binary), lab.manifest, self.seed, self.sandbox, self.jobs,
                               present=self.build.tests_present)
        return LabResult(lab.manifest, results, notes, self.seed, time.monotonic() - started)

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
        key = self.cache.objects.key(flags, name, data, headers)
        private = self.work / "objects"  # the grader's copies, out of the sandbox user's reach
        private.mkdir(exist_ok=True)
        cached = self.cache.objects.fetch(key, private, name)
        if cached is not None:
            return cached, None
        argv = flags + ["-fdiagnostics-color=never", "-MD", "-MF", f"obj/{name}.d",
                        "-o", f"obj/{name}.o", "-c", f"src/{name}"]
        run = run_sandboxed(argv, self.compile_sandbox, cwd=self.work)
        if run.returncode is None:
            return None, f"{name}: compiling took longer than {self.compile_sandbox.timeout:g} s"
        if run.returncode != 0:
            outside = integrity.outside_includes(self.work, flags, name, self.build.compile_argv)
            if outside:
                return None, f"{name} includes {outside}, a file outside the submission and the framework"
            return None, first_errors(run.output)
        if run.output.strip():
            self.notes.append(f"{name}: the compiler warns:\n{tail(run.output, 12)}")
        # Copy out of the sandbox user's folder before anything reads it.
        shutil.copyfile(self.work / "obj" / f"{name}.o", private / f"{name}.o")
        shutil.copyfile(self.work / "obj" / f"{name}.d", private / f"{name}.d")
        self.cache.objects.store(key, private / f"{name}.o", private / f"{name}.d")
        return private / f"{name}.o", None

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
        run = subprocess.run(self.build.link.argv(library, binary), cwd=bin_dir, capture_output=True, text=True)
        if run.returncode != 0:
            return None, first_errors(run.stdout + run.stderr)
        os.chmod(bin_dir, 0o755)
        os.chmod(binary, 0o755)
        return binary, None


def first_errors(output, lines=25):
    """The compiler's first error lines, paths shortened to the file names students know."""
    text = re.sub(r"(^|\s)(?:\S*/)?src/", r"\1", output)
    keep = [line for line in text.splitlines() if line.strip()]
    first = next((i for i, line in enumerate(keep) if "error" in line), 0)
    return "\n".join(keep[max(0, first - 2):first + lines])


# ---- one submission --------------------------------------------------------------------------
def grade_submission(submission, cache, labs, seed, jobs, sandbox, compile_sandbox, name=None):
    submission = pathlib.Path(submission)
    if not submission.exists():
        raise GradeError(f"{submission}: no such file or folder")
    started = time.monotonic()
    notes = []
    base = pathlib.Path(tempfile.mkdtemp(prefix="springlab-grade-"))
    os.chmod(base, 0o711)  # the sandbox user may enter known paths, never list them
    try:
        root = unpack(submission, base, notes)
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


# ---- the grading session ---------------------------------------------------------------------
@dataclasses.dataclass
class Session:
    """What grading any submission against this tree needs, set up once."""
    labs: list
    cache: Cache
    sandbox: Sandbox          # the tests'
    compile_sandbox: Sandbox  # the compiler's
    seed: int

    def prepare(self):
        """Find each lab's build (compile flags, link, test list) now, not in a worker."""
        for lab in self.labs:
            self.cache.lab(lab, self.sandbox)


def start_session(cache_path, build=True, jobs=1, seed=None, timeout=TIMEOUT, memory_mb=4096):
    labs = discover_labs()
    if not (ROOT / "solutions").exists():
        raise GradeError(f"{ROOT}: no solutions/ folder: grading needs the instructor tree, not a student release")
    sandbox = Sandbox(timeout=timeout, memory_mb=memory_mb)
    compile_sandbox = Sandbox(timeout=COMPILE_TIMEOUT, memory_mb=0, file_mb=256)
    cache = Cache(cache_path, labs, build=build, jobs=jobs)
    if compile_sandbox.identity():
        # The compiler runs as the sandbox user only if that user can read the framework's
        # headers (not so in a checkout under /root); else as us, with the include check.
        folders = {f[2:] for lab in labs for f in cache.lab(lab, sandbox).compile_argv if f.startswith("-I")}
        probe = run_sandboxed(["/bin/sh", "-c", " && ".join(f"test -r {shlex.quote(d)} -a -x {shlex.quote(d)}"
                                                            for d in sorted(folders)) or "true"], compile_sandbox)
        if probe.returncode != 0:
            compile_sandbox.drop_to = None
    return Session(labs, cache, sandbox, compile_sandbox, draw_seed(seed))


def grade_class(session, entries, out, jobs, progress=sys.stderr):
    """Grade (name, path) submissions side by side, writing each one's reports under out/<name>/;
    [(name, Graded or None when it could not be graded)] in the order given."""
    session.prepare()  # each lab's build once, before the workers start
    started = time.monotonic()
    done = [0]
    lock = threading.Lock()

    def one(entry):
        name, path = entry
        try:
            graded = grade_submission(path, session.cache, session.labs, session.seed, 1, session.sandbox,
                                      session.compile_sandbox, name=name)
            write_submission(graded, out / name, session.seed)
            line = f"{graded.score:g}/{graded.max_score:g}"
        except GradeError as error:
            graded, line = None, f"error: {error}"
        with lock:
            done[0] += 1
            print(f"[{done[0]:{len(str(len(entries)))}}/{len(entries)}] {name}: {line} "
                  f"({time.monotonic() - started:.0f} s)", file=progress, flush=True)
        return name, graded

    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        return list(pool.map(one, entries))
