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


# ---- a failed test's message as sentences (check's report) ------------------------------------
# GoogleTest's own text for each kind of failed assertion; what follows it, up to the next one,
# is the test's own message: the physics to check.
_EQUAL = re.compile(r"^Expected equality of these values:$")
_COMPARE = re.compile(r"^Expected: \((?P<a>.*)\) (?P<op><=|>=|<|>|!=) \((?P<b>.*)\), actual: (?P<x>.*) vs (?P<y>.*)$")
_BOOLEAN = re.compile(r"^Value of: (?P<what>.*)$")
_NEAR = re.compile(r"^The difference between (?P<a>.*) and (?P<b>.*) is (?P<d>.*), which exceeds (?P<tol>.*), where$")
_THROWN = re.compile(r'^C\+\+ exception with description "(?P<what>.*)" thrown in (?P<where>.*)\.$')
_THROWS = re.compile(r"^Expected: (?P<what>.*) (?P<kind>throws an exception of type .*|doesn't throw an exception)\.$")
_FAILED = re.compile(r"^Failed$")
_STARTS = [_EQUAL, _COMPARE, _BOOLEAN, _NEAR, _THROWN, _THROWS, _FAILED,
           re.compile(r"^Unknown C\+\+ exception thrown"), re.compile(r"^Expected: .* (throws|doesn't throw)")]
_WORDS = {"<": "below", "<=": "at most", ">": "above", ">=": "at least", "!=": "different from"}


def _short(value):
    """A number GoogleTest printed with 17 digits, with 6; anything else as it is."""
    return re.sub(r"-?\d+\.\d{7,}(?:e[-+]?\d+)?", lambda m: f"{float(m[0]):.6g}", value.strip())


def _literal(expression, value):
    """Whether an operand is written as its value (a number in the test's source)."""
    return expression.strip() == value.strip() or _short(expression) == _short(value)


def _named(expression, value):
    """`expression = value`, or the value alone when the expression is that value."""
    return _short(value) if _literal(expression, value) else f"{expression.strip()} = {_short(value)}"


def _came(*operands):
    """What came: each operand that is not a literal, with its value."""
    shown = [_named(e, v) for e, v in operands if not _literal(e, v)]
    return ", ".join(shown or [_named(e, v) for e, v in operands])


def _blocks(message):
    """The message cut at each of GoogleTest's failures: [(its lines, the test's lines after it)]."""
    blocks = []
    for line in message.splitlines():
        if any(p.match(line) for p in _STARTS) or not blocks:
            blocks.append([line])
        else:
            blocks[-1].append(line)
    return blocks


def _said(block):
    """(expected, came, the test's own words) of one failure; expected None when GoogleTest's text
    is not one of the kinds above (then the lines are the test's words as they are)."""
    head, rest = block[0], block[1:]
    if _EQUAL.match(head):
        # "  a\n    Which is: 1\n  b\n    Which is: 2": each operand, its value when not a literal.
        operands, i = [], 0
        while i < len(rest) and rest[i].startswith("  ") and len(operands) < 2:
            expression, value = rest[i].strip(), rest[i].strip()
            i += 1
            if i < len(rest) and rest[i].strip().startswith("Which is:"):
                value = rest[i].strip()[len("Which is:"):]
                i += 1
            operands.append((expression, value))
        if len(operands) == 2:
            (a, x), (b, y) = operands
            return f"{a} equal to {b}", _came((a, x), (b, y)), rest[i:]
    m = _COMPARE.match(head)
    if m:
        return f"{m['a']} {_WORDS[m['op']]} {m['b']}", _came((m["a"], m["x"]), (m["b"], m["y"])), rest
    m = _BOOLEAN.match(head)
    if m and len(rest) >= 2 and rest[0].strip().startswith("Actual:") and rest[1].startswith("Expected:"):
        actual, expected = rest[0].strip()[len("Actual:"):].strip(), rest[1][len("Expected:"):].strip()
        return f"{m['what']} to be {expected}", f"{actual}", rest[2:]
    m = _NEAR.match(head)
    if m:
        values = {}
        i = 0
        while i < len(rest) and " evaluates to " in rest[i]:
            name, _, value = rest[i].partition(" evaluates to ")
            values[name.strip()] = value.rstrip(",.").removesuffix(", and")
            i += 1
        a, b = m["a"], m["b"]
        return (f"{a} within {_short(values.get(m['tol'], m['tol']))} of {_named(b, values.get(b, b))}",
                f"{_named(a, values.get(a, a))} (a difference of {_short(m['d'])})", rest[i:])
    m = _THROWN.match(head)
    if m and m["what"].startswith("not implemented: "):
        return None, None, [m["what"], *rest]  # a skeleton's stub: its own words say it all
    if m:
        return "no exception", f"an exception: {m['what']}", rest
    m = _THROWS.match(head)
    if m and rest and rest[0].strip().startswith("Actual:"):
        return (f"{m['what']} {m['kind'].replace('throws', 'to throw').replace('doesn' + chr(39) + 't throw', 'to throw no')}",
                rest[0].strip()[len("Actual:"):].strip().rstrip("."), rest[1:])
    if _FAILED.match(head):
        return None, None, rest
    return None, None, block


def sentences(message, raw=False, most=3):
    """A failed test's message as the student reads it in `check`: for each failed assertion
    (up to `most`), what was expected, what came and what to check (the test's own words);
    with `raw`, GoogleTest's own text under each."""
    # The same failure repeated (an assertion in a loop) is said once, with its count.
    said = {}
    for block in _blocks(message):
        expected, came, words = _said(block)
        # The test's words on one line after a GoogleTest comparison; as written otherwise.
        kept = [w.rstrip() for w in words if w.strip()]
        key = (expected, came, " ".join(w.strip() for w in kept) if expected is not None else "\n".join(kept))
        said.setdefault(key, []).append(block)
    out = []
    for (expected, came, words), blocks in list(said.items())[:most]:
        times = f" ({len(blocks)} times)" if len(blocks) > 1 else ""
        if expected is None:
            out.append((words or "\n".join(blocks[0])) + times)
        else:
            out += [f"expected: {expected}", f"came:     {came}{times}"] + ([f"check:    {words}"] if words else [])
        if raw and any(p.match(blocks[0][0]) for p in _STARTS):
            out += ["GoogleTest: " + blocks[0][0], *("            " + line for line in blocks[0][1:])]
    if len(said) > most:
        more = len(said) - most
        out.append(f"({more} more failed check{'s' if more > 1 else ''} in this test: "
                   f"{'below' if raw else 'shown with --verbose'})")
        if raw:
            out += [line for blocks in list(said.values())[most:] for line in blocks[0]]
    return "\n".join(out)
