"""The compiler's sandbox. A compiler reads files on the student's say-so (`#include`,
`__has_include`, `.incbin`, `#embed`), so it runs in bubblewrap as the sandbox user, where the
whole file system is the toolchain (/usr, read-only), copies of the framework's public header
folders at neutral paths (/springlab/framework/include, ...), the submission's own exercise
files (/submission/src, read-only) and the folder its object goes to (/submission/obj): no
grading tree, no build folder, no other submission. It has limits on memory, CPU time, wall
time and the size of every file it writes (object, dependency file, messages). Messages name
files relative to the submission; any path of the grader left in them is replaced."""
import dataclasses
import os
import pathlib
import re
import signal

from .errors import GradeError
from .sandbox import Run, Sandbox, run_sandboxed
from .staging import stage

NEUTRAL = pathlib.PurePosixPath("/springlab")     # the framework's headers, inside
SUBMISSION = pathlib.PurePosixPath("/submission")  # the submission's files and objects, inside

# The compiler's limits: its memory, its CPU time and its wall time per file (a file that
# honestly compiles in seconds; the wall limit only catches a compiler that waits), and the
# size of each file it writes (an object of the exercise files is well under 2 MiB).
MEMORY_MB = 2048
CPU_SECONDS = 60
WALL_SECONDS = 120.0
OUTPUT_MB = 32
TMP_MB = 256  # its private /tmp (a memory file system)


def compile_sandbox(identity_user="nobody"):
    return Sandbox(timeout=WALL_SECONDS, memory_mb=MEMORY_MB, file_mb=OUTPUT_MB, drop_to=identity_user,
                   cpu_seconds=CPU_SECONDS)


@dataclasses.dataclass
class SealedCompiler:
    """One lab's compile as the sandbox runs it."""
    argv: list     # the compiler and its flags, include folders at their paths inside
    binds: list    # (staged folder on this machine, its path inside)
    outside: list  # the staged folders' real paths (the fallback without bubblewrap uses them)
    sealed: bool   # False: bubblewrap cannot run here; the compiler runs as the sandbox user alone

    def command(self, name):
        tail = ["-pipe", "-fdiagnostics-color=never", "-MD", "-MF", f"obj/{name}.d", "-o", f"obj/{name}.o",
                "-c", f"src/{name}"]
        return [*(self.argv if self.sealed else self.outside), *tail]

    def bwrap_argv(self, bwrap, work, name):
        # The compiler is the namespace's first process (--as-pid-1), so its CPU time, and its
        # children's, reaches the grader through bwrap's exit (sandbox.reap).
        argv = [bwrap, "--unshare-all", "--as-pid-1", "--die-with-parent", "--new-session", "--clearenv",
                "--setenv", "PATH", "/usr/bin:/bin", "--setenv", "LANG", "C.UTF-8", "--setenv", "HOME", "/tmp",
                "--setenv", "TMPDIR", "/tmp",
                "--ro-bind", "/usr", "/usr", "--symlink", "usr/lib", "/lib", "--symlink", "usr/lib64", "/lib64",
                "--symlink", "usr/bin", "/bin", "--dev", "/dev", "--size", str(TMP_MB << 20), "--tmpfs", "/tmp"]
        for staged, inside in self.binds:
            argv += ["--ro-bind", str(staged), str(inside)]
        argv += ["--ro-bind", str(work / "src"), str(SUBMISSION / "src"),
                 "--bind", str(work / "obj"), str(SUBMISSION / "obj"), "--chdir", str(SUBMISSION)]
        return argv + self.command(name)

    def run(self, work, name, sandbox):
        """Compile work/src/<name> to work/obj/<name>.o and .d; the Run."""
        from .judged_run import bubblewrap
        program = bubblewrap() if self.sealed else None
        if program is None:
            return run_sandboxed(self.command(name), sandbox, cwd=work)
        return run_sandboxed(self.bwrap_argv(program, work, name), sandbox, cwd=work)

    def include_folders(self):
        """The folders the compile may read headers from, as its dependency file names them."""
        inside = [pathlib.Path(str(p)) for _, p in self.binds] if self.sealed else [pathlib.Path(s) for s, _ in self.binds]
        return [pathlib.Path("/usr"), *inside]


