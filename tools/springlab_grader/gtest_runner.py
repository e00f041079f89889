"""Running a GoogleTest grading program: listing its tests, and running each alone, started
exactly as `grade` starts a worker (judged_run.launch_worker: the same command line,
environment, descriptors, folder, user and sandbox; the test's name on standard input), so
nothing the program can see tells a check from a graded run, or which test runs. The outcome
counts only from the report the grading main (tests/support/grading_main.cpp) writes on the
channel descriptor once every test has returned: printed output and exit codes do not count.
Hidden tests' messages lose the values GoogleTest printed. Also the seed of the random test
inputs and the time budgets."""
import concurrent.futures
import dataclasses
import json
import os
import random
import re
import tempfile
import threading
import time

from .failures import clean, crash_signal, signal_name
from .judged_run import kill_user, launch_worker, outcome_of, read_tail, run_judged, wait_until, worker_uid
from .manifest import ManifestError
from .results import TestResult
from .sandbox import read_until_closed, run_sandboxed, tail


@dataclasses.dataclass
class Outcome:
    passed: bool
    message: str
    seconds: float
    cpu_seconds: float = 0.0  # what the test costs a budget (sandbox.reap)


def run_test(binary, name, seed, sandbox, slot=0, seccomp=None):
    """Run one GoogleTest test alone, launched as a worker is; trust only the report on the
    channel (one JSON object, written after the test returned)."""
    start = time.monotonic()
    with tempfile.TemporaryFile() as log:
        launch = launch_worker(binary, name, sandbox, {"SPRINGLAB_SEED": str(seed)}, log, slot=slot, seccomp=seccomp)
        deadline = start + sandbox.timeout
        channel = read_until_closed(launch.channel, deadline)
        os.close(launch.channel)
        code = wait_until(launch.proc, deadline)
        cpu = launch.finish() if code is not None else max(launch.finish(), sandbox.timeout)
        seconds = time.monotonic() - start
        output = read_tail(log)
    outcome = outcome_of_test(name, sandbox, code, channel, output, seconds)
    outcome.cpu_seconds = cpu
    return outcome


def outcome_of_test(name, sandbox, code, channel, output, seconds):
    """The Outcome of one test process from its exit code and the report on its channel."""
    from .judged_run import crash_signal
    try:
        report = json.loads(channel.decode("utf-8", "replace")) if channel.strip() else None
    except ValueError:
        report = None
    if code is None:
        return Outcome(False, f"timed out after {sandbox.timeout:g} s: an infinite loop, or far too much work", seconds)
    if crash_signal(code) is not None:
        return Outcome(False, f"crashed: {signal_name(crash_signal(code), output)}\n{tail(output)}", seconds)
    if not isinstance(report, dict):
        return Outcome(False, f"the test process ended (exit code {code}) without the grader's report: "
                              f"exit() or a crash inside the code under test\n{tail(output)}", seconds)
    tests = [t for t in report.get("tests", []) if isinstance(t, dict)]
    if len(tests) != 1 or tests[0].get("name") != name:
        return Outcome(False, "the test did not run (not found in the test program)", seconds)
    status, failures = tests[0].get("status"), [str(f) for f in tests[0].get("failures", [])]
    if status == "passed" and code == 0:
        return Outcome(True, "", seconds)
    if failures:
        return Outcome(False, "\n".join(clean(f) for f in failures), seconds)
    if status == "skipped":
        return Outcome(False, "skipped: a skipped test earns no points", seconds)
    return Outcome(False, f"the test passed but its process then exited with code {code}", seconds)


# GoogleTest's own lines that print compared values; in a hidden test those may be the
# reference's, so they are dropped and only the test's physics message is kept.
_VALUE_LINES = re.compile(r"^\s*(Which is:|Expected:|Actual:|Value of:|Expected equality of these values:|"
                          r"The difference between|Expected: \(|  Actual:|[^ ].* evaluates to |"
                          r"tol evaluates to|With diff:|Google Test trace:)")


def redact(message):
    """A hidden test's message without the values GoogleTest printed (they may be the reference's)."""
    kept, skipping = [], False
    for line in message.splitlines():
        if _VALUE_LINES.match(line) or re.match(r"^.*, actual: .* vs .*$", line):
            skipping = skipping or line.strip().startswith("Expected equality")
            continue
        if skipping and line.startswith("  "):
            continue  # the operand lines of "Expected equality of these values:"
        skipping = False
        kept.append(line)
    text = "\n".join(kept).strip()
    return text or "does not match the reference solution (the values are not shown for hidden tests)"


