"""Checks of a submission's compiled exercise files, run on the trusted side: a file that
includes anything outside the submission and the framework (solutions/, hidden tests), calls
the reference "oracle", or redefines the framework's, GoogleTest's or the grading main's
symbols, or calls what an exercise never needs to (the test framework, files, the environment,
other processes) is graded as the released skeleton's file, and the report says why."""
import pathlib
import re
import subprocess

from .labs import exercises_in


def defined_symbols(files):
    """Global symbols the files define strongly (weak ones, inline functions, may repeat)."""
    files = [str(f) for f in files if f]
    if not files:
        return set()
    run = subprocess.run(["nm", "-g", "--defined-only", "-P", *files], capture_output=True, text=True)
    return {parts[0] for parts in (line.split() for line in run.stdout.splitlines())
            if len(parts) >= 2 and parts[1] in "TDBRG" and not parts[0].endswith(":")}


# The kinds of definition a student's object may make: strong (T, D, B, R, G) and weak (W, V:
# `__attribute__((weak))`, u: unique, i: indirect). A weak definition in the student's archive,
# which comes first in the link, keeps a library's strong one out of it: it counts as a
# redefinition as much as a strong one.
STUDENT_DEFINITIONS = "TDBRGWVui"


def symbols_by_file(files, undefined=False):
    """{file: its global symbols, strong or weak (or its undefined ones)}, one nm for all files."""
    files = [str(f) for f in files]
    found = {f: set() for f in files}
    if not files:
        return found
    argv = ["nm", "-A", "-P", *(["-u"] if undefined else ["-g", "--defined-only"]), *files]
    run = subprocess.run(argv, capture_output=True, text=True)
    for line in run.stdout.splitlines():
        where, _, rest = line.partition(": ")
        parts = rest.split()
        if where in found and parts and (undefined or (len(parts) >= 2 and parts[1] in STUDENT_DEFINITIONS)):
            found[where].add(parts[0])
    return found


# What exercise code never needs, and hostile code would use to learn which test runs or that
# it is graded (the test framework's state, the command line and environment, the grading
# tree's files) or to reach beyond its process. Matched against the undefined symbols of the
# student's object: the calls it makes. Code that reads its own memory without calling
# anything is out of reach of this check (the README's limits).
FORBIDDEN_CALLS = [
    (re.compile(r"^_ZN?K?7testing"), "the test framework (GoogleTest)"),
    (re.compile(r"^(getenv|secure_getenv|environ|__environ|__libc_argv|program_invocation(_short)?_name)$"),
     "the environment or command line"),
    (re.compile(r"^(open|open64|openat|openat64|__open_2|__open64_2|__openat_2|creat|creat64|fopen|fopen64|"
                r"freopen|freopen64|opendir|fdopendir|readlink|readlinkat|stat|stat64|lstat|__xstat|__xstat64|"
                r"access|faccessat|dlopen|dlmopen|dlsym|dlvsym|dladdr|dladdr1|dlinfo|dl_iterate_phdr)$"),
     "files or loaded programs"),
    (re.compile(r"^_ZNSt(7__cxx11)?1[34]basic_[io]?fstream|^_ZNSt(7__cxx11)?10filesystem|"
                r"^_ZNSt(7__cxx11)?1[34]basic_filebuf"), "files (std::fstream, std::filesystem)"),
    (re.compile(r"^(backtrace|backtrace_symbols|backtrace_symbols_fd|_Unwind_Backtrace|_Unwind_GetIP)$"),
     "its own call stack"),
    (re.compile(r"^(syscall|ptrace|process_vm_readv|process_vm_writev|prctl|fork|vfork|clone|clone3|execv|execve|"
                r"execvp|execvpe|execl|execle|execlp|fexecve|system|popen|posix_spawn|posix_spawnp|kill|killpg|"
                r"socket|connect|bind|mprotect|setuid|setgid|setsid|setpgid|daemon)$"),
     "other processes or the operating system"),
]


def forbidden_calls(undefined):
    """[(symbol, what it reaches)] among an object's undefined symbols (`nm -u`)."""
    found = []
    for symbol in sorted(undefined):
        bare = symbol.split("@")[0]
        for pattern, what in FORBIDDEN_CALLS:
            if pattern.search(bare):
                found.append((bare, what))
                break
    return found


