"""Grading submissions: for one lab of one submission, compile its exercise files in the
sandbox (the object cache skips repeats), replace the files the integrity checks flag by the
skeleton's, archive the objects with the lab's given objects, link the grading program as CMake
wrote it down, and run every test in the sandbox; then whole submissions and whole classes."""
import concurrent.futures
import dataclasses
import functools
import hashlib
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile
import threading
import time

from . import compile_errors, integrity
from .build_cache import Cache
from .compile_errors import first_errors
from .errors import GradeError
from .gtest_runner import Budget, BudgetRule, draw_seed, grade_binary, grade_judged
from .labs import ROOT, discover_labs, exercises_in
from .reports import write_submission
from .results import Graded, LabResult, TestResult, failed_lab
from .sandbox import TIMEOUT, Sandbox, tail
from .sealed_compile import compile_sandbox as make_compile_sandbox
from .sealed_compile import scrub, stop_reason
from .staging import stage
from .submission import SOURCE_SUFFIXES, collect_sources, locate_labs, unpack

# The time budget of a lab's tests: BUDGET_FLOOR seconds plus BUDGET_FACTOR times the
# reference's own CPU time on them, in CPU seconds, shared among its files (BudgetRule); a
# submission's is the sum of its labs'. A judged test runs two processes and streams a trace,
# about twice the reference's one process: 10 leaves five times that of slack.
BUDGET_FACTOR = 10.0
BUDGET_FLOOR = 120.0
# What a lab may cost a grading slot, whatever its code does: its compiles may use
# COMPILE_BUDGET CPU seconds together (an honest exercise file takes about 3), and the whole lab
# (compiles, links, tests) LAB_WALL_LIMIT seconds of wall time: no compile or test starts after
# it, and none runs past it (each one's time limit is cut to what is left). The worst case for
# one lab is therefore LAB_WALL_LIMIT and the links of what compiled in time (a second each):
# under five minutes. An honest lab takes under a minute cold on an idle machine.
COMPILE_BUDGET = 90.0
LAB_WALL_LIMIT = 270.0


def object_key(objects, compile_argv, sealed, name, data, headers):
    """The object cache's key of one exercise file's compile. It holds the places the compile
    reads its include folders from: an object's dependency file names them, and the include
    check reads them. Sealed, those are the neutral paths inside the sandbox (the same for
    every grader of this tree); without bubblewrap they are this grader's own staged copies
    under /tmp, so a compile is reused only by the grader that staged them (another grader's
    object would name folders this one does not allow, and its file would be graded as the
    skeleton's)."""
    shown = [str(place) for place in sealed.include_folders()] + [str(sealed.sealed)]
    return objects.key(compile_argv + ["-Isrc"] + shown, name, data, headers)