def listed_tests(binary, sandbox):
    """The tests a grading program holds (listed under the sandbox: listing runs its code too)."""
    run = run_sandboxed([binary, "--gtest_list_tests"], dataclasses.replace(sandbox, timeout=60))
    if run.returncode != 0:
        raise ManifestError(f"{binary}: --gtest_list_tests failed (exit code {run.returncode}):\n{tail(run.output)}")
    names, suite = [], None
    for line in run.output.splitlines():
        if not line.strip() or line.startswith("Running main()"):
            continue
        if not line.startswith(" "):
            suite = line.split("#")[0].strip()
        else:
            names.append(suite + line.split("#")[0].strip())
    return names


class Budget:
    """CPU seconds a submission or a lab may spend on its tests (the sum of its tests' CPU time,
    worker and judge: sandbox.reap; a test stopped at the time limit costs the limit), and a
    wall-time limit on the whole (`wall`, seconds from its creation), which a test that waits
    without computing (sleep, a blocked read) spends instead; both checked before each test
    starts. None as a limit means none. Budgets nest: a lab's spending counts against its
    submission's too. CPU time is not stretched by a loaded machine, so an honest submission is
    not cut off because the grader shares its cores; the wall limit is far above what any honest
    lab takes and bounds what a hostile one costs a grading slot."""

    def __init__(self, limit, parent=None, what="lab", wall=None):
        self.limit, self.parent, self.what, self.wall = limit, parent, what, wall
        self.started = time.monotonic()
        self.spent = 0.0
        self.lock = threading.Lock()

    def exhausted(self):
        """The budget that is spent (this one or an enclosing one), or None."""
        if self.limit is not None and self.spent >= self.limit:
            return self
        if self.wall is not None and time.monotonic() - self.started >= self.wall:
            return self
        return self.parent.exhausted() if self.parent else None

    def wall_left(self):
        """Seconds until the nearest wall-time limit (this budget's or an enclosing one's); None: none."""
        own = None if self.wall is None else self.wall - (time.monotonic() - self.started)
        outer = self.parent.wall_left() if self.parent else None
        return min((x for x in (own, outer) if x is not None), default=None)

    def limited(self, sandbox):
        """The sandbox of a test started now: its time limit cut to the wall time left, so no
        test runs past the limit. (sandbox, True when cut)."""
        left = self.wall_left()
        if left is None or left >= sandbox.timeout:
            return sandbox, False
        return dataclasses.replace(sandbox, timeout=max(0.1, left), cpu_seconds=sandbox.timeout + 2), True

    def past_wall_limit(self):
        """The budget (this one or an enclosing one) whose wall-time limit has passed, or None."""
        if self.wall is not None and time.monotonic() - self.started >= self.wall:
            return self
        return self.parent.past_wall_limit() if self.parent else None

    def spend(self, seconds):
        with self.lock:
            self.spent += seconds
        if self.parent:
            self.parent.spend(seconds)

    def message(self):
        if self.limit is not None and self.spent >= self.limit:
            return (f"time budget spent: this {self.what}'s tests had already used {self.spent:.0f} s of CPU time, "
                    f"more than its budget of {self.limit:.0f} s (a multiple of the reference solution's own CPU "
                    f"time), so this test was not run")
        return (f"wall-time limit reached: this {self.what}'s tests had already run for {self.wall:.0f} s (its limit: "
                f"tests that wait, such as sleep, cost wall time without CPU time), so this test was not run")


@dataclasses.dataclass
class BudgetRule:
    """A lab's time budget: `floor` seconds plus `factor` times the reference's own time on its
    tests, shared among its exercise files: each file gets an equal part of the floor plus
    `factor` times the reference's time on that file's tests. Shares follow the reference's
    time, not the number of tests: one slow simulation test is not a dozen quick ones."""
    floor: float
    factor: float
    reference: dict  # test name -> the reference's seconds

    @property
    def limit(self):
        return self.floor + self.factor * sum(self.reference.values())

    def share(self, tests, files):
        return self.floor / max(1, files) + self.factor * sum(self.reference.get(t, 0.0) for t in tests)


