#!/usr/bin/env python3
"""Run one lab's grading tests, each in its own process with a time limit, and score them.

Points come from the lab's manifest (tests/<lab>/exercises.json), the one place they are
declared. A test scores only if its process exits 0 AND GoogleTest's JSON report, written to
a fresh file, shows it ran and passed: a crash, a hang, exit(0) from inside the test or
printed fake output score nothing.

    tools/grade.py --binary build/tests/rope_grading_student --manifest tests/01_rope/exercises.json
    tools/grade.py ... --expect-percent 100        exit 1 unless the score is exactly 100 %
    tools/grade.py ... --out DIR                   also write DIR/report.md and DIR/results.json
    tools/grade.py --manifest M --check-handout H  check the handout's exercise headings and points
"""
import argparse
import concurrent.futures
import json
import os
import pathlib
import random
import re
import subprocess
import sys
import tempfile
import time


def load_manifest(path):
    data = json.loads(pathlib.Path(path).read_text())
    for ex in data["exercises"]:
        ex["points"] = sum(t["points"] for t in ex["tests"])
        for t in ex["tests"]:
            if t["visibility"] not in ("visible", "hidden", "after_due_date", "after_published"):
                raise SystemExit(f"{path}: test {t['name']}: unknown visibility {t['visibility']!r}")
    return data


def listed_tests(binary):
    out = subprocess.run([binary, "--gtest_list_tests"], capture_output=True, text=True, timeout=60)
    if out.returncode != 0:
        raise SystemExit(f"{binary}: --gtest_list_tests failed:\n{out.stderr}")
    names, suite = [], None
    for line in out.stdout.splitlines():
        if not line.strip() or line.startswith("Running main()"):
            continue
        if not line.startswith(" "):
            suite = line.split("#")[0].strip()
        else:
            names.append(suite + line.split("#")[0].strip())
    return names


def run_one(binary, name, timeout, seed):
    """Run a single test in its own process; return (passed, message, seconds)."""
    with tempfile.TemporaryDirectory() as tmp:
        report = pathlib.Path(tmp) / "report.json"
        env = dict(os.environ, SPRINGLAB_SEED=str(seed))
        start = time.monotonic()
        try:
            proc = subprocess.run([binary, f"--gtest_filter={name}", f"--gtest_output=json:{report}"],
                                  capture_output=True, text=True, timeout=timeout, env=env, cwd=tmp)
        except subprocess.TimeoutExpired:
            return False, f"timed out after {timeout} s (an infinite loop, or far too many steps)", timeout
        seconds = time.monotonic() - start
        if proc.returncode < 0:
            return False, f"crashed with signal {-proc.returncode}\n{tail(proc.stdout + proc.stderr)}", seconds
        try:
            result = json.loads(report.read_text())
            case = [t for s in result["testsuites"] for t in s["testsuite"]][0]
        except (OSError, ValueError, KeyError, IndexError):
            return False, f"the test process ended (exit code {proc.returncode}) before reporting a result\n{tail(proc.stdout)}", seconds
        failures = [f["failure"] for f in case.get("failures", [])]
        skipped = case.get("result") == "SKIPPED" or case.get("status") != "RUN"
        if proc.returncode == 0 and not failures and not skipped:
            return True, "", seconds
        if failures:
            return False, "\n".join(clean(f) for f in failures), seconds
        return False, f"did not pass (exit code {proc.returncode}, skipped={skipped})", seconds


def clean(failure):
    # Drop the source location line GoogleTest puts first; students want the physics.
    lines = failure.splitlines()
    if lines and re.match(r"^\S+:\d+$", lines[0]):
        lines = lines[1:]
    return "\n".join(lines)


def tail(text, lines=15):
    return "\n".join(text.strip().splitlines()[-lines:])


