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
import pathlib
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
        launch.finish()
        seconds = time.monotonic() - start
        output = read_tail(log)
    try:
        report = json.loads(channel.decode("utf-8", "replace")) if channel.strip() else None
    except ValueError:
        report = None
    if code is None:
        return Outcome(False, f"timed out after {sandbox.timeout:g} s: an infinite loop, or far too much work", seconds)
    if crash_signal(code) is not None:
        return Outcome(False, f"crashed: {signal_name(crash_signal(code))}\n{tail(output)}", seconds)
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


# A loaded machine (a class graded two at a time beside other work) stretches every test's
# wall time; budgets count a test's wall time divided by the machine's slowdown, so an honest
# submission is not cut off because the grader shares its cores. At most this factor, so code
# that loads the machine itself buys a bounded discount.
MAX_SLOWDOWN = 8.0


def machine_slowdown(loadavg="/proc/loadavg", cores=None):
    """How many times slower than alone a CPU-bound test runs now: the larger of the 1-minute
    load average and the tasks runnable this instant (besides the reader), per core; between 1
    and MAX_SLOWDOWN. 1 where the load cannot be read (not Linux)."""
    try:
        fields = pathlib.Path(loadavg).read_text().split()
        load, runnable = float(fields[0]), int(fields[3].split("/")[0]) - 1
    except (OSError, ValueError, IndexError):
        return 1.0
    per_core = max(load, runnable) / (cores or os.cpu_count() or 1)
    return min(MAX_SLOWDOWN, max(1.0, per_core))


def budget_seconds(wall, slowdown=None):
    """What a test's wall time counts in a budget (and in the reference's own time): the wall
    time over the machine's slowdown when it ended."""
    return wall / (machine_slowdown() if slowdown is None else slowdown)


class Budget:
    """Seconds of test time a submission or a lab may spend (the sum of its tests' run times,
    each over the machine's slowdown when it ran: budget_seconds; checked before each test
    starts); None as the limit means no budget. Budgets nest: a lab's spending counts against
    its submission's too."""

    def __init__(self, limit, parent=None, what="lab"):
        self.limit, self.parent, self.what = limit, parent, what
        self.spent = 0.0
        self.lock = threading.Lock()

    def exhausted(self):
        """The budget that is spent (this one or an enclosing one), or None."""
        if self.limit is not None and self.spent >= self.limit:
            return self
        return self.parent.exhausted() if self.parent else None

    def spend(self, seconds):
        with self.lock:
            self.spent += seconds
        if self.parent:
            self.parent.spend(seconds)

    def message(self):
        return (f"time budget spent: this {self.what}'s tests had already run {self.spent:.0f} s, more than "
                f"its budget of {self.limit:.0f} s (a multiple of the reference solution's own time; both "
                f"counted as wall time over the machine's load), so this test was not run")


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
            outcome = run_test(binary, t["name"], seed, sandbox, slot=slot, seccomp=seccomp)
            if budget:
                budget.spend(budget_seconds(outcome.seconds))
        message = redact(outcome.message) if t["visibility"] != "visible" and outcome.message else outcome.message
        result = TestResult(ex, t, outcome.passed, message, outcome.seconds)
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
            run = run_judged(judge, worker, t["name"], sandbox,
                             {"SPRINGLAB_SEED": str(seed)}, slot=slot, seccomp=seccomp)
            passed, message = outcome_of(run, t["name"], sandbox.timeout)
            outcome = Outcome(passed, message, run.seconds)
            if budget:
                budget.spend(budget_seconds(outcome.seconds))
        message = redact(outcome.message) if t["visibility"] != "visible" and outcome.message else outcome.message
        return TestResult(ex, t, outcome.passed, message, outcome.seconds)

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
