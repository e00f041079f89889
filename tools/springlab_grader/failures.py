"""What a failed or crashed test tells the student: the signal that ended a program, its name
in words, and GoogleTest's failure text without its source location line. Shared by the test
runner (gtest_runner) and the judged runs (judged_run), which import it and not each other."""
import re
import signal


def crash_signal(returncode):
    """The signal that ended a launched program, or None: killed outright (a negative code), or,
    under bubblewrap, which exits with 128 + the signal of the program it ran."""
    if returncode is None:
        return None
    if returncode < 0:
        return -returncode
    if returncode > 128 and returncode - 128 in signal.Signals._value2member_map_:
        return returncode - 128
    return None


def signal_name(number, output=""):
    """A sentence for the signal that ended a test process, naming the sandbox's limit when one
    stopped it (sandbox.Sandbox: per test TIMEOUT s of wall time and that plus 2 s of CPU time,
    4096 MiB of memory, 64 MiB per file written; the worker's seccomp filter)."""
    from .sandbox import Sandbox
    limits = Sandbox()
    if number == signal.SIGABRT and "bad_alloc" in output:
        return (f"out of memory: the sandbox allows {limits.memory_mb} MiB of memory per test, and an allocation "
                f"beyond it failed (std::bad_alloc)")
    names = {signal.SIGSEGV: "segmentation fault (SIGSEGV): an invalid memory access, or a stack overflow from "
                             f"too deep a recursion (the stack may hold {limits.stack_mb} MiB)",
             signal.SIGABRT: "aborted (SIGABRT): abort(), a failed assert, or an exception nobody caught",
             signal.SIGFPE: "arithmetic error (SIGFPE), e.g. an integer division by zero",
             signal.SIGKILL: f"killed (SIGKILL) at a limit of the sandbox: {limits.memory_mb} MiB of memory, or "
                             f"the CPU time of {limits.timeout:g} s per test",
             signal.SIGXCPU: f"stopped at the sandbox's CPU-time limit (SIGXCPU): {limits.timeout:g} s per test",
             signal.SIGXFSZ: f"stopped at the sandbox's output limit (SIGXFSZ): a test may write {limits.file_mb} MiB",
             signal.SIGSYS: "stopped by the sandbox (SIGSYS): a system call exercise code may not make (new "
                            "processes, other processes' memory, sockets, mounts: the student README lists them)",
             signal.SIGBUS: "bus error (SIGBUS): an invalid memory access"}
    return names.get(number, f"signal {number}")


def clean(failure):
    # Drop the source location line GoogleTest puts first; students want the physics.
    lines = failure.splitlines()
    if lines and re.match(r"^\S+:\d+$", lines[0]):
        lines = lines[1:]
    return "\n".join(lines)