def undefined_symbols(obj):
    run = subprocess.run(["nm", "-u", "-P", str(obj)], capture_output=True, text=True)
    return {line.split()[0] for line in run.stdout.splitlines() if line.strip()}


def demangle(symbols):
    run = subprocess.run(["c++filt"], input="\n".join(sorted(symbols)), capture_output=True, text=True)
    return run.stdout.split("\n")[:len(symbols)] if run.returncode == 0 else sorted(symbols)


def parse_depfile(text):
    body = text.replace("\\\n", " ")
    _, _, deps = body.partition(": ")
    return [d.replace("\\ ", " ") for d in re.split(r"(?<!\\)\s+", deps.strip()) if d]


def allowed_folders(work, build):
    """The submission's own files, the folders the compiler's sandbox shows (sealed_compile.py)."""
    return [(work / "src").resolve(), *build.sealed.include_folders()]


def find_cheats(objects, work, build, lab, notes, others=None, call_check=True):
    """Files to grade as the skeleton's: they include the instructor's files, call the
    reference solution, or redefine the framework's, GoogleTest's or the grader's symbols.
    `objects` are the compiled files (with their .d files beside them), `build` the lab's
    LabBuild; each finding is added to notes. `others` maps a file's name to the symbols the
    reference's other exercise files define: a file that defines another exercise's function
    (which its grading program takes from the reference) is flagged too, and so is a file that
    calls what FORBIDDEN_CALLS lists (unless `call_check` is off, to test the sandbox)."""
    allowed = allowed_folders(work, build)
    flagged = {}
    defined_in = symbols_by_file(objects)
    undefined_in = symbols_by_file(objects, undefined=True)
    inside_cache = {}

    def inside(dep):
        if dep not in inside_cache:
            path = pathlib.Path(dep)
            resolved = (work / path).resolve() if not path.is_absolute() else path.resolve()
            inside_cache[dep] = any(resolved.is_relative_to(folder) for folder in allowed)
        return inside_cache[dep]

    for obj in objects:
        name = obj.name[:-2]
        deps = obj.with_suffix(".d")
        for dep in parse_depfile(deps.read_text()) if deps.exists() else []:
            if not inside(dep):
                # Its name only: the path may be the grading tree's.
                flagged.setdefault(name, f"includes {pathlib.PurePath(dep).name}, a file outside the submission "
                                         f"and the framework")
                break
        used = undefined_in[str(obj)] & build.oracle_symbols
        if used:
            flagged.setdefault(name, "calls the reference solution (" + ", ".join(demangle(used)[:3]) + ")")
        defined = defined_in[str(obj)] & build.protected_symbols
        if defined:
            flagged.setdefault(name, "redefines symbols of the framework, GoogleTest or the grader ("
                               + ", ".join(demangle(defined)[:3]) + ")")
        reached = forbidden_call_reason(undefined_in[str(obj)]) if call_check else None
        if reached:
            flagged.setdefault(name, reached)
        foreign = defined_in[str(obj)] & (others or {}).get(name, set())
        if foreign:
            flagged.setdefault(name, "defines functions of another exercise file ("
                               + ", ".join(demangle(foreign)[:3]) + "); each exercise is graded in its own file")
    for name, why in flagged.items():
        notes.append(replaced_note(name, why, exercises_in(lab.solution / name),
                                   name in {p.name for p in lab.skeleton.iterdir()}))
    return sorted(flagged)


def forbidden_call_reason(undefined):
    """Why an object with these undefined symbols is graded as the skeleton's, or None: the
    sentence `grade` and `check` both print."""
    reached = forbidden_calls(undefined)
    if not reached:
        return None
    what = sorted({w for _, w in reached})
    called = sorted({d.split("(")[0] for d in demangle([s for s, _ in reached])})
    return (f"calls {', '.join(called[:3])}, which reach {' and '.join(what)}: exercise code may compute, "
            f"allocate and print, nothing more")


def replaced_note(name, why, exercises, exercise_file=True):
    """The note of a file graded as the skeleton's (or left out), the same in `grade` and `check`."""
    if not exercise_file:
        return f"{name} {why}: it was left out of the build"
    what = f"exercise {', '.join(exercises)} scores 0" if exercises else "it was left out"
    return f"{name} {why}: it is graded as the released skeleton's {name}, so {what}"


REPLACED = "{name} was replaced by the released skeleton's file (see the note)"
