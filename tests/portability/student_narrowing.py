#!/usr/bin/env python3
"""A student's `int n = v.size();` warns but never stops their build, and grades the same.
(The same for `for (int k = 0; k < v.size(); ++k)`.)

Students' laptops (issue 14): -Wconversion stays on for the exercises so that students see
the narrowing, but their build (even with SPRINGLAB_WARNINGS_AS_ERRORS, as in CI) must not
stop on it, and the grader must give the same points as without it. This test takes Lab 1's
reference, adds exactly that line to one exercise (build_rope.cpp, Exercise 1.7), then
  1. compiles that file with the build's own command for the student's copy of it
     (compile_commands.json): it must compile, and the compiler must warn (-Wconversion);
  2. grades the lab (tools/submission.py, the build as cache): 100 %, as the reference.
usage: student_narrowing.py --build BUILD --work DIR
"""
import argparse
import json
import pathlib
import shlex
import shutil
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXERCISE = "build_rope.cpp"
ANCHOR = "  return rope;\n  // END EXERCISE 1.7"
# `n` is taken in that function (and -Wshadow is an error in CI), so the count is `count`.
NARROWING = ("  const std::vector<Spring>& v = rope.springs;\n"
             "  int count = v.size();  // as `int n = v.size();`: narrowing from size_t (-Wconversion)\n"
             "  for (int k = 0; k < v.size(); ++k) --count;  // int against size_t (-Wsign-compare)\n"
             "  (void)count;\n")


def fail(message):
    print(f"student_narrowing: {message}", file=sys.stderr)
    sys.exit(1)


def submission_with_narrowing(work):
    """A flat copy of Lab 1's reference exercises with the narrowing line in EXERCISE."""
    lab = work / "submission"
    shutil.rmtree(lab, ignore_errors=True)
    shutil.copytree(ROOT / "solutions" / "01_rope", lab)
    path = lab / EXERCISE
    text = path.read_text()
    if ANCHOR not in text:
        fail(f"{path}: the line `{ANCHOR.splitlines()[0].strip()}` of Exercise 1.7 moved; update ANCHOR")
    path.write_text(text.replace(ANCHOR, NARROWING + ANCHOR))
    return lab


def student_compile_command(build):
    """The build's command that compiles the student's labs/01_rope/EXERCISE."""
    student = (ROOT / "labs" / "01_rope" / EXERCISE).resolve()
    commands = json.loads((build / "compile_commands.json").read_text())
    for entry in commands:
        if pathlib.Path(entry["file"]).resolve() == student:
            return entry
    fail(f"{build}/compile_commands.json has no command for {student}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", type=pathlib.Path, required=True)
    parser.add_argument("--work", type=pathlib.Path, required=True)
    args = parser.parse_args()
    args.work.mkdir(parents=True, exist_ok=True)
    lab = submission_with_narrowing(args.work)

    # 1. The student's own compile command, on the edited file: compiles, with a warning.
    entry = student_compile_command(args.build)
    command = shlex.split(entry["command"]) if "command" in entry else list(entry["arguments"])
    student = str((ROOT / "labs" / "01_rope" / EXERCISE).resolve())
    command = [str(lab / EXERCISE) if c in (entry["file"], student) else c for c in command]
    if "-o" in command:
        command[command.index("-o") + 1] = str(args.work / "narrowing.o")
    compiled = subprocess.run(command, cwd=entry["directory"], capture_output=True, text=True)
    if compiled.returncode != 0:
        fail(f"the student's build stops on `int n = v.size();` (-Werror: {'-Werror' in command}):\n{compiled.stderr}")
    if "Wconversion" not in compiled.stderr:
        fail(f"no -Wconversion warning for `int n = v.size();`; the compiler said:\n{compiled.stderr}")
    print(f"compiles with a warning (-Werror in the command: {'-Werror' in command})")

    # 2. The grader: the same points as the reference.
    graded = subprocess.run([sys.executable, str(ROOT / "tools" / "submission.py"), "grade", str(lab),
                             "--lab", "rope", "--cache", str(args.build), "--no-build", "--seed", "2024",
                             "--quiet", "--expect-percent", "100", "--out", str(args.work / "report")],
                            capture_output=True, text=True)
    print(graded.stdout, end="")
    if graded.returncode != 0:
        fail(f"graded below 100 % with the narrowing line:\n{graded.stdout}{graded.stderr}")
    print("graded 100 %, as the reference")


if __name__ == "__main__":
    main()
