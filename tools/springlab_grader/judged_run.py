"""One graded test as two processes (tests/support/call_trace.hpp): the worker, which runs the
test with the student's exercise file inside bubblewrap (its own user, PID, network, IPC and
mount namespaces; only /usr, a private /tmp and the worker program visible; a clean
environment; nothing left running afterwards), and the judge, a program without student code
that replays the worker's call trace and decides. Only the judge's report counts."""
import dataclasses
import errno
import fcntl
import functools
import json
import os
import pathlib
import re
import resource
import shutil
import signal
import subprocess
import tempfile
import threading
import time

from .failures import clean, crash_signal, signal_name
from .sandbox import Sandbox, read_until_closed, reap, tail
from .staging import stage

# The worker sees these variables and nothing else of the grader's environment.
WORKER_ENV = {"PATH": "/usr/bin:/bin", "HOME": "/tmp", "TMPDIR": "/tmp", "LANG": "C.UTF-8", "OMP_NUM_THREADS": "1"}
TRACE_ENDED = "SPRINGLAB_TRACE_ENDED: "


_plain = []  # set by go_without_bubblewrap()


def bubblewrap():
    """The bwrap program if it can make its namespaces here, else None: then workers run with
    the process sandbox alone (their own user, limits, process group, a clean environment),
    as in a container that forbids user namespaces. isolation() says which."""
    return None if _plain else _bubblewrap_here()


def go_without_bubblewrap():
    """From now on this grader launches plain processes (`check` of a program that cannot
    start in bubblewrap: see starts_in_bubblewrap)."""
    _plain.append(True)


@functools.lru_cache(maxsize=1)
def _bubblewrap_here():
    program = shutil.which("bwrap")
    if program is None:
        return None
    probe = subprocess.run([program, "--unshare-all", "--die-with-parent", "--ro-bind", "/usr", "/usr",
                            "--symlink", "usr/lib", "/lib", "--symlink", "usr/lib64", "/lib64",
                            "--symlink", "usr/bin", "/bin", "/usr/bin/true"], capture_output=True)
    return program if probe.returncode == 0 else None


@functools.lru_cache(maxsize=4)
def seccomp_filter(program):
    """The workers' seccomp filter (tests/support/worker_seccomp.cpp) as a file of BPF, written
    once per grader by `program`; None without the program (no libseccomp) or if it fails."""
    if not program or not os.access(program, os.X_OK):
        return None
    run = subprocess.run([program], capture_output=True)
    if run.returncode != 0 or not run.stdout or len(run.stdout) % 8:
        return None
    # In this grader's stage, removed with it (staging.py).
    handle, path = tempfile.mkstemp(prefix="springlab-seccomp-", suffix=".bpf", dir=stage().root)
    with os.fdopen(handle, "wb") as out:
        out.write(run.stdout)
    return path


def isolation(seccomp=None):
    """One line for reports: how workers are isolated on this machine."""
    if bubblewrap():
        extra = " and a seccomp filter" if seccomp_filter(seccomp) else " (no seccomp filter: libseccomp missing)"
        return "workers run in bubblewrap (own user, PID, network and mount namespaces)" + extra
    why = "bwrap is not installed" if shutil.which("bwrap") is None else "bwrap cannot create namespaces here"
    return (f"workers run as their own user with limits only ({why}; install bubblewrap, or allow user "
            f"namespaces, for namespaces)")


_claimed = {}
_claim_lock = threading.Lock()


def worker_uid(slot):
    """The user a submission's workers run as when the grader is root: one per submission
    slot of this grader, never a real account (no files of its own, its own process limit).
    Graders running side by side (ctest, two instructors) each hold a lock on the users they
    use, so no grader ever signals another's workers."""
    with _claim_lock:
        if slot not in _claimed:
            folder = pathlib.Path(tempfile.gettempdir()) / "springlab-worker-users"
            folder.mkdir(mode=0o700, exist_ok=True)
            start = (os.getpid() * 7 + slot) % 4000
            for k in range(4000):
                uid = 61000 + (start + k) % 4000
                handle = open(folder / f"{uid}.lock", "w")
                try:
                    fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
                except OSError:
                    handle.close()
                    continue
                _claimed[slot] = (uid, handle)  # held until this grader ends
                break
            else:
                raise RuntimeError("no free worker user among 61000-64999")
        return _claimed[slot][0]


