#!/usr/bin/env python3
"""Each handout's command examples run as written.

    check_handout_commands.py ROOT BUILD_DIR [--list]

Reads handouts/0*.md and collects every `./springlab ...` command a student is told to type:
the lines of indented and fenced (```sh, ```bash) code blocks, and inline code spans. Runs
each from ROOT, as the student would, with the build in BUILD_DIR (SPRINGLAB_BUILD_DIR) and no
display (`run` then renders headless under Xvfb). In a tree with solutions/ (the instructor's,
whose labs/ is the untouched skeleton) each runs with `--reference`, so it runs a finished lab;
in a student tree it runs as written, and exit 3 naming a missing exercise counts as run.

A command passes when it exits 0 (or 3 as above, or the exit EXPECTED_EXIT gives an example that
shows a failure on purpose), within its time cap, and a file it names with --out exists after a
clean exit. A number the handout states about a scene is checked the same way: a code-block
command whose comment says `# prints NAME = VALUE` (or `NAME > VALUE`, `NAME < VALUE`; several
joined by `;`) passes only when its output holds `NAME = X` (or `NAME X`) with X equal to VALUE
to the digits VALUE is written with (half a unit of its last digit), or beyond the bound; so
the handout's prose quotes the number its command prints, and neither can drift alone. Commands too costly for a test run, and spans that only name a
command or hold a placeholder, are SKIPPED with their reason (printed; listed in SKIP below):
never silently. --list prints what would run and what is skipped, and runs nothing.
"""
import os
import pathlib
import re
import shlex
import subprocess
import sys
import time

# Commands left out on purpose: (regex on the command as written, reason).
SKIP = [
    (r"^\./springlab bench\b", "times the reference for about 3 minutes (Google Benchmark); "
                               "bench.springlab_bench.report_from_one_quick_run covers it"),
    (r"^\./springlab chart stability scenes/(rope|net_hanging|softbody_ball)\.json\b(?!.*--integrators)",
     "the full stability charts of the 80-mass rope (with its stiffness x dt map, about 7 min), of the "
     "32 x 32 cloth (3 to 6 min) and of the ball (about 12 min: explicit Euler's trials run 303 s at "
     "0.1-0.25 ms): studies.chart_commands_write_charts runs the same command on a 20-mass "
     "rope, and tools/handout_charts.sh makes the charts the handouts show"),
    (r"^\./springlab (web|site)\b", "builds with Emscripten for minutes; web.pages and web.site build "
                                      "and test the same pages and site"),
]
# Commands whose point is to fail in a known way: (regex, exit code, why the handout shows it).
EXPECTED_EXIT = [
    (r"^\./springlab sim scenes/net_thesis\.json .*--integrator explicit_euler", 4,
     "section 5: explicit Euler blows up on the thesis' cloth at dt = 1/60 s (exit 4, blow-up)"),
    (r"^\./springlab sim scenes/softbody_ball\.json --integrator explicit_euler --dt 0\.001 --steps 3000", 4,
     "question 6 of handout 03: explicit Euler blows up in the ball's second landing (exit 4, blow-up)"),
    (r"^\./springlab sim scenes/rope\.json --dt 0\.0024 --steps 5000", 4,
     "section 5 of handout 01: symplectic Euler past the rope's limit, stopped by passivity (exit 4)"),
    (r"^\./springlab sim scenes/rope\.json --set rope\.air_friction=0 --integrator explicit_euler", 4,
     "section 5 of handout 01: without air explicit Euler has no stable dt on the rope (exit 4)"),
    (r"^\./springlab sim scenes/net_hanging\.json .*--integrator implicit_euler_blocks --steps 600", 4,
     "section 2 of handout 02: one block sweep past its limit, its growth taken out by the stretch limit, "
     "stopped by passivity on the step's own energy (exit 4)"),
    (r"^\./springlab sim scenes/net_trampoline\.json --integrator explicit_euler --dt 0\.00025 --steps 8000", 4,
     "question 8 of handout 02: explicit Euler below its limit at rest blows up after the stretch limit's "
     "catch (exit 4; with the stretch limit off the same run lasts)"),
    (r"^\./springlab run rope --integrator explicit_euler --dt 0\.0005", 4,
     "section 5: explicit Euler blows up on the rope at dt = 0.5 ms; the headless run says so (exit 4)"),
]
TIME_CAP_S = 240  # per command: a `run` renders 240 frames; a `check` runs a lab's tests


def commands(handout):
    """(line, command) for every `./springlab ...` the handout shows."""
    text = handout.read_text()
    lines = text.splitlines()
    found = []
    in_fence, fence_runs = False, False
    for number, line in enumerate(lines, 1):
        stripped = line.strip()
        if stripped.startswith("```"):
            if not in_fence:
                in_fence, fence_runs = True, stripped[3:].strip() in ("", "sh", "bash", "shell", "console")
            else:
                in_fence = False
            continue
        code = None
        if in_fence and fence_runs:
            code = stripped.removeprefix("$ ")
        elif not in_fence and line.startswith("    ") and stripped.startswith("./springlab"):
            code = stripped
        if code and code.startswith("./springlab"):
            comment = code.partition(" #")[2]
            found.append((number, code.split("  #")[0].split(" #")[0].strip(), comment.strip()))
    # Inline spans, which may wrap over a line break.
    for m in re.finditer(r"`(\./springlab[^`]*)`", text):
        number = text.count("\n", 0, m.start()) + 1
        found.append((number, " ".join(m.group(1).split()), ""))
    return sorted(set(found))