def sealed_compiler(compile_argv, root, bwrap_available):
    """The sandbox's form of a lab's compile: the compiler by its real path (/usr/bin/c++ is a
    chain of links through /etc), each include folder outside /usr staged and bound at a
    neutral path: /springlab/<its path in the tree>, or /springlab/include/<k> elsewhere."""
    root = pathlib.Path(root).resolve()
    compiler = os.path.realpath(compile_argv[0])
    if not pathlib.Path(compiler).is_relative_to("/usr"):
        raise GradeError(f"{compile_argv[0]}: the grading build's compiler is outside /usr ({compiler}); the "
                         f"compiler's sandbox shows /usr only: configure the grading build with a system compiler")
    inside_argv, outside_argv, binds = [compiler], [compiler], []
    take_next = None
    for flag in compile_argv[1:]:
        if take_next:
            folder, prefix = flag, take_next
            take_next = None
        elif flag in ("-I", "-isystem", "-iquote", "-idirafter"):
            take_next = flag
            continue
        elif flag.startswith("-I") and len(flag) > 2:
            folder, prefix = flag[2:], "-I"
        else:
            inside_argv.append(flag)
            outside_argv.append(flag)
            continue
        path = pathlib.Path(folder).resolve()
        if path.is_relative_to("/usr"):
            inside, staged = path, path
        else:
            check_include_folder(path, root)
            staged = stage().headers(path)
            inside = NEUTRAL / (path.relative_to(root) if path.is_relative_to(root) else f"include/{len(binds)}")
            binds.append((staged, inside))
        for argv, where in ((inside_argv, inside), (outside_argv, staged)):
            argv += [f"-I{where}"] if prefix == "-I" else [prefix, str(where)]
    return SealedCompiler(inside_argv, binds, outside_argv, bwrap_available)


def stop_reason(run: Run, name):
    """A sentence naming the limit that stopped the compiler, or None when it was not stopped."""
    text = run.output
    if run.returncode is None:
        return (f"{name}: compiling was stopped at the compiler's wall-time limit of {WALL_SECONDS:g} s (does the "
                f"file include something that never ends, such as a device?)")
    if "out of memory" in text or "virtual memory exhausted" in text or "std::bad_alloc" in text:
        return (f"{name}: compiling was stopped at the compiler's memory limit of {MEMORY_MB} MiB (a file that "
                f"includes something huge, or templates that never end?)")
    if "CPU time limit exceeded" in text or run.returncode in (-signal.SIGXCPU, 128 + signal.SIGXCPU):
        return f"{name}: compiling was stopped at the compiler's CPU-time limit of {CPU_SECONDS} s"
    if "File size limit exceeded" in text or run.returncode in (-signal.SIGXFSZ, 128 + signal.SIGXFSZ):
        return (f"{name}: compiling was stopped at the compiler's output limit: every file it writes (the object, "
                f"its messages) may hold {OUTPUT_MB} MiB")
    if "Killed signal terminated program" in text or run.returncode in (-signal.SIGKILL, 128 + signal.SIGKILL):
        return (f"{name}: the compiler was killed at one of its limits ({MEMORY_MB} MiB of memory, {CPU_SECONDS} s "
                f"of CPU time)")
    return None


def scrub(text, places):
    """The text with every path of the grader in it (the tree, its build, the grading folder)
    replaced by a neutral word: students see paths relative to their submission only."""
    for place, word in sorted(places.items(), key=lambda item: -len(str(item[0]))):
        if str(place) not in ("", "/"):
            text = text.replace(str(place), word)
    return re.sub(r"(?<![\w/])/submission/src/", "", text)


def check_include_folder(folder, root):
    """An include folder of the lab's compile may be staged only if it holds no part of the
    grading tree beyond headers: never the tree itself or a folder above solutions/ or tests/."""
    folder = pathlib.Path(folder).resolve()
    for private in (root / "solutions", root / "tests"):
        if private.resolve().is_relative_to(folder):
            raise GradeError(f"the lab's compile flags include -I{folder}, which holds {private.name}/: the "
                             f"compiler's sandbox would show the reference or the tests; include the framework's "
                             f"header folders only")
