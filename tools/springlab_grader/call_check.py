"""The call check, the same in `grade` (integrity.py) and a student's `check` (tools/grade.py,
student_check.py): the calls an exercise file makes, read from its object's undefined symbols,
against what exercise code never needs; and which symbols an object defines. Shipped in the
student release (it reads objects only)."""
import re
import subprocess


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
