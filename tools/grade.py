#!/usr/bin/env python3
"""Run one lab's grading tests, each in its own sandboxed process, and score them.

Points come from the lab's manifest (tests/<lab>/exercises.json), the one place they are
declared. Each test runs alone in a fresh process and folder, with limits on time, CPU,
memory, stack, file size and open files, and as the user `nobody` when the grader runs as
root. A test scores only if the grading main (tests/support/grading_main.cpp) reports it
passed on a private channel, with the secret nonce this run handed it, and the process exits
0: a crash, a hang, exit(0) inside an exercise or printed fake GoogleTest output score 0.

    tools/grade.py --binary build/tests/rope_grading_student --manifest tests/01_rope/exercises.json
    tools/grade.py ... --expect-percent 100        exit 1 unless the score is exactly 100 %
    tools/grade.py ... --out DIR                   also write report.md, results.json, junit.xml
    tools/grade.py --manifest M --check-handout H  check the handout's exercise headings and points

This file is also the library tools/submission.py grades whole submissions with.
"""
import argparse
import concurrent.futures
import dataclasses
import json
import os
import pathlib
import pwd
import random
import re
import resource
import secrets
import select
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET

VISIBILITIES = ("visible", "hidden", "after_due_date", "after_published")
TIMEOUT = 20.0  # seconds per test; each takes well under a second


# ---- the manifest ---------------------------------------------------------------------------
class ManifestError(Exception):
    pass


def load_manifest(path):
    """Read and check tests/<lab>/exercises.json; errors name the file and the field."""
    path = pathlib.Path(path)
    try:
        data = json.loads(path.read_text())
    except OSError as error:
        raise ManifestError(f"{path}: cannot read: {error.strerror}") from None
    except ValueError as error:
        raise ManifestError(f"{path}: not valid JSON: {error}") from None

    def need(obj, key, kind, where):
        if not isinstance(obj, dict) or key not in obj:
            raise ManifestError(f"{path}: {where}{key}: missing")
        if not isinstance(obj[key], kind) or isinstance(obj[key], bool):
            raise ManifestError(f"{path}: {where}{key}: must be a {kind.__name__ if isinstance(kind, type) else 'number'}")
        return obj[key]

    for key in ("lab", "title", "handout"):
        need(data, key, str, "")
    names = set()
    for i, ex in enumerate(need(data, "exercises", list, "")):
        where = f"exercises[{i}]."
        need(ex, "id", str, where)
        need(ex, "title", str, where)
        for j, t in enumerate(need(ex, "tests", list, where)):
            twhere = f"{where}tests[{j}]."
            name = need(t, "name", str, twhere)
            points = need(t, "points", (int, float), twhere)
            if points < 0:
                raise ManifestError(f"{path}: {twhere}points: must be >= 0, got {points}")
            if need(t, "visibility", str, twhere) not in VISIBILITIES:
                raise ManifestError(f"{path}: {twhere}visibility: must be one of {', '.join(VISIBILITIES)}, "
                                    f"got {t['visibility']!r}")
            if name in names:
                raise ManifestError(f"{path}: {twhere}name: {name} is declared twice")
            names.add(name)
        ex["points"] = sum(t["points"] for t in ex["tests"])
    data["points"] = sum(ex["points"] for ex in data["exercises"])
    return data


def check_handout(manifest, handout_path):
    text = pathlib.Path(handout_path).read_text()
    problems = []
    for ex in manifest["exercises"]:
        heading = f"### Exercise {ex['id']}: {ex['title']} ({ex['points']:g} points)"
        if heading not in text.splitlines():
            problems.append(f"{handout_path}: missing the heading line '{heading}' (points must agree with the manifest)")
    if f"{manifest['points']:g} points" not in text:
        problems.append(f"{handout_path}: never states the lab's total of {manifest['points']:g} points")
    return problems


# ---- the sandbox: one process per test -------------------------------------------------------
@dataclasses.dataclass
class Sandbox:
    """Limits and the user every test process runs with."""
    timeout: float = TIMEOUT
    memory_mb: int = 4096    # address space; 0 = none (AddressSanitizer builds need none)
    stack_mb: int = 64
    file_mb: int = 64
    drop_to: str = "nobody"  # the user tests run as when the grader is root

    def identity(self):
        if os.geteuid() != 0 or not self.drop_to:
            return None
        user = pwd.getpwnam(self.drop_to)
        return user.pw_uid, user.pw_gid

    def limits(self):
        mib = 1 << 20
        cpu = int(self.timeout) + 2
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
    output: str             # stdout and stderr, the end of it
    channel: bytes          # what arrived on the results channel


