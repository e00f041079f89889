"""The instructor build the grader compiles and links submissions with (build-grader/, built
once and reused): configuring and building it, each lab's compile flags (from CMake's
compile_commands.json), its link (from grading/<name>_link.json, which tests/CMakeLists.txt
writes with file(GENERATE)), the symbols the integrity checks protect, and the cache of
compiled exercise objects, keyed by everything a compile reads."""
import dataclasses
import functools
import hashlib
import json
import os
import pathlib
import shlex
import shutil
import subprocess
import threading

from .errors import GradeError
from .gtest_runner import grade_binary, listed_tests
from .integrity import defined_symbols
from .link_file import LinkFile, read_link_file  # noqa: F401 (tests read the link file through here)
from .labs import ROOT
from .sandbox import tail
from .sealed_compile import sealed_compiler
from .staging import stage


# ---- one lab's compile and link --------------------------------------------------------------
@dataclasses.dataclass
class LabBuild:
    compile_argv: list      # compiler and flags, without -I of the lab, -o, -c
    link: LinkFile
    tests_present: set
    oracle_symbols: set     # strong symbols the reference "oracle" defines
    protected_symbols: set  # strong symbols of the framework, GoogleTest and the grading main
    sealed: object = None   # the compile as its sandbox runs it (sealed_compile.SealedCompiler)

    @property
    def given_objects(self):
        return self.link.given_objects


def compile_flags(commands, lab, where):
    """The compile flags of the lab's exercise objects (springlab_<name>_student_objects) from
    compile_commands.json, without -o, -c, -Werror (a warning in student code is reported,
    never fatal) and the -I of the skeleton folder."""
    target = f"springlab_{lab.name}_student"
    entry = next((c for c in commands if f"/{target}_objects.dir/" in c.get("command", "")), None)
    if entry is None:
        raise GradeError(f"{where}: no compile command for {target}; was the lab built?")
    flags, skip = [], False
    for arg in shlex.split(entry["command"]):
        if skip:
            skip = False
            continue
        if arg in ("-o", "-c"):
            skip = True
            continue
        if arg == "-Werror":
            continue
        if arg.startswith("-I") and pathlib.PurePath(arg[2:]).parts[-2:] == ("labs", lab.dir):
            continue
        flags.append(arg)
    return flags


# ---- the object cache ------------------------------------------------------------------------
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


class ObjectCache:
    """Compiled exercise files (object and dependency file) of earlier submissions, in a folder
    only the grader can open, keyed by the flags, the file's name and bytes and the headers.
    Bounded: an object above OBJECT_LIMIT bytes is never kept, and once the folder holds more
    than `cap` bytes the entries used longest ago go (each use touches its entry)."""

    OBJECT_LIMIT = 32 << 20   # the compiler's own output limit (sealed_compile.OUTPUT_MB)
    CAP = 2 << 30              # the folder's size

    def __init__(self, folder, cap=CAP):
        self.folder = pathlib.Path(folder)
        self.folder.mkdir(exist_ok=True)
        os.chmod(self.folder, 0o700)
        self.cap = cap
        self.lock = threading.Lock()

    @staticmethod
    def key(flags, name, data, headers):
        # The key covers the instructor's headers too: an object compiled against an older
        # Simulation (another vtable) must never be linked with the new framework.
        headers += include_digest(tuple(flags))
        return hashlib.sha256(json.dumps(flags).encode() + b"\0" + name.encode() + b"\0" + data + headers).hexdigest()

    def fetch(self, key, into, name):
        """Copy a cached compile to into/<name>.o and .d; its object, or None. An entry whose
        bytes no longer match the digest stored with it is not used (it is compiled again)."""
        cached, deps, digest = (self.folder / f"{key}{suffix}" for suffix in (".o", ".d", ".sha256"))
        if not (cached.exists() and deps.exists() and digest.exists()):
            return None
        try:
            shutil.copyfile(cached, into / f"{name}.o")
            shutil.copyfile(deps, into / f"{name}.d")
            if entry_digest(into / f"{name}.o", into / f"{name}.d") != digest.read_text().strip():
                return None
            os.utime(digest)  # used now: the last to be evicted
        except FileNotFoundError:  # evicted by a grader beside this one meanwhile
            return None
        return into / f"{name}.o"

    def store(self, key, obj, deps):
        """Keep a compile the grader has copied out of the sandbox's reach, with its digest;
        nothing when the object is above OBJECT_LIMIT."""
        if pathlib.Path(obj).stat().st_size + pathlib.Path(deps).stat().st_size > self.OBJECT_LIMIT:
            return
        for source, target in ((obj, self.folder / f"{key}.o"), (deps, self.folder / f"{key}.d")):
            temporary = target.with_name(f"{target.name}.{os.getpid()}.{threading.get_ident()}")
            shutil.copyfile(source, temporary)
            os.replace(temporary, target)  # whole or absent, for graders running side by side
        digest = self.folder / f"{key}.sha256"
        temporary = digest.with_name(f"{digest.name}.{os.getpid()}.{threading.get_ident()}")
        temporary.write_text(entry_digest(obj, deps) + "\n")
        os.replace(temporary, digest)
        self.evict()

    def evict(self):
        """Remove the entries used longest ago until the folder holds at most 3/4 of the cap,
        once it holds more than the cap."""
        with self.lock:
            entries = {}
            for path in self.folder.iterdir():
                key = path.name.split(".", 1)[0]
                try:
                    stat = path.stat()
                except FileNotFoundError:
                    continue
                size, used = entries.get(key, (0, 0.0))
                entries[key] = (size + stat.st_size, max(used, stat.st_mtime) if path.suffix == ".sha256" else used)
            total = sum(size for size, _ in entries.values())
            if total <= self.cap:
                return
            for key, (size, _) in sorted(entries.items(), key=lambda item: item[1][1]):
                if total <= self.cap * 3 // 4:
                    break
                for suffix in (".o", ".d", ".sha256"):
                    (self.folder / f"{key}{suffix}").unlink(missing_ok=True)
                total -= size


