#!/usr/bin/env python3
"""Run a lab's reference grading program over many seeds: every random-input test must pass
on the reference for every seed, or a student's score would depend on the seed.

    tools/seed_sweep.py LAB [--seeds N] [--first S] [--jobs J] [--build DIR] [--binary PATH]

LAB is a lab's id, rope, net or softbody (the program is DIR/tests/LAB_grading_reference). One run with
seed FIRST finds the tests that draw random inputs (tests/support/seeded.hpp records
`random_draws` per test); only those then run, once per seed FIRST .. FIRST+N-1, all of them
in one process per seed (each test reseeds itself in SetUp, as when the grader runs it alone),
on J processes at once. Prints, per failing test, its failing seeds and one failure message,
with the command that replays it; exits 1 when any test failed for any seed.
"""
import argparse
import concurrent.futures
import json
import os
import pathlib
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tools"))
from springlab_grader.labs import discover_labs  # noqa: E402


def run(binary, seed, filt, workdir, timeout):
    """One process with SPRINGLAB_SEED=seed: {test: (status, message, random_draws)}."""
    out = pathlib.Path(workdir) / f"seed_{seed}.json"
    env = dict(os.environ, SPRINGLAB_SEED=str(seed))
    env.pop("SPRINGLAB_CALL_TRACE_FD", None)
    cmd = [str(binary), f"--gtest_output=json:{out}", "--gtest_brief=1"]
    if filt:
        cmd.append(f"--gtest_filter={filt}")
    try:
        proc = subprocess.run(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              timeout=timeout, text=True, errors="replace")
    except subprocess.TimeoutExpired:
        return {"<process>": ("failed", f"timed out after {timeout} s", 0)}
    if not out.exists():
        tail = proc.stdout[-1500:]
        return {"<process>": ("failed", f"exit code {proc.returncode}, no report:\n{tail}", 0)}
    report = json.loads(out.read_text())
    out.unlink()
    results = {}
    for suite in report.get("testsuites", []):
        for t in suite.get("testsuite", []):
            name = f"{suite['name']}.{t['name']}"
            failures = t.get("failures", [])
            status = "failed" if failures else ("skipped" if t.get("result") == "SKIPPED" else "passed")
            message = failures[0].get("failure", "") if failures else ""
            results[name] = (status, message, int(t.get("random_draws", 0)))
    if proc.returncode != 0 and not any(s == "failed" for s, _, _ in results.values()):
        results["<process>"] = ("failed", f"exit code {proc.returncode}:\n{proc.stdout[-1500:]}", 0)
    return results


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("lab", choices=[lab.name for lab in discover_labs(ROOT)])
    ap.add_argument("--seeds", type=int, default=1000, help="how many consecutive seeds (default 1000)")
    ap.add_argument("--first", type=int, default=1, help="the first seed (default 1)")
    ap.add_argument("--jobs", type=int, default=2, help="processes at once (default 2)")
    ap.add_argument("--build", default=str(ROOT / "build"), help="the build folder (default build/)")
    ap.add_argument("--binary", help="the grading program, instead of BUILD/tests/LAB_grading_reference")
    ap.add_argument("--filter", default="", help="a --gtest_filter to narrow the swept tests")
    ap.add_argument("--timeout", type=float, default=300, help="seconds per process (default 300)")
    args = ap.parse_args()

    binary = pathlib.Path(args.binary or pathlib.Path(args.build) / "tests" / f"{args.lab}_grading_reference")
    if not binary.is_file():
        print(f"seed_sweep: {binary} not found: build the target {args.lab}_grading_reference", file=sys.stderr)
        return 2

    start = time.monotonic()
    failures = {}  # test -> {"seeds": [...], "message": str}

    def note(seed, results):
        for name, (status, message, _) in results.items():
            if status == "failed":
                entry = failures.setdefault(name, {"seeds": [], "message": message})
                entry["seeds"].append(seed)

    with tempfile.TemporaryDirectory(prefix="seed_sweep_") as workdir:
        first = run(binary, args.first, args.filter, workdir, args.timeout)
        note(args.first, first)
        seeded = sorted(n for n, (_, _, draws) in first.items() if draws > 0)
        if not seeded:
            print(f"seed_sweep: {binary.name}: no test draws random inputs", file=sys.stderr)
            return 2 if "<process>" not in first else 1
        filt = ":".join(seeded)
        seeds = range(args.first + 1, args.first + args.seeds)
        with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
            futures = {pool.submit(run, binary, s, filt, workdir, args.timeout): s for s in seeds}
            for fut in concurrent.futures.as_completed(futures):
                note(futures[fut], fut.result())

    elapsed = time.monotonic() - start
    last = args.first + args.seeds - 1
    print(f"{binary.name}: {len(seeded)} random-input tests of {len(first)}, seeds {args.first}..{last}, "
          f"{args.jobs} jobs, {elapsed:.1f} s")
    for name in sorted(failures):
        entry = failures[name]
        seeds_failed = sorted(entry["seeds"])
        shown = ", ".join(map(str, seeds_failed[:30])) + (" ..." if len(seeds_failed) > 30 else "")
        print(f"\nFAILED {name}: {len(seeds_failed)}/{args.seeds} seeds: {shown}")
        print(f"  replay: SPRINGLAB_SEED={seeds_failed[0]} {binary} --gtest_filter={name}")
        for line in entry["message"].strip().splitlines()[:12]:
            print(f"  | {line}")
    if not failures:
        print("every random-input test passed for every seed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