def run_sandboxed(argv, sandbox, env_extra=None, nonce=None, cwd=None):
    """Run argv under the sandbox in cwd (default: a fresh folder); with a nonce, open the
    results channel."""
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
        fds = ()
        if nonce is not None:
            nonce_r, nonce_w = os.pipe()
            result_r, result_w = os.pipe()
            os.write(nonce_w, nonce.encode())
            os.close(nonce_w)
            env["SPRINGLAB_RESULT_CHANNEL"] = f"{nonce_r}:{result_w}"
            fds = (nonce_r, result_w)
        limits = sandbox.limits()

        def in_child():
            for which, value in limits:
                resource.setrlimit(which, (value, value))

        start = time.monotonic()
        proc = subprocess.Popen(argv, cwd=work, env=env, stdin=subprocess.DEVNULL, stdout=log, stderr=subprocess.STDOUT,
                                pass_fds=fds, process_group=0, preexec_fn=in_child,
                                user=ids[0] if ids else None, group=ids[1] if ids else None,
                                extra_groups=[] if ids else None)
        channel = b""
        deadline = start + sandbox.timeout
        if nonce is not None:
            os.close(fds[0])
            os.close(fds[1])
            channel = read_until_closed(result_r, deadline)
            os.close(result_r)
        try:
            code = proc.wait(timeout=max(0.0, deadline - time.monotonic()))
        except subprocess.TimeoutExpired:
            code = None
        # Whatever the test left running in its process group goes too.
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except (ProcessLookupError, PermissionError):
            pass
        if code is None:
            proc.wait()
        seconds = time.monotonic() - start
        log.seek(0, os.SEEK_END)
        size = log.tell()
        log.seek(max(0, size - 8192))
        output = log.read().decode("utf-8", "replace")
        if size > 8192:
            output = f"[... {size - 8192} bytes of output left out ...]\n" + output
        log.close()
        return Run(code, seconds, output, channel)


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


# ---- one test -------------------------------------------------------------------------------
@dataclasses.dataclass
class Outcome:
    passed: bool
    message: str
    seconds: float


def run_test(binary, name, seed, sandbox):
    """Run one GoogleTest test alone; trust only the nonce-signed report on the channel."""
    nonce = secrets.token_hex(32)
    run = run_sandboxed([binary, f"--gtest_filter={name}", "--gtest_color=no"], sandbox,
                        {"SPRINGLAB_SEED": str(seed)}, nonce=nonce)
    report = None
    lines = run.channel.decode("utf-8", "replace").splitlines()
    for line in lines:
        try:
            message = json.loads(line)
        except ValueError:
            continue
        if isinstance(message, dict) and message.get("nonce") == nonce:
            report = message
    if run.returncode is None:
        return Outcome(False, f"timed out after {sandbox.timeout:g} s: an infinite loop, or far too much work", run.seconds)
    if run.returncode < 0:
        return Outcome(False, f"crashed: {signal_name(-run.returncode)}\n{tail(run.output)}", run.seconds)
    if report is None or len(lines) != 1:
        return Outcome(False, f"the test process ended (exit code {run.returncode}) without the grader's report: "
                              f"exit() or a crash inside the code under test\n{tail(run.output)}", run.seconds)
    tests = [t for t in report.get("tests", []) if isinstance(t, dict)]
    if len(tests) != 1 or tests[0].get("name") != name:
        return Outcome(False, "the test did not run (not found in the test program)", run.seconds)
    status, failures = tests[0].get("status"), [str(f) for f in tests[0].get("failures", [])]
    if status == "passed" and run.returncode == 0:
        return Outcome(True, "", run.seconds)
    if failures:
        return Outcome(False, "\n".join(clean(f) for f in failures), run.seconds)
    if status == "skipped":
        return Outcome(False, "skipped: a skipped test earns no points", run.seconds)
    return Outcome(False, f"the test passed but its process then exited with code {run.returncode}", run.seconds)


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


def tail(text, lines=15):
    return "\n".join(text.strip().splitlines()[-lines:])


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


# ---- a lab's results ------------------------------------------------------------------------
@dataclasses.dataclass
class TestResult:
    exercise: dict
    test: dict
    passed: bool
    message: str
    seconds: float

    @property
    def score(self):
        return self.test["points"] if self.passed else 0


@dataclasses.dataclass
class LabResult:
    manifest: dict
    results: list
    notes: list = dataclasses.field(default_factory=list)  # build errors, replaced files, ...
    seed: int = 0
    seconds: float = 0.0

    @property
    def score(self):
        return sum(r.score for r in self.results)

    @property
    def max_score(self):
        return sum(r.test["points"] for r in self.results)

    def exercise_score(self, ex):
        return sum(r.score for r in self.results if r.exercise is ex)