def judge_uid(slot):
    """The user a submission's judges run as when the grader is root: paired with its workers'
    user (worker_uid, whose lock it shares), 4000 below it, so never a worker's."""
    return worker_uid(slot) - 4000


@dataclasses.dataclass
class Fate:
    """How a worker ended: its exit code, the signal that killed it, or the time limit."""
    returncode: int | None
    output: str

    def describe(self):
        if self.returncode is None:
            return "it was still running at the time limit (an infinite loop, or far too much work)"
        if crash_signal(self.returncode) is not None:
            return f"it crashed: {signal_name(crash_signal(self.returncode), self.output)}"
        return f"its process exited with code {self.returncode} before the call returned (exit() or abort)"


@dataclasses.dataclass
class JudgedRun:
    report: dict | None  # the judge's {"tests": [...], "trace_calls": N}
    judge_code: int | None
    judge_output: str
    worker: Fate
    seconds: float
    cpu_seconds: float = 0.0  # judge and worker; the time limit when either was stopped at it


# Every worker's command line, whatever test it runs (the test comes on its standard input).
WORKER_ARGS = ["--gtest_color=no"]
# Where every launched program finds its channel back to the grader (a worker's call trace, a
# check's report: SPRINGLAB_CALL_TRACE_FD) and, under bubblewrap, the seccomp filter: the same
# numbers in every launch, whatever the grader has open.
CHANNEL_FD = 3
SECCOMP_FD = 4
# argv[0] of every launched program: where bubblewrap binds it, and its name without bubblewrap.
PROGRAM_NAME = "/sandbox/test"


def worker_argv(program, env, seccomp_fd=None, info_fd=None):
    """The command line of every launch: bwrap around the program, which is bound read-only
    at /sandbox/test and runs in a private /tmp with the environment worker_env(env), the
    seccomp filter read from seccomp_fd (if any) loaded just before it starts. Without
    bubblewrap, the program itself, named /sandbox/test all the same (launch_worker runs it
    with worker_env and its own folder)."""
    if bubblewrap() is None:
        return [PROGRAM_NAME, *WORKER_ARGS]
    argv = [bubblewrap(), "--unshare-all", "--die-with-parent", "--new-session", "--clearenv"]
    if seccomp_fd is not None:
        argv += ["--seccomp", str(seccomp_fd)]
    if info_fd is not None:  # where bwrap says the sandbox's first process (sandbox_cpu_seconds)
        argv += ["--info-fd", str(info_fd)]
    for key, value in worker_env(env).items():
        argv += ["--setenv", key, value]
    argv += ["--ro-bind", "/usr", "/usr", "--symlink", "usr/lib", "/lib", "--symlink", "usr/lib64", "/lib64",
             "--symlink", "usr/bin", "/bin", "--proc", "/proc", "--dev", "/dev", "--tmpfs", "/tmp",
             "--ro-bind", str(program), PROGRAM_NAME, "--chdir", "/tmp", PROGRAM_NAME, *WORKER_ARGS]
    return argv


def worker_env(env, private=None):
    """The whole environment of a launched program: WORKER_ENV, the run's own variables (the
    seed) and the channel; without bubblewrap its HOME and TMPDIR are its private folder."""
    home = {"HOME": private, "TMPDIR": private} if private else {}
    return {**WORKER_ENV, **env, **home, "SPRINGLAB_CALL_TRACE_FD": str(CHANNEL_FD)}