class LabGrader:
    """One lab of one submission. Points follow the exercise: for each exercise file F, a
    grading program links the student's F with the reference's objects of every other file
    (and the given code, tests and oracle), and runs only the tests of F's exercises, so a bug
    in one exercise costs that exercise's points alone. A file that does not compile, or that
    the integrity checks flag, is the skeleton's: its exercises score 0, the rest is graded."""

    def __init__(self, cache, lab, work, sandbox, compile_sandbox, jobs, seed, budget=None, slot=0,
                 call_check=True, budget_rule=None):
        self.cache, self.lab, self.work, self.jobs, self.seed = cache, lab, work, jobs, seed
        self.call_check = call_check  # off only to test the sandbox behind it (sabotage.py)
        self.slot = slot  # which sandbox user this submission's workers run as
        self.sandbox, self.compile_sandbox = sandbox, compile_sandbox
        self.build = cache.lab(lab, sandbox)
        self.budget = budget
        self.budget_rule = budget_rule  # how the lab's budget is shared among its files
        self.notes = []
        self.links = 0
        self.timing = {"compile": 0.0, "link": 0.0, "test": 0.0}
        self.compile_cpu = 0.0  # CPU seconds its compiles used (COMPILE_BUDGET)
        self.compile_lock = threading.Lock()

    def grade(self, submitted):
        """Compile, check, link and test; a LabResult whatever the student's code does."""
        lab, notes, build = self.lab, self.notes, self.build
        started = time.monotonic()
        skeleton = {p.name: p.read_bytes() for p in lab.skeleton.iterdir() if p.suffix in SOURCE_SUFFIXES}
        if not submitted:
            return failed_lab(lab.manifest, f"{lab.dir} was not submitted",
                              [f"{lab.dir}: not submitted (no folder or exercise files of this lab in the "
                               f"submission): every test of this lab scores 0"])
        files = dict(skeleton)
        files.update(submitted)
        missing = sorted(set(skeleton) - set(submitted))
        if missing:
            notes.append(f"missing from the submission, taken from the released skeleton (their exercises "
                         f"score 0): {', '.join(missing)}")
        file_exercises = {name: exercises_in(lab.solution / name) for name in skeleton}
        # Why a file is graded as the skeleton's; the message its tests get.
        reasons = {name: f"{name} was not submitted: the released skeleton's file, not done" for name in missing}
        for name in skeleton:
            if name in submitted and submitted[name] == skeleton[name]:
                reasons[name] = f"{name} is the released skeleton's file, unchanged: not done yet"
        changed = {n: d for n, d in files.items() if n not in reasons}

        mark = time.monotonic()
        objects, errors = self.compile_all(files, changed)
        self.timing["compile"] = time.monotonic() - mark
        for name, error in sorted(errors.items()):
            # The first error placed in the file and its hint (the same summary `check` prints),
            # then the compiler's first lines.
            first = compile_errors.summary(error, lambda path, n=name: pathlib.PurePath(path).name == n,
                                           root=self.work / "src")
            notes.append(compile_errors.not_compiling_note(name, file_exercises.get(name, []), first,
                                                           f"The compiler's first errors:\n{error}"))
            reasons[name] = compile_errors.NOT_COMPILING.format(name=name)
        solution = self.object_map(build.link.solution_objects)
        skeleton_objects = self.object_map(build.link.skeleton_objects)
        per_file = bool(solution) and all(n in solution and n in skeleton_objects for n in skeleton)
        others = {}
        if per_file:
            symbols = {n: reference_symbols(solution[n]) for n in skeleton}
            others = {n: set().union(*(s for m, s in symbols.items() if m != n)) for n in skeleton}
        for name in integrity.find_cheats(list(objects.values()), self.work, build, lab, notes, others,
                                          call_check=self.call_check):
            objects.pop(name, None)
            reasons[name] = integrity.REPLACED.format(name=name)

        if not per_file:
            results = self.grade_whole(objects, skeleton_objects, reasons)
            if isinstance(results, LabResult):
                return results
        elif build.link.judges:
            results = self.grade_judged(objects, solution, file_exercises, reasons)
        else:
            results = self.grade_per_file(objects, solution, file_exercises, reasons)
        self.timing["links"] = self.links
        self.timing["compile_cpu"] = self.compile_cpu
        return LabResult(lab.manifest, results, notes, self.seed, time.monotonic() - started, dict(self.timing))

    @staticmethod
    def object_map(paths):
        """{exercise file name: its object} from CMake's object paths (.../spring_force.cpp.o)."""
        return {pathlib.Path(p).name[:-2]: pathlib.Path(p) for p in paths if p.endswith(".o")}

    def wanted_tests(self):
        present = self.build.tests_present
        return [(ex, t) for ex in self.lab.manifest["exercises"] for t in ex["tests"]
                if t["name"] in present or t["visibility"] == "visible"]

    def grade_per_file(self, objects, solution, file_exercises, reasons):
        """One program per exercise file the student did: their file, the reference's others."""
        owner = {ex_id: name for name, ids in file_exercises.items() for ex_id in ids}
        by_file = {}
        for ex, t in self.wanted_tests():
            by_file.setdefault(owner.get(ex["id"]), []).append(t["name"])
        programs, failed = {}, {}
        for name, tests in by_file.items():
            if name is None:  # an exercise no file claims: every student file, the skeleton's for the rest
                members = [objects.get(n, solution[n]) if n in objects else self.skeleton_object(n) for n in solution]
                programs["whole lab"] = (members, tests)
            elif name in reasons:
                failed.update({test: reasons[name] for test in tests})
            else:
                members = [objects[name], *(obj for n, obj in solution.items() if n != name)]
                programs[name] = (members, tests)
        binaries = self.link_all({k: m for k, (m, _) in programs.items()})
        outcome = {}
        for key, (_, tests) in programs.items():
            binary, error = binaries[key]
            if error:
                failed.update(self.does_not_link(key, error, tests))
                continue
            mark = time.monotonic()
            for r in grade_binary(str(binary), self.lab.manifest, self.seed, self.sandbox, self.jobs,
                                  present=self.build.tests_present, only=set(tests), budget=self.budget,
                                  slot=self.slot, seccomp=self.build.link.worker_seccomp):
                outcome[r.test["name"]] = r
            self.timing["test"] += time.monotonic() - mark
        return [outcome.get(t["name"]) or TestResult(ex, t, False, failed.get(t["name"], "not run"), 0.0)
                for ex, t in self.wanted_tests()]

    def grade_judged(self, objects, solution, file_exercises, reasons):
        """Each exercise file the student did as a worker (their file, renamed, with the
        reference's other files) whose call trace the file's judge replays: the verdict comes
        from the judge, which runs no student code (tests/support/call_trace.hpp)."""
        owner = {ex_id: name for name, ids in file_exercises.items() for ex_id in ids}
        by_file = {}
        for ex, t in self.wanted_tests():
            by_file.setdefault(owner.get(ex["id"]), []).append(t["name"])
        functions = self.build.link.exercise_functions()
        from .judged_run import bubblewrap, isolation, seccomp_filter
        seccomp = self.build.link.worker_seccomp
        if bubblewrap() is None or not seccomp_filter(seccomp):
            self.notes.append(f"sandbox: {isolation(seccomp)}")
        workers, failed = {}, {}
        # What each student object defines, read once for all files (nm is slow to start).
        defined = integrity.symbols_by_file([objects[n] for n in by_file if n in objects])
        for name, tests in by_file.items():
            if name is None:
                failed.update({test: "no exercise file of the reference holds this exercise" for test in tests})
            elif name in reasons:
                failed.update({test: reasons[name] for test in tests})
            elif name not in self.build.link.judges:
                failed.update({test: f"the grading build has no judge for {name}; rebuild it" for test in tests})
            else:
                renamed, error = self.rename_exercises(name, objects[name], solution[name], functions.get(name, []),
                                                       defined.get(str(objects[name]), set()))
                if error:
                    self.notes.append(error)
                    failed.update({test: compile_errors.NOT_DEFINED.format(name=name) for test in tests})
                    continue
                members = [renamed, *(obj for n, obj in solution.items() if n != name)]
                workers[name] = (members, tests)
        binaries = self.link_all({k: m for k, (m, _) in workers.items()}, worker=True)
        outcome = {}
        for key, (_, tests) in workers.items():
            binary, error = binaries[key]
            if error:
                failed.update(self.does_not_link(key, error, tests))
                continue
            # Each file's tests have their share of the lab's budget: one that hangs cannot
            # spend the time of the others.
            share = None
            if self.budget is not None and self.budget_rule is not None:
                share = Budget(self.budget_rule.share(tests, len(workers)), parent=self.budget,
                               what=f"exercise file ({key})")
            mark = time.monotonic()
            for r in grade_judged(self.build.link.judges[key], str(binary), self.lab.manifest, self.seed,
                                  self.sandbox, self.jobs, only=set(tests), budget=share, slot=self.slot,
                                  seccomp=seccomp):
                outcome[r.test["name"]] = r
            self.timing["test"] += time.monotonic() - mark
        return [outcome.get(t["name"]) or TestResult(ex, t, False, failed.get(t["name"], "not run"), 0.0)
                for ex, t in self.wanted_tests()]

    def rename_exercises(self, name, student, reference, functions, defined):
        """The student's object of `name` with its exercise functions renamed
        springlab_student_<function> (the worker's record objects call them so); (object, None)
        or (None, a note) when the file lacks a function as the header declares it."""
        wanted = exercise_symbols(reference, self.lab.name, tuple(functions))
        missing = [function for symbol, function in wanted.items() if symbol not in defined]
        if missing:
            return None, compile_errors.not_defined_note(name, missing)
        out = self.work / "renamed"
        out.mkdir(exist_ok=True)
        mapping = out / f"{name}.map"
        mapping.write_text("".join(f"{symbol} springlab_student_{function}\n" for symbol, function in wanted.items()))
        renamed = out / f"{name}.o"
        run = subprocess.run(["objcopy", f"--redefine-syms={mapping}", str(student), str(renamed)],
                             capture_output=True, text=True)
        if run.returncode != 0:
            return None, f"{name}: its object could not be prepared for grading ({run.stderr.strip()})"
        return renamed, None

    def does_not_link(self, key, error, tests):
        """The note and the tests' message for an exercise file whose program does not link."""
        self.notes.append(f"{key} compiles but its grading program does not link (it must stand on its own "
                          f"beside the reference's other files), so its exercises score 0. "
                          f"The linker's first errors:\n{error}")
        return {test: f"{key} does not link (see the note)" for test in tests}

    def skeleton_object(self, name):
        return self.object_map(self.build.link.skeleton_objects)[name]

    def grade_whole(self, objects, skeleton_objects, reasons):
        """A build without per-file reference objects: one program of the student's files."""
        members = [objects[n] if n in objects else skeleton_objects[n] for n in sorted(set(objects) | set(reasons))
                   if n in objects or n in skeleton_objects]
        binary, error = self.link_all({"lab": members})["lab"]
        if error:
            return failed_lab(self.lab.manifest, f"{self.lab.dir} does not link; see the note above",
                              self.notes + [f"{self.lab.dir} compiles but does not link, so every test of this "
                                            f"lab scores 0. The linker's first errors:\n{error}"])
        return grade_binary(str(binary), self.lab.manifest, self.seed, self.sandbox, self.jobs,
                            present=self.build.tests_present, budget=self.budget, slot=self.slot,
                            seccomp=self.build.link.worker_seccomp)

    # -- compiling
    def compile_all(self, files, changed):
        """Compile the changed files; ({name: object}, {name: first errors})."""
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
        os.chmod(obj, 0o755)
        headers = b"".join(hashlib.sha256(files[n]).digest() for n in sorted(files) if not n.endswith(".cpp"))
        sources = sorted(n for n in changed if n.endswith(".cpp"))
        if sources and not self.build.sealed.sealed:
            self.notes.append("sandbox: the compiler runs without bubblewrap here (it cannot create namespaces), as "
                              "the sandbox user alone: it can read what that user can; install bubblewrap, or allow "
                              "user namespaces, to seal it")
        with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, self.jobs)) as pool:
            outcomes = dict(zip(sources, pool.map(lambda n: self.compile_one(n, files[n], headers), sources)))
        return ({n: o for n, (o, e) in outcomes.items() if not e}, {n: e for n, (o, e) in outcomes.items() if e})

    def compile_one(self, name, data, headers):
        """Compile src/<name> to an object in the compiler's sandbox (sealed_compile.py), or
        reuse the same compile of an earlier submission."""
        key = object_key(self.cache.objects, self.build.compile_argv, self.build.sealed, name, data, headers)
        private = self.work / "objects"  # the grader's copies, out of the sandbox user's reach
        private.mkdir(exist_ok=True)
        cached = self.cache.objects.fetch(key, private, name)
        if cached is not None:
            return cached, None
        late = self.budget.past_wall_limit() if self.budget else None
        if late is not None:
            return None, (f"{name}: not compiled: the lab had already taken {late.wall:.0f} s of wall time, its "
                          f"limit")
        with self.compile_lock:
            used = self.compile_cpu
        if used >= COMPILE_BUDGET:
            return None, (f"{name}: not compiled: the lab's files had already used {used:.0f} s of the compiler's "
                          f"CPU time, its budget of {COMPILE_BUDGET:g} s (an exercise file compiles in seconds)")
        # No compile runs past the lab's wall-time limit.
        left = self.budget.wall_left() if self.budget else None
        sandbox = self.compile_sandbox if left is None or left >= self.compile_sandbox.timeout else \
            dataclasses.replace(self.compile_sandbox, timeout=max(0.1, left))
        run = self.build.sealed.run(self.work, name, sandbox)
        with self.compile_lock:
            self.compile_cpu += run.cpu_seconds
        stopped = stop_reason(run, name)
        if stopped:
            return None, stopped
        output = scrub(run.output, self.grader_places())
        if run.returncode != 0:
            return None, first_errors(output)
        if output.strip():
            self.notes.append(f"{name}: the compiler warns:\n{tail(output, 12)}")
        # Copy out of the sandbox user's folder before anything reads it: plain files only.
        for suffix in (".o", ".d"):
            made = self.work / "obj" / f"{name}{suffix}"
            if made.is_symlink() or not made.is_file():
                return None, f"{name}: the compiler left no {suffix} file"
            shutil.copyfile(made, private / f"{name}{suffix}")
        self.cache.objects.store(key, private / f"{name}.o", private / f"{name}.d")
        return private / f"{name}.o", None

    def grader_places(self):
        """The grader's own paths, as a student must never read them in a message."""
        return {ROOT: "<grading tree>", self.cache.path: "<grading build>", stage().root: "/springlab",
                self.work.parent: "<grading folder>"}

    # -- linking
    def link_all(self, programs, worker=False):
        """{key: (binary, None) or (None, errors)} for {key: [exercise objects]}, side by side."""
        mark = time.monotonic()
        with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, self.jobs)) as pool:
            done = dict(zip(programs, pool.map(self.link, programs, programs.values(), [worker] * len(programs))))
        self.links += len(programs)
        self.timing["link"] += time.monotonic() - mark
        return done

    def link(self, key, objects, worker=False):
        tag = re.sub(r"[^A-Za-z0-9_]+", "_", key)
        bin_dir = self.work / "bin" / tag
        shutil.rmtree(bin_dir, ignore_errors=True)
        bin_dir.mkdir(parents=True)
        os.chmod(bin_dir.parent, 0o711)
        library = bin_dir / f"libstudent_{self.lab.name}.a"
        members = [*map(str, objects), *map(str, self.build.given_objects)]
        # q, not r: members of the same file name (a given and an exercise file) both stay.
        run = subprocess.run(["ar", "qcs", str(library), *members], capture_output=True, text=True)
        if run.returncode != 0:
            return None, run.stderr
        binary = bin_dir / f"{self.lab.name}_grading"
        argv = self.build.link.worker_argv(key, library, binary) if worker else self.build.link.argv(library, binary)
        run = subprocess.run(argv, cwd=bin_dir, capture_output=True, text=True)
        if run.returncode != 0:
            return None, first_errors(run.stdout + run.stderr)
        os.chmod(bin_dir, 0o755)
        os.chmod(binary, 0o755)
        return binary, None


