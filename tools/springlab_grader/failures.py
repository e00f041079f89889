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


def signal_name(number):
    names = {signal.SIGSEGV: "segmentation fault (SIGSEGV): an invalid memory access, or a stack overflow from "
                             "too deep a recursion",
             signal.SIGABRT: "aborted (SIGABRT): abort(), a failed assert, or an exception nobody caught",
             signal.SIGFPE: "arithmetic error (SIGFPE), e.g. an integer division by zero",
             signal.SIGKILL: "killed (SIGKILL): the memory or CPU time limit",
             signal.SIGXCPU: "CPU time limit exceeded (SIGXCPU)",
             signal.SIGXFSZ: "wrote more output than allowed (SIGXFSZ)",
             signal.SIGBUS: "bus error (SIGBUS): an invalid memory access"}
    return names.get(number, f"signal {number}")


def clean(failure):
    # Drop the source location line GoogleTest puts first; students want the physics.
    lines = failure.splitlines()
    if lines and re.match(r"^\S+:\d+$", lines[0]):
        lines = lines[1:]
    return "\n".join(lines)