@dataclasses.dataclass
class Launch:
    """A program started by launch_worker: its process, the grader's read end of its channel
    (SPRINGLAB_CALL_TRACE_FD), and what finish() takes away afterwards."""
    proc: subprocess.Popen
    channel: int
    private: str
    info: int | None = None  # bwrap's --info-fd, read end

    def finish(self):
        """Kill whatever is left of it (its process group) and remove its private folder; its
        CPU seconds (sandbox.reap), the program's inside bubblewrap included."""
        cpu = kill_group(self.proc)
        if self.info is not None:
            cpu += sandbox_cpu_seconds(read_until_closed(self.info, time.monotonic() + 1, cap=1 << 16))
            os.close(self.info)
            self.info = None
        shutil.rmtree(self.private, ignore_errors=True)
        return cpu


@functools.lru_cache(maxsize=1)
def become_subreaper():
    """Make this grader the reaper of its orphans (Linux's PR_SET_CHILD_SUBREAPER): bubblewrap
    leaves its sandbox's first process unreaped when it ends, and only its reaper learns that
    process's CPU time (and its children's). True if set."""
    try:
        import ctypes
        return ctypes.CDLL(None, use_errno=True).prctl(36, 1, 0, 0, 0) == 0
    except (OSError, AttributeError):
        return False


def sandbox_cpu_seconds(info):
    """The CPU seconds of the sandbox's first process (bwrap --info-fd names it: "child-pid"),
    reaped here as its subreaper once bubblewrap has ended; 0 when it cannot be."""
    match = re.search(rb'"child-pid":\s*(\d+)', info)
    if not match or not become_subreaper():
        return 0.0
    pid, deadline = int(match[1]), time.monotonic() + 2.0
    while True:
        try:
            done, _, usage = os.wait4(pid, os.WNOHANG)
        except ChildProcessError:  # not ours (bubblewrap reaped it) or gone
            return 0.0
        if done:
            return usage.ru_utime + usage.ru_stime
        if time.monotonic() > deadline:
            return 0.0
        time.sleep(0.005)


def launch_worker(program, test, sandbox: Sandbox, env, log, slot=0, seccomp=None):
    """Start `program` to run the test named `test`, the one way the grader starts student
    code: a `grade` worker (run_judged) and a `check` test process (gtest_runner.run_test)
    alike. The command line (worker_argv), the environment (worker_env: the same names and
    values), the descriptors (the channel at CHANNEL_FD, nothing else above stderr), the
    folder and the user are the same whatever runs; the test's name comes as one line on
    standard input. Under bubblewrap the program is /sandbox/test, run in /tmp; without it,
    it runs as its own user (root graders) in a private folder, argv[0] still /sandbox/test.
    Output goes to `log`. The caller reads launch.channel and calls launch.finish()."""
    channel_r, channel_w = os.pipe()
    name_r, name_w = os.pipe()
    limits = sandbox.limits()
    uid = worker_uid(slot) if os.geteuid() == 0 else None
    private = tempfile.mkdtemp(prefix="springlab-worker-")  # the fallback's cwd and HOME
    if uid is not None:
        os.chown(private, uid, uid)
    bpf = seccomp_filter(seccomp) if bubblewrap() else None
    seccomp_fd = os.open(bpf, os.O_RDONLY) if bpf else None
    info_r, info_w = os.pipe() if bubblewrap() and become_subreaper() else (None, None)
    given = [channel_w] + ([seccomp_fd] if seccomp_fd is not None else []) + ([info_w] if info_w is not None else [])
    top = os.sysconf("SC_OPEN_MAX")

    def in_child():
        # The channel (and the filter) at fixed numbers, every other inherited descriptor shut.
        moved = [fcntl.fcntl(fd, fcntl.F_DUPFD, 64) for fd in given]
        for target, fd in enumerate(moved, start=CHANNEL_FD):
            os.dup2(fd, target)
        try:  # up to the highest open one (Linux); else up to the limit, bounded
            end = max(int(entry) for entry in os.listdir("/proc/self/fd")) + 1
        except (OSError, ValueError):
            end = min(max(top, 1024), 65536)
        os.closerange(CHANNEL_FD + len(moved), end)
        for which, value in limits:
            resource.setrlimit(which, (value, value))

    argv = worker_argv(program, env, SECCOMP_FD if seccomp_fd is not None else None,
                       CHANNEL_FD + len(given) - 1 if info_w is not None else None)
    try:
        proc = subprocess.Popen(
            argv, executable=None if bubblewrap() else str(program),
            env={"PATH": "/usr/bin:/bin"} if bubblewrap() else worker_env(env, private), cwd=private,
            stdin=name_r, stdout=log, stderr=subprocess.STDOUT, close_fds=False, process_group=0,
            preexec_fn=in_child, user=uid, group=uid, extra_groups=[] if uid else None)
    finally:
        for fd in (channel_w, name_r, seccomp_fd, info_w):
            if fd is not None:
                os.close(fd)
    # A test name is far below a pipe's buffer: this write never waits for the program.
    os.write(name_w, test.encode() + b"\n")
    os.close(name_w)
    return Launch(proc, channel_r, private, info_r)