def failed_lab(manifest, message, notes=()):
    """Every test of a lab that could not be built scores 0, with the reason."""
    results = [TestResult(ex, t, False, message, 0.0) for ex in manifest["exercises"] for t in ex["tests"]]
    return LabResult(manifest, results, list(notes))


def grade_binary(binary, manifest, seed, sandbox, jobs, present=None, on_result=None):
    """Run every manifest test the binary holds, side by side; results in manifest order."""
    present = set(present if present is not None else listed_tests(binary, sandbox))
    # A student's own build has no hidden tests; those are left out there, not failed.
    todo = [(ex, t) for ex in manifest["exercises"] for t in ex["tests"]
            if t["name"] in present or t["visibility"] == "visible"]

    def one(item):
        ex, t = item
        if t["name"] not in present:
            outcome = Outcome(False, "this test is not in the test program (a hidden test in a student build?)", 0.0)
        else:
            outcome = run_test(binary, t["name"], seed, sandbox)
        message = redact(outcome.message) if t["visibility"] != "visible" and outcome.message else outcome.message
        result = TestResult(ex, t, outcome.passed, message, outcome.seconds)
        if on_result:
            on_result(result)
        return result

    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        return list(pool.map(one, todo))


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


# ---- outputs: terminal, Markdown, Gradescope results.json, JUnit XML --------------------------
def print_lab(lab, quiet=False, file=sys.stdout):
    m = lab.manifest
    for note in lab.notes:
        print(f"  note: {note}".replace("\n", "\n        "), file=file)
    if not quiet:
        for ex in m["exercises"]:
            print(f"  Exercise {ex['id']}: {ex['title']}  {lab.exercise_score(ex):g}/{ex['points']:g}", file=file)
            for r in (r for r in lab.results if r.exercise is ex):
                print(f"    {'PASS' if r.passed else 'FAIL'} {r.score:g}/{r.test['points']:g}  {r.test['name']}"
                      + ("" if r.test["visibility"] == "visible" else f"  ({r.test['visibility']})"), file=file)
                if r.message and not r.passed:
                    print("           " + r.message.replace("\n", "\n           "), file=file)
    percent = 100.0 * lab.score / lab.max_score if lab.max_score else 0.0
    print(f"{m['title']}: {lab.score:g} / {lab.max_score:g} points ({percent:.1f} %)", file=file)


def report_markdown(labs, title, seed):
    score, max_score = sum(lab.score for lab in labs), sum(lab.max_score for lab in labs)
    lines = [f"# {title}: {score:g} / {max_score:g} points", "",
             f"Random inputs drawn with SPRINGLAB_SEED={seed} (set it to replay this run).", ""]
    if labs:
        lines += ["| lab | points |", "|---|---|"]
        lines += [f"| {lab.manifest['title']} | {lab.score:g} / {lab.max_score:g} |" for lab in labs]
        lines.append("")
    for lab in labs:
        lines += [f"## {lab.manifest['title']}: {lab.score:g} / {lab.max_score:g} points", ""]
        for note in lab.notes:
            lines += ["> **Note**", ">", *(f"> {n}" if n else ">" for n in note.splitlines()), ""]
        for ex in lab.manifest["exercises"]:
            lines += [f"### Exercise {ex['id']}: {ex['title']} ({lab.exercise_score(ex):g} / {ex['points']:g} points)", ""]
            for r in (r for r in lab.results if r.exercise is ex):
                hidden = "" if r.test["visibility"] == "visible" else " (hidden test)"
                lines.append(f"- {'pass' if r.passed else '**FAIL**'} {r.score:g}/{r.test['points']:g} "
                             f"`{r.test['name']}`{hidden}")
                if r.message and not r.passed:
                    lines += ["", "  ```", *("  " + m for m in r.message.splitlines()), "  ```", ""]
            lines.append("")
    return "\n".join(lines)


def gradescope_results(labs, seconds, seed, notes=()):
    tests = []
    for lab in labs:
        for r in lab.results:
            tests.append(dict(name=f"{r.exercise['id']} {r.test['name']}", number=r.exercise["id"], score=r.score,
                              max_score=r.test["points"], output=r.message or "passed",
                              visibility=r.test["visibility"], tags=[lab.manifest["lab"], f"exercise {r.exercise['id']}"],
                              status="passed" if r.passed else "failed"))
    text = [f"Random inputs: SPRINGLAB_SEED={seed}", *notes]
    for lab in labs:
        text += [f"{lab.manifest['title']}: {lab.score:g} / {lab.max_score:g}", *lab.notes]
    return dict(score=sum(lab.score for lab in labs), max_score=sum(lab.max_score for lab in labs),
                execution_time=round(seconds, 3), output="\n".join(text), visibility="visible",
                stdout_visibility="hidden", tests=tests)


