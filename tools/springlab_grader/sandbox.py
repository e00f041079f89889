"""The sandbox every untrusted process runs in: limits on time, CPU, memory, stack, file size
and open files; the user `nobody` when the grader runs as root; a fresh private folder; its own
process group, killed whole afterwards. run_sandboxed runs the compiler and lists a program's
tests; test processes are started by judged_run.launch_worker, with these limits."""
import dataclasses
import os
import pathlib
import pwd
import resource
import select
import signal
import subprocess
import tempfile
import time

TIMEOUT = 20.0  # seconds per test; each takes well under a second
# What a run keeps of its output: this many bytes of its beginning and as many of its end.
KEPT = 8192


@dataclasses.dataclass
class Sandbox:
    """Limits and the user every test process runs with."""
    timeout: float = TIMEOUT
    memory_mb: int = 4096    # address space; 0 = none (AddressSanitizer builds need none)
    stack_mb: int = 64
    file_mb: int = 64
    drop_to: str = "nobody"  # the user tests run as when the grader is root
    cpu_seconds: float = None  # CPU time per process; None: the wall-time limit and 2 s

    def identity(self):
        if os.geteuid() != 0 or not self.drop_to:
            return None
        user = pwd.getpwnam(self.drop_to)
        return user.pw_uid, user.pw_gid

    def limits(self):
        mib = 1 << 20
        cpu = int(self.cpu_seconds) if self.cpu_seconds else int(self.timeout) + 2
        pairs = [(resource.RLIMIT_CPU, cpu), (resource.RLIMIT_STACK, self.stack_mb * mib),
                 (resource.RLIMIT_FSIZE, self.file_mb * mib), (resource.RLIMIT_CORE, 0),
                 (resource.RLIMIT_NOFILE, 256)]
        if self.memory_mb:
            pairs.append((resource.RLIMIT_AS, self.memory_mb * mib))
        if self.identity():
            pairs.append((resource.RLIMIT_NPROC, 512))  # counts the sandbox user's processes only
        return pairs


@dataclasses.dataclass
class Run:
    """What one sandboxed process did."""
    returncode: int | None  # None: killed at the time limit
    seconds: float
    output: str             # stdout and stderr: its first and last KEPT bytes
    cpu_seconds: float = 0.0  # its CPU time and that of the processes it waited for


def reap(proc, deadline=None):
    """Wait for a child until `deadline` (time.monotonic(); None: for good): (its exit code, or
    None at the deadline; the CPU seconds, user and system, of it and the descendants it
    waited for). CPU time is what budgets count: a loaded machine stretches wall time, never
    CPU time. The code and the seconds stay on proc (proc.returncode, proc.cpu_seconds)."""
    if proc.returncode is not None:
        return proc.returncode, getattr(proc, "cpu_seconds", 0.0)
    try:
        handle = os.pidfd_open(proc.pid)
    except (AttributeError, OSError):
        handle = None
    try:
        while True:
            try:
                pid, status, usage = os.wait4(proc.pid, 0 if deadline is None else os.WNOHANG)
            except ChildProcessError:  # reaped elsewhere
                return proc.returncode, getattr(proc, "cpu_seconds", 0.0)
            if pid:
                proc.returncode = os.waitstatus_to_exitcode(status)
                proc.cpu_seconds = usage.ru_utime + usage.ru_stime
                return proc.returncode, proc.cpu_seconds
            left = deadline - time.monotonic()
            if left <= 0:
                return None, None
            if handle is not None:
                select.select([handle], [], [], left)
            else:
                time.sleep(min(left, 0.01))
    finally:
        if handle is not None:
            os.close(handle)


def run_sandboxed(argv, sandbox, env_extra=None, cwd=None):
    """Run argv under the sandbox in cwd (default: a fresh folder)."""
    ids = sandbox.identity()
    with tempfile.TemporaryDirectory(prefix="springlab-run-") as private:
        # The output file lives in the grader's private folder; the test writes it only
        # through its stdout and stderr, up to the file size limit.
        os.chmod(private, 0o711)  # the sandbox user may enter, not list
        work = pathlib.Path(private) / "cwd"
        work.mkdir()
        if ids:
            os.chown(work, *ids)
        if cwd is not None:
            work = pathlib.Path(cwd)
        log = open(pathlib.Path(private) / "output.txt", "w+b")
        home = pathlib.Path(private) / "cwd"
        # One thread per test: the grader runs tests side by side, and OpenMP threads that
        # wait for a busy core would only make each test slower.
        env = {"PATH": "/usr/bin:/bin", "HOME": str(home), "LANG": "C.UTF-8", "TMPDIR": str(home),
               "OMP_NUM_THREADS": "1"}
        env.update(env_extra or {})
        limits = sandbox.limits()

        def in_child():
            for which, value in limits:
                resource.setrlimit(which, (value, value))

        start = time.monotonic()
        proc = subprocess.Popen(argv, cwd=work, env=env, stdin=subprocess.DEVNULL, stdout=log, stderr=subprocess.STDOUT,
                                process_group=0, preexec_fn=in_child,
                                user=ids[0] if ids else None, group=ids[1] if ids else None,
                                extra_groups=[] if ids else None)
        deadline = start + sandbox.timeout
        code, cpu = reap(proc, deadline)
        # Whatever the test left running in its process group goes too.
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except (ProcessLookupError, PermissionError):
            pass
        if code is None:
            reap(proc)
            cpu = sandbox.timeout  # stopped at the wall-time limit: it costs the limit
        seconds = time.monotonic() - start
        # Its beginning and its end: a compiler's first error comes first (Eigen's templates can
        # follow it for many kilobytes), a crashed test's last words come last.
        log.seek(0, os.SEEK_END)
        size = log.tell()
        log.seek(0)
        head = log.read(min(size, KEPT)).decode("utf-8", "replace")
        log.seek(max(KEPT, size - KEPT))
        end = log.read().decode("utf-8", "replace")
        output = head + (f"\n[... {size - 2 * KEPT} bytes of output left out ...]\n" if size > 2 * KEPT else "") + end
        log.close()
        return Run(code, seconds, output, cpu)


def read_until_closed(fd, deadline, cap=1 << 20):
    """Read a pipe until every writer has closed it, the deadline passes or cap bytes came."""
    data = b""
    while len(data) < cap:
        left = deadline - time.monotonic()
        if left <= 0:
            break
        ready, _, _ = select.select([fd], [], [], left)
        if not ready:
            break
        chunk = os.read(fd, 65536)
        if not chunk:
            break
        data += chunk
    return data


def tail(text, lines=15):
    return "\n".join(text.strip().splitlines()[-lines:])