@functools.lru_cache(maxsize=256)
def _exercise_symbols(path, stamp, lab, functions):
    run = subprocess.run(["nm", "-g", "--defined-only", "-P", path], capture_output=True, text=True)
    symbols = sorted(line.split()[0] for line in run.stdout.splitlines()
                     if len(line.split()) >= 2 and line.split()[1] in "TW")
    found = {}
    for symbol, readable in zip(symbols, integrity.demangle(symbols) if symbols else []):
        qualified = readable.split("(")[0]
        function = qualified.rsplit("::", 1)[-1]
        if qualified == f"springlab::{lab}::{function}" and function in functions:
            found[symbol] = function
    return found


def exercise_symbols(path, lab, functions):
    """{mangled symbol: function} of the exercise functions a reference object defines."""
    stat = os.stat(path)
    return dict(_exercise_symbols(str(path), (stat.st_mtime_ns, stat.st_size), lab, functions))


@functools.lru_cache(maxsize=256)
def _symbols(path, stamp):
    return frozenset(integrity.defined_symbols([path]))


def reference_symbols(path):
    """The strong symbols of a reference exercise object, read once per version of the file."""
    stat = os.stat(path)
    return _symbols(str(path), (stat.st_mtime_ns, stat.st_size))


# ---- one submission --------------------------------------------------------------------------
def grade_submission(submission, cache, labs, seed, jobs, sandbox, compile_sandbox, name=None, only=None,
                     budgets=None, slot=0, call_check=True, lab_wall_limit=LAB_WALL_LIMIT):
    """Grade a submission (a folder or a zip: a labs/ folder, a whole repository, lab folders
    or the flat files of one lab). `only`: the one lab to grade (--lab), the others are left
    out of the result; `budgets`: {lab name: its BudgetRule, or None for no budget}."""
    submission = pathlib.Path(submission)
    if not submission.exists():
        raise GradeError(f"{submission}: no such file or folder")
    if only is not None and not any(only in (lab.name, lab.dir) for lab in labs):
        raise GradeError(f"--lab {only}: no such lab (labs: {', '.join(lab.name for lab in labs)})")
    started = time.monotonic()
    notes = []
    base = pathlib.Path(tempfile.mkdtemp(prefix="springlab-grade-"))
    os.chmod(base, 0o711)  # the sandbox user may enter known paths, never list them
    budgets = budgets or {}
    graded_labs = [lab for lab in labs if only is None or only in (lab.name, lab.dir)]
    limits = [budgets[lab.name].limit if budgets.get(lab.name) else None for lab in graded_labs]
    total = Budget(sum(limits) if limits and None not in limits else None, what="submission")
    try:
        root = unpack(submission, base, notes)
        folders = locate_labs(root, labs, notes, only)
        results = []
        found_any = False
        for lab in graded_labs:
            folder = folders.get(lab.dir)
            lab_notes = []
            submitted = collect_sources(folder, lab_notes, lab.dir, lab.skeleton) if folder else {}
            found_any |= bool(submitted)
            work = base / lab.dir
            work.mkdir()
            os.chmod(work, 0o711)
            grader = LabGrader(cache, lab, work, sandbox, compile_sandbox, jobs, seed,
                               budget=Budget(budgets[lab.name].limit if budgets.get(lab.name) else None,
                                             parent=total, wall=lab_wall_limit),
                               slot=slot, call_check=call_check, budget_rule=budgets.get(lab.name))
            grader.notes.extend(lab_notes)
            results.append(grader.grade(submitted))
        if not found_any:
            notes.append("the submission holds no exercise files of " + ", ".join(lab.dir for lab in graded_labs)
                         + ": nothing to grade, every test scores 0")
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
    only: str = None            # --lab: the one lab graded
    budget_factor: float = BUDGET_FACTOR
    budget_floor: float = BUDGET_FLOOR
    budgets: dict = dataclasses.field(default_factory=dict)
    call_check: bool = True     # integrity.FORBIDDEN_CALLS; off only to test the sandbox
    lab_wall_limit: float = LAB_WALL_LIMIT

    def prepare(self):
        """Find each lab's build (compile flags, link, test list) and its time budget (a
        multiple of the reference's own grading time, measured once) now, not in a worker."""
        for lab in self.labs:
            if self.only is not None and self.only not in (lab.name, lab.dir):
                continue
            self.cache.lab(lab, self.sandbox)
            if lab.name not in self.budgets and self.budget_factor > 0:
                reference = self.cache.reference_times(lab, self.sandbox)
                self.budgets[lab.name] = (None if reference is None
                                          else BudgetRule(self.budget_floor, self.budget_factor, reference))

    def grade(self, path, jobs, name=None, slot=0):
        self.prepare()
        return grade_submission(path, self.cache, self.labs, self.seed, jobs, self.sandbox, self.compile_sandbox,
                                name=name, only=self.only, budgets=self.budgets, slot=slot,
                                call_check=self.call_check, lab_wall_limit=self.lab_wall_limit)