def junit_xml(labs, seconds):
    suites = ET.Element("testsuites", name="springlab", time=f"{seconds:.3f}")
    for lab in labs:
        failures = sum(1 for r in lab.results if not r.passed)
        suite = ET.SubElement(suites, "testsuite", name=lab.manifest["title"], tests=str(len(lab.results)),
                              failures=str(failures), errors="0", time=f"{sum(r.seconds for r in lab.results):.3f}")
        for r in lab.results:
            case = ET.SubElement(suite, "testcase", classname=f"{lab.manifest['lab']}.exercise_{r.exercise['id']}",
                                 name=r.test["name"], time=f"{r.seconds:.3f}")
            ET.SubElement(ET.SubElement(case, "properties"), "property", name="points",
                          value=f"{r.score:g}/{r.test['points']:g}")
            if not r.passed:
                failure = ET.SubElement(case, "failure", message=(r.message.splitlines() or ["failed"])[0][:200])
                failure.text = r.message
    ET.indent(suites)
    return ET.tostring(suites, encoding="unicode", xml_declaration=True) + "\n"


def write_outputs(out, labs, title, seconds, seed, notes=()):
    out = pathlib.Path(out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "report.md").write_text(report_markdown(labs, title, seed))
    (out / "results.json").write_text(json.dumps(gradescope_results(labs, seconds, seed, notes), indent=1) + "\n")
    (out / "junit.xml").write_text(junit_xml(labs, seconds))


def draw_seed(given=None):
    """--seed, else SPRINGLAB_SEED from the environment (to replay a run), else drawn."""
    if given is not None:
        return given
    if os.environ.get("SPRINGLAB_SEED", "").isdigit():
        return int(os.environ["SPRINGLAB_SEED"])
    return random.randrange(2**32)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--binary", help="grading test executable")
    ap.add_argument("--manifest", required=True, help="tests/<lab>/exercises.json")
    ap.add_argument("--timeout", type=float, default=TIMEOUT, help=f"seconds per test (default {TIMEOUT:g})")
    ap.add_argument("--memory-limit-mb", type=int, default=4096, help="address space per test; 0 = none")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="tests run at once (default: cores)")
    ap.add_argument("--seed", type=int, help="seed for random inputs (default: drawn and printed)")
    ap.add_argument("--expect-percent", type=float, help="exit 1 unless the score is this percentage")
    ap.add_argument("--out", help="folder for report.md, results.json and junit.xml")
    ap.add_argument("--check-handout", help="check the handout's headings against the manifest and exit")
    ap.add_argument("--quiet", action="store_true", help="print only the summary")
    args = ap.parse_args()

    try:
        manifest = load_manifest(args.manifest)
    except ManifestError as error:
        print(error, file=sys.stderr)
        return 2
    if args.check_handout:
        problems = check_handout(manifest, args.check_handout)
        for p in problems:
            print(p, file=sys.stderr)
        print("handout agrees with the manifest" if not problems else f"{len(problems)} problem(s)")
        return 1 if problems else 0
    if not args.binary:
        ap.error("--binary is required")
    binary = str(pathlib.Path(args.binary).resolve())  # tests run in their own folders
    if not os.access(binary, os.X_OK):
        print(f"{binary}: no such test program (was the lab built?)", file=sys.stderr)
        return 2
    sandbox = Sandbox(timeout=args.timeout, memory_mb=args.memory_limit_mb)
    shown = binary
    reachable = tempfile.TemporaryDirectory(prefix="springlab-binary-")
    if sandbox.identity():
        # The sandbox user may not reach the build folder (a checkout under /root): a copy.
        os.chmod(reachable.name, 0o711)
        copy = pathlib.Path(reachable.name) / pathlib.Path(binary).name
        shutil.copy2(binary, copy)
        os.chmod(copy, 0o755)
        binary = str(copy)
    try:
        present = check_binary_against_manifest(binary, manifest, args.manifest, sandbox,
                                                student_build=not (pathlib.Path(args.manifest).resolve().parents[2] / "solutions").exists())
    except ManifestError as error:
        print(error, file=sys.stderr)
        return 2

    seed = draw_seed(args.seed)
    print(f"{manifest['title']}: grading {shown} (SPRINGLAB_SEED={seed})")
    started = time.monotonic()
    results = grade_binary(binary, manifest, seed, sandbox, args.jobs, present)
    lab = LabResult(manifest, results, seed=seed, seconds=time.monotonic() - started)
    print_lab(lab, quiet=args.quiet)
    if args.out:
        write_outputs(args.out, [lab], manifest["title"], lab.seconds, seed)
    percent = 100.0 * lab.score / lab.max_score if lab.max_score else 0.0
    if args.expect_percent is not None and abs(percent - args.expect_percent) > 1e-9:
        print(f"expected {args.expect_percent:g} %, got {percent:.1f} %", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