def check_handout(manifest, handout_path):
    text = pathlib.Path(handout_path).read_text()
    problems = []
    for ex in manifest["exercises"]:
        heading = f"### Exercise {ex['id']}: {ex['title']} ({ex['points']} points)"
        if heading not in text.splitlines():
            problems.append(f"{handout_path}: missing the heading line '{heading}' (points must agree with the manifest)")
    total = sum(ex["points"] for ex in manifest["exercises"])
    if f"{total} points" not in text:
        problems.append(f"{handout_path}: never states the lab's total of {total} points")
    return problems


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--binary", help="grading test executable")
    ap.add_argument("--manifest", required=True, help="tests/<lab>/exercises.json")
    ap.add_argument("--timeout", type=float, default=20.0, help="seconds per test (default 20; each takes < 2 s)")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="tests run at once (default: cores)")
    ap.add_argument("--seed", type=int, help="seed for random inputs (default: drawn and printed)")
    ap.add_argument("--expect-percent", type=float, help="exit 1 unless the score is this percentage")
    ap.add_argument("--out", help="folder for report.md and results.json")
    ap.add_argument("--check-handout", help="check the handout's headings against the manifest and exit")
    ap.add_argument("--quiet", action="store_true", help="print only the summary")
    args = ap.parse_args()

    manifest = load_manifest(args.manifest)
    if args.check_handout:
        problems = check_handout(manifest, args.check_handout)
        for p in problems:
            print(p, file=sys.stderr)
        print("handout agrees with the manifest" if not problems else f"{len(problems)} problem(s)")
        return 1 if problems else 0
    if not args.binary:
        ap.error("--binary is required")
    args.binary = str(pathlib.Path(args.binary).resolve())  # tests run in their own folders
    if not os.access(args.binary, os.X_OK):
        print(f"{args.binary}: no such test program (was the lab built?)", file=sys.stderr)
        return 2

    # Every test in the binary must carry points, and every manifest test must exist
    # (hidden tests are absent from a student release build and are left out there).
    present = set(listed_tests(args.binary))
    declared = {t["name"] for ex in manifest["exercises"] for t in ex["tests"]}
    unpointed = sorted(present - declared)
    if unpointed:
        print(f"{args.manifest}: tests without points: {', '.join(unpointed)}", file=sys.stderr)
        return 2
    missing = sorted(t["name"] for ex in manifest["exercises"] for t in ex["tests"]
                     if t["name"] not in present and t["visibility"] == "visible")
    if missing:
        print(f"{args.binary}: manifest tests not found in the binary: {', '.join(missing)}", file=sys.stderr)
        return 2

    # The seed: --seed, else SPRINGLAB_SEED from the environment (to replay a run), else drawn.
    if args.seed is not None:
        seed = args.seed
    elif os.environ.get("SPRINGLAB_SEED", "").isdigit():
        seed = int(os.environ["SPRINGLAB_SEED"])
    else:
        seed = random.randrange(2**32)
    print(f"{manifest['title']}: grading {args.binary} (SPRINGLAB_SEED={seed})")
    # Run the tests side by side, each in its own process; report them in manifest order.
    started = time.monotonic()
    todo = [(ex, t) for ex in manifest["exercises"] for t in ex["tests"] if t["name"] in present]
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        outcomes = list(pool.map(lambda et: run_one(args.binary, et[1]["name"], args.timeout, seed), todo))
    results, score, max_score = [], 0.0, 0.0
    for (ex, t), (passed, message, seconds) in zip(todo, outcomes):
        points = t["points"] if passed else 0
        score += points
        max_score += t["points"]
        results.append(dict(exercise=ex, test=t, passed=passed, message=message, seconds=seconds, score=points))
        if not args.quiet:
            mark = "PASS" if passed else "FAIL"
            print(f"  {mark} {points}/{t['points']}  {ex['id']} {t['name']}")
            if message:
                print("         " + message.replace("\n", "\n         "))

    percent = 100.0 * score / max_score if max_score else 0.0
    print(f"{manifest['title']}: {score:g} / {max_score:g} points ({percent:.1f} %)")
    if args.out:
        write_outputs(pathlib.Path(args.out), manifest, results, score, max_score, time.monotonic() - started, seed)
    if args.expect_percent is not None and abs(percent - args.expect_percent) > 1e-9:
        print(f"expected {args.expect_percent:g} %, got {percent:.1f} %", file=sys.stderr)
        return 1
    return 0


def write_outputs(out, manifest, results, score, max_score, seconds, seed):
    out.mkdir(parents=True, exist_ok=True)
    lines = [f"# {manifest['title']}: {score:g} / {max_score:g} points", "", f"Seed: SPRINGLAB_SEED={seed}", ""]
    for ex in manifest["exercises"]:
        rows = [r for r in results if r["exercise"] is ex]
        got = sum(r["score"] for r in rows)
        lines += [f"## Exercise {ex['id']}: {ex['title']} ({got:g} / {ex['points']} points)", ""]
        for r in rows:
            lines.append(f"- {'pass' if r['passed'] else 'FAIL'} ({r['score']:g}/{r['test']['points']}) `{r['test']['name']}`")
            if r["message"]:
                lines += ["", "  ```", *("  " + m for m in r["message"].splitlines()), "  ```", ""]
        lines.append("")
    (out / "report.md").write_text("\n".join(lines))
    tests = [dict(name=f"{r['exercise']['id']} {r['test']['name']}", number=r["exercise"]["id"], score=r["score"],
                  max_score=r["test"]["points"], output=r["message"] or "passed", visibility=r["test"]["visibility"],
                  tags=[manifest["lab"], f"exercise {r['exercise']['id']}"], status="passed" if r["passed"] else "failed")
             for r in results]
    (out / "results.json").write_text(json.dumps(dict(score=score, max_score=max_score, execution_time=round(seconds, 3),
                                                      output=f"SPRINGLAB_SEED={seed}", tests=tests), indent=1))


if __name__ == "__main__":
    sys.exit(main())