def grade_binary(binary, manifest, seed, sandbox, jobs, present=None, on_result=None, only=None, budget=None,
                 slot=0, seccomp=None):
    """Run every manifest test the binary holds, side by side; results in manifest order.
    `only`: names of the tests to run (the others are left out); `budget`: a Budget, after
    which the remaining tests fail with "time budget spent". Each test is launched as a worker
    (run_test); `slot` and `seccomp` as in grade_judged."""
    present = set(present if present is not None else listed_tests(binary, sandbox))
    # A student's own build has no hidden tests; those are left out there, not failed.
    todo = [(ex, t) for ex in manifest["exercises"] for t in ex["tests"]
            if (t["name"] in present or t["visibility"] == "visible") and (only is None or t["name"] in only)]

    def one(item):
        ex, t = item
        spent = budget.exhausted() if budget else None
        if t["name"] not in present:
            outcome = Outcome(False, "this test is not in the test program (a hidden test in a student build?)", 0.0)
        elif spent is not None:
            outcome = Outcome(False, spent.message(), 0.0)
        else:
            limited, cut = budget.limited(sandbox) if budget else (sandbox, False)
            outcome = run_test(binary, t["name"], seed, limited, slot=slot, seccomp=seccomp)
            if budget:
                budget.spend(outcome.cpu_seconds)
                if cut and budget.past_wall_limit():
                    outcome.message = budget.past_wall_limit().message().replace(", so this test was not run",
                                                                                 ": this test was stopped there")
        message = redact(outcome.message) if t["visibility"] != "visible" and outcome.message else outcome.message
        result = TestResult(ex, t, outcome.passed, message, outcome.seconds, outcome.cpu_seconds)
        if on_result:
            on_result(result)
        return result

    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        results = list(pool.map(one, todo))
    if todo and os.geteuid() == 0:
        kill_user(worker_uid(slot))
    return results


def grade_judged(judge, worker, manifest, seed, sandbox, jobs, only=None, budget=None, slot=0, seccomp=None):
    """Run the manifest's tests `only` as judge and worker pairs (judged_run.py); results in
    manifest order. The judge holds every test of the lab (hidden ones too)."""
    todo = [(ex, t) for ex in manifest["exercises"] for t in ex["tests"] if only is None or t["name"] in only]

    def one(item):
        ex, t = item
        spent = budget.exhausted() if budget else None
        if spent is not None:
            outcome = Outcome(False, spent.message(), 0.0)
        else:
            limited, cut = budget.limited(sandbox) if budget else (sandbox, False)
            run = run_judged(judge, worker, t["name"], limited,
                             {"SPRINGLAB_SEED": str(seed)}, slot=slot, seccomp=seccomp)
            passed, message = outcome_of(run, t["name"], limited.timeout)
            outcome = Outcome(passed, message, run.seconds, run.cpu_seconds)
            if budget:
                budget.spend(outcome.cpu_seconds)
                if cut and not passed and budget.past_wall_limit():
                    outcome.message = budget.past_wall_limit().message().replace(", so this test was not run",
                                                                                 ": this test was stopped there")
        message = redact(outcome.message) if t["visibility"] != "visible" and outcome.message else outcome.message
        return TestResult(ex, t, outcome.passed, message, outcome.seconds, outcome.cpu_seconds)

    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        results = list(pool.map(one, todo))
    if os.geteuid() == 0:
        kill_user(worker_uid(slot))
    return results


def check_binary_against_manifest(binary, manifest, manifest_path, sandbox, student_build=False):
    """Every test in the binary carries points; every visible manifest test exists."""
    present = set(listed_tests(binary, sandbox))
    declared = {t["name"] for ex in manifest["exercises"] for t in ex["tests"]}
    unpointed = sorted(present - declared)
    if unpointed:
        raise ManifestError(f"{manifest_path}: tests without points: {', '.join(unpointed)}")
    wanted = [t["name"] for ex in manifest["exercises"] for t in ex["tests"]
              if not student_build or t["visibility"] == "visible"]
    missing = sorted(n for n in wanted if n not in present)
    if missing:
        raise ManifestError(f"{binary}: manifest tests not found in the binary: {', '.join(missing)}")
    return present


def draw_seed(given=None):
    """--seed, else SPRINGLAB_SEED from the environment (to replay a run), else drawn."""
    if given is not None:
        return given
    if os.environ.get("SPRINGLAB_SEED", "").isdigit():
        return int(os.environ["SPRINGLAB_SEED"])
    return random.randrange(2**32)