def start_session(cache_path, build=True, jobs=1, seed=None, timeout=TIMEOUT, memory_mb=4096, only=None,
                  budget_factor=BUDGET_FACTOR, budget_floor=BUDGET_FLOOR, call_check=True, lab_wall_limit=LAB_WALL_LIMIT):
    labs = discover_labs()
    if only is not None and not any(only in (lab.name, lab.dir) for lab in labs):
        raise GradeError(f"--lab {only}: no such lab (labs: {', '.join(lab.name for lab in labs)})")
    if not (ROOT / "solutions").exists():
        raise GradeError(f"{ROOT}: no solutions/ folder: grading needs the instructor tree, not a student release")
    sandbox = Sandbox(timeout=timeout, memory_mb=memory_mb)
    compile_sandbox = make_compile_sandbox()
    # With --lab, only that lab's grading programs are built (a Gradescope assignment per lab).
    cache = Cache(cache_path, [lab for lab in labs if only is None or only in (lab.name, lab.dir)] or labs,
                  build=build, jobs=jobs)
    if only is not None and not any(only in (lab.name, lab.dir) for lab in labs):
        raise GradeError(f"--lab {only}: no such lab (labs: {', '.join(lab.name for lab in labs)})")
    return Session(labs, cache, sandbox, compile_sandbox, draw_seed(seed), only, budget_factor, budget_floor,
                   call_check=call_check, lab_wall_limit=lab_wall_limit)


def grade_class(session, entries, out, jobs, progress=sys.stderr):
    """Grade (name, path) submissions side by side, writing each one's reports under out/<name>/;
    [(name, Graded or None when it could not be graded)] in the order given."""
    session.prepare()  # each lab's build once, before the workers start
    started = time.monotonic()
    done = [0]
    lock = threading.Lock()

    def one(indexed):
        slot, (name, path) = indexed
        try:
            # Each submission's workers run as a user of their own (judged_run.worker_uid).
            graded = session.grade(path, 1, name=name, slot=slot + 1)
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
        return list(pool.map(one, enumerate(entries)))