def starts_in_bubblewrap(program, sandbox: Sandbox, seccomp=None):
    """Whether `program` starts when launched in bubblewrap: a student's own build may need
    libraries outside /usr (a compiler in /opt or a conda environment), which bubblewrap does
    not show. Launched as any test is, with no test named, its main answers with exit code 2."""
    with tempfile.TemporaryFile() as log:
        launch = launch_worker(program, "", sandbox, {}, log, seccomp=seccomp)
        os.close(launch.channel)
        code = wait_until(launch.proc, time.monotonic() + 60)
        launch.finish()
    return code == 2


def run_judged(judge, worker, test, sandbox: Sandbox, env, slot=0, seccomp=None):
    """Run the test named `test` in the judge and the worker side by side, joined by the trace
    pipe; the judge's report, the worker's fate. The judge has the name on its command line;
    the worker is started by launch_worker (the name on its standard input), so its command
    line and environment are the same for every test, and the same as a check's. The time
    limit covers both; both end before this returns. `seccomp`: the program that writes the
    workers' seccomp filter."""
    report_r, report_w = os.pipe()
    limits = sandbox.limits()

    def limited():
        for which, value in limits:
            resource.setrlimit(which, (value, value))

    start = time.monotonic()
    with tempfile.TemporaryFile() as judge_log, tempfile.TemporaryFile() as worker_log:
        launch = launch_worker(worker, test, sandbox, env, worker_log, slot=slot, seccomp=seccomp)
        trace_r = launch.channel
        # The judge runs no student code but reads what it sent: it runs unprivileged too, as a
        # user of its own (never the worker's, who could then reach it), from the stage.
        uid = judge_uid(slot) if os.geteuid() == 0 else None
        if uid is not None:
            os.fchown(report_w, uid, uid)  # it opens /dev/fd/N: the pipe must be its own
        judge_proc = start_retrying(
            [str(stage().program(judge)), f"--gtest_filter={test}", *WORKER_ARGS,
             f"--springlab-report=/dev/fd/{report_w}"],
            env={**WORKER_ENV, **env, "SPRINGLAB_CALL_TRACE_FD": str(trace_r)}, cwd="/",
            stdin=subprocess.DEVNULL, stdout=judge_log, stderr=subprocess.STDOUT, pass_fds=(trace_r, report_w),
            process_group=0, preexec_fn=limited, user=uid, group=uid, extra_groups=[] if uid else None)
        for fd in (trace_r, report_w):
            os.close(fd)
        deadline = start + sandbox.timeout
        report = read_until_closed(report_r, deadline, cap=1 << 22)
        os.close(report_r)
        judge_code = wait_until(judge_proc, deadline)
        # The judge is done: the worker has nothing left to say.
        worker_code = wait_until(launch.proc, deadline if judge_code is None else time.monotonic() + 0.5)
        # bubblewrap's PID namespace ends with its first process: nothing of the worker is left.
        cpu = kill_group(judge_proc) + launch.finish()
        if judge_code is None:
            cpu = max(cpu, sandbox.timeout)  # stopped at the wall-time limit: it costs the limit
        seconds = time.monotonic() - start
        try:
            parsed = json.loads(report.decode("utf-8", "replace")) if report.strip() else None
        except ValueError:
            parsed = None
        return JudgedRun(parsed if isinstance(parsed, dict) else None, judge_code, read_tail(judge_log),
                         Fate(worker_code, read_tail(worker_log)), seconds, cpu)