NUMBER = r"-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?"


def expectations(comment):
    """[(name, relation, value as written)] from a comment `prints NAME = VALUE; NAME > VALUE`."""
    found = []
    if comment.startswith("prints "):
        for part in comment[len("prints "):].split(";"):
            m = re.fullmatch(rf"\s*([a-z_][a-z_ ]*?)\s*(=|>|<)\s*({NUMBER})(?:\s*\S*)?\s*", part)
            if m:
                found.append((m.group(1), m.group(2), m.group(3)))
    return found


def number_problems(output, wanted):
    """What in OUTPUT disagrees with the handout's numbers WANTED (expectations())."""
    problems = []
    for name, relation, written in wanted:
        values = re.findall(rf"\b{re.escape(name)}(?: =)? ({NUMBER})", output)
        if not values:
            problems.append(f"the output has no `{name} = ...` (the handout says {name} {relation} {written})")
            continue
        got, value = float(values[-1]), float(written)
        decimals = len(written.split(".")[1].split("e")[0].split("E")[0]) if "." in written else 0
        exponent = int(re.split("[eE]", written)[1]) if re.search("[eE]", written) else 0
        slack = 0.5 * 10.0 ** (exponent - decimals)
        fits = {"=": abs(got - value) <= slack * (1 + 1e-9), ">": got > value, "<": got < value}[relation]
        if not fits:
            problems.append(f"the handout says {name} {relation} {written}, the command printed {values[-1]}")
    return problems


def why_skipped(command):
    for pattern, reason in SKIP:
        if re.search(pattern, command):
            return reason
    words = shlex.split(command)
    if len(words) < 3:
        return "names the command only, with nothing to run it on"
    # (`=[` is a JSON value, as in --set net.colliders.spheres=[], not a placeholder.)
    if re.search(r"<|(?<![=,\[])\[", command) or any(re.fullmatch(r"[A-Z][A-Z_]*", w) for w in words):
        return "holds a placeholder (<...>, [...] or a name in capitals such as DT)"
    return None


def main():
    root, build = pathlib.Path(sys.argv[1]).resolve(), pathlib.Path(sys.argv[2]).resolve()
    only_list = "--list" in sys.argv[3:]
    instructor = (root / "solutions").is_dir()
    env = dict(os.environ, SPRINGLAB_BUILD_DIR=str(build))
    env.pop("DISPLAY", None)
    env.pop("WAYLAND_DISPLAY", None)
    failures, ran, skipped = [], 0, 0
    seen = {}  # command -> where it ran first
    for handout in sorted((root / "handouts").glob("0*.md")):
        for number, command, comment in commands(handout):
            where = f"{handout.name}:{number}"
            if command in seen:
                print(f"same as {seen[command]}: {command}")
                continue
            seen[command] = where
            reason = why_skipped(command)
            if reason:
                skipped += 1
                print(f"SKIPPED {where}: {command}\n        ({reason})")
                continue
            words = shlex.split(command)
            if instructor and words[1] in ("run", "sim", "check", "chart", "advise"):
                words.append("--reference")
            if only_list:
                print(f"WOULD RUN {where}: {' '.join(words)}")
                continue
            out = words[words.index("--out") + 1] if "--out" in words[:-1] else None
            if out:
                (root / out).unlink(missing_ok=True)
            start = time.monotonic()
            try:
                p = subprocess.run(words, cwd=root, env=env, capture_output=True, text=True, timeout=TIME_CAP_S)
                code, output = p.returncode, p.stdout + p.stderr
            except subprocess.TimeoutExpired as e:
                code, output = None, f"no exit within {TIME_CAP_S} s\n{e.stdout or ''}{e.stderr or ''}"
            seconds = time.monotonic() - start
            ran += 1
            expected = next(((c, why) for pattern, c, why in EXPECTED_EXIT if re.search(pattern, command)), (0, ""))
            missing_exercise = code == 3 and not instructor and "not implemented" in output
            ok = code == expected[0] or missing_exercise
            if expected[0] != 0:
                print(f"        (expects exit {expected[0]}: {expected[1]})")
            if ok and out and code == 0 and not (root / out).exists():
                ok, output = False, output + f"\n{out} was not written"
            wrong = number_problems(output, expectations(comment)) if code == 0 else []
            if ok and wrong:
                ok, output = False, "\n".join(wrong) + "\n" + output
            elif expectations(comment):
                print(f"        (checks {comment})")
            print(f"{'ok' if ok else 'FAILED'} {where} ({seconds:.1f} s, exit {code}): {' '.join(words)}")
            if not ok:
                failures.append(f"{where}: {' '.join(words)}: exit {code}\n{output[-3000:]}")
    for f in failures:
        print("FAIL:", f)
    print(f"handout commands: {ran} ran, {skipped} skipped, {len(failures)} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