def entry_digest(obj, deps):
    return hashlib.sha256(pathlib.Path(obj).read_bytes() + b"\0" + pathlib.Path(deps).read_bytes()).hexdigest()


# ---- the cache build -------------------------------------------------------------------------
class Cache:
    """The instructor build: framework, reference oracle and the grading tests' objects."""

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
        self.objects = ObjectCache(self.path / "grader-objects")
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
        # The judges: one per exercise file of the reference (tests/CMakeLists.txt).
        judges = [f"{lab.name}_judge_{source.stem}" for lab in self.labs for source in sorted(lab.solution.glob("*.cpp"))]
        targets = [t for lab in self.labs
                   for target in (f"{lab.name}_grading_student", f"{lab.name}_grading_reference",
                                  f"springlab_{lab.name}_solution_objects", f"{lab.name}_worker_layer",
                                  f"{lab.name}_trace_support")
                   for t in ("--target", target)]
        targets += [t for judge in judges for t in ("--target", judge)]
        run = subprocess.run(["cmake", "--build", str(self.path), "-j", str(jobs), *targets],
                             capture_output=True, text=True, env=env)
        if run.returncode != 0:
            raise GradeError(f"building the grading build {self.path} failed (the instructor tree does not build):\n"
                             + tail(run.stdout + run.stderr, 40))

    # How the reference's times were counted (a record counted otherwise is measured again).
    COUNTED = "CPU seconds of the test's processes, inside bubblewrap too (sandbox.reap, judged_run.Launch)"

    def reference_times(self, lab, sandbox):
        """The reference's own grading time for a lab ({test: seconds}), measured once on the
        trusted side and kept in grading/<name>_reference_time.json beside the link, keyed by
        the reference program's bytes; None when the build has no reference."""
        link = self.lab(lab, sandbox).link
        program = link.reference_program
        if not program or not os.access(program, os.X_OK):
            return None
        digest = hashlib.sha256(pathlib.Path(program).read_bytes()).hexdigest()
        record = self.path / "grading" / f"{lab.name}_reference_time.json"
        with self.lock:
            try:
                data = json.loads(record.read_text())
                per_test = data.get("per_test")
                if (data.get("program_sha256") == digest and data.get("counted") == self.COUNTED and isinstance(per_test, dict)
                        and all(isinstance(v, (int, float)) for v in per_test.values())):
                    return {str(k): float(v) for k, v in per_test.items()}
            except (OSError, ValueError):
                pass
            # Launched as the workers are (gtest_runner.run_test), so the times compare; from
            # the stage, which the sandbox users can reach wherever the checkout lives.
            results = grade_binary(str(stage().program(program)), lab.manifest, 1, sandbox, 1, seccomp=link.worker_seccomp)
            # Counted as budgets count a student's tests: CPU time, which load does not stretch.
            per_test = {r.test["name"]: r.cpu_seconds for r in results}
            temporary = record.with_name(f"{record.name}.{os.getpid()}")
            temporary.write_text(json.dumps({"program_sha256": digest, "counted": self.COUNTED, "seconds": sum(per_test.values()),
                                             "per_test": per_test,
                                             "passed": sum(r.passed for r in results),
                                             "tests": len(results)}, indent=1) + "\n")
            os.replace(temporary, record)
            return per_test

    def link_file(self, lab):
        return self.path / "grading" / f"{lab.name}_link.json"

    def lab(self, lab, sandbox):
        """What compiling and linking this lab's grading program needs, found once."""
        with self.lock:
            if lab.name not in self.lab_builds:
                self.lab_builds[lab.name] = self._lab_build(lab, sandbox)
            return self.lab_builds[lab.name]

    def _lab_build(self, lab, sandbox):
        flags = compile_flags(self.commands, lab, self.path)
        link = read_link_file(self.link_file(lab))
        protected = [*link.test_objects, *link.given_objects, *link.worker_objects, *link.main_objects,
                     *(f for f in link.libraries if f.endswith((".a", ".o")) and not f.startswith("-")
                       and f != link.oracle)]
        if not os.access(link.skeleton_program, os.X_OK):
            raise GradeError(f"{link.skeleton_program}: missing; was {lab.name}_grading_student built?")
        present = set(listed_tests(str(stage().program(link.skeleton_program)), sandbox))
        for judge in link.judges.values():  # staged now, before graders run side by side
            stage().program(judge)
        from .judged_run import bubblewrap
        return LabBuild(flags, link, present, defined_symbols([link.oracle]) if link.oracle else set(),
                        defined_symbols(protected), sealed_compiler(flags, ROOT, bubblewrap() is not None))