def start_retrying(argv, **options):
    """subprocess.Popen, tried again while the program is "busy": a program just copied to the
    stage may still be open for writing in a child another thread forked meanwhile (ETXTBSY
    until that child execs)."""
    for attempt in range(50):
        try:
            return subprocess.Popen(argv, **options)
        except OSError as error:
            if error.errno != errno.ETXTBSY or attempt == 49:
                raise
            time.sleep(0.02)


def wait_until(proc, deadline):
    return reap(proc, deadline)[0]


def kill_group(proc):
    """Kill a launched program's process group and reap it; its CPU seconds (sandbox.reap)."""
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass
    return reap(proc)[1] or 0.0


def kill_user(uid):
    """Whatever still runs as a submission's worker user once its tests are done (bubblewrap's
    PID namespace should leave nothing; this is the second lock)."""
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            if os.stat(f"/proc/{entry}").st_uid == uid:
                os.kill(int(entry), signal.SIGKILL)
        except (FileNotFoundError, ProcessLookupError, PermissionError):
            pass


def read_tail(log, size=8192):
    log.seek(0, os.SEEK_END)
    total = log.tell()
    log.seek(max(0, total - size))
    text = log.read().decode("utf-8", "replace")
    return tail(text, 30)


# libstdc++'s assertion (the judges are built with -D_GLIBCXX_ASSERTIONS), as it prints it before
# abort(): "...: std::vector<_Tp, _Alloc>::operator[](size_type) [with ...]: Assertion '__n <
# this->size()' failed."
_ASSERTION = re.compile(r"(std::\w+)<[^:]*?>::(operator\[\]|\w+)\(.*Assertion '([^']+)' failed")


def failed_assertion(judge_output):
    """The container function and condition of the libstdc++ assertion that stopped the judge
    ("std::vector::operator[], __n < this->size()"), or None. Only the judge's own output is
    read: the worker cannot write there."""
    for line in reversed(judge_output.splitlines()):
        match = _ASSERTION.search(line)
        if match:
            return f"{match[1]}::{match[2]}, {match[3]}"
    return None


def outcome_of(run: JudgedRun, name, timeout):
    """(passed, message) of one test from a judged run."""
    tests = [t for t in (run.report or {}).get("tests", []) if isinstance(t, dict)]
    if run.judge_code is None:
        why = run.worker.describe() if run.worker.returncode is None else "the judge ran out of time"
        return False, f"timed out after {timeout:g} s: {why}"
    if run.report is None:
        stopped = failed_assertion(run.judge_output)
        if stopped:
            return False, (f"the test failed: the grader's judge stopped at an index past the end of what your code "
                           f"returned ({stopped}): check the sizes of the containers your function returns")
        if run.judge_code < 0:
            return False, (f"the test failed: the grader's judge crashed ({signal_name(-run.judge_code)}) on what "
                           f"your code returned (sizes or indices out of range?)")
        return False, f"the test failed: the grader's judge ended without a report (exit code {run.judge_code})"
    if len(tests) != 1 or tests[0].get("name") != name:
        return False, "the test did not run (not found in the grading program)"
    status, failures = tests[0].get("status"), [str(f) for f in tests[0].get("failures", [])]
    if status == "passed":
        return True, ""
    messages = []
    for failure in failures:
        text = clean(failure)
        if TRACE_ENDED in text:
            text = text.replace(TRACE_ENDED, "") + f". Your code's run: {run.worker.describe()}"
            if run.worker.output.strip():
                text += "\n" + tail(run.worker.output, 8)
        messages.append(text)
    if status == "skipped":
        return False, "skipped: a skipped test earns no points"
    return False, "\n".join(messages) or "failed"
