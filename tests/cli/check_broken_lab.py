#!/usr/bin/env python3
"""A compile error stops only what it must: in a student tree (tools/release.py) whose Lab 1
exercises are written (the reference's copied in) and whose Lab 2 has one file that does not
compile (normals.cpp multiplies two Vec3 with `a * b`), `./springlab sim` and `run` of a Lab 1
scene build and run, `./springlab check rope` scores every point, a Lab 3 scene still builds and
runs, and `run net` fails with the compiler's error naming the broken file. `check net` grades
the lab as `grade` would: normals.cpp costs exercise 2.3 only, the other files' tests run and
score (2.1 written: its public points), the compiler's first error comes first, placed at
normals.cpp's line with a hint, and its full text only with --verbose; a failed test (2.2 with a
sign error) reads as what was expected, what came and what to check, GoogleTest's own text
only with --verbose. The tree is configured by the script itself, as a student's first command
does, so CMake's configure must not trip on the broken file either.

    check_broken_lab.py --work DIR     (run by ctest; DIR keeps the tree and its build/)

DIR/tree is rewritten file by file, and only where a file's content changed, so its build
folder stays warm and a rerun rebuilds nothing but the broken file.
"""
import argparse
import json
import os
import pathlib
import shutil
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
KEEP = {"build", "out"}  # the tree's own build folder and outputs survive a sync


def sync(source, tree, overrides):
    """Make tree hold source's files with the overrides' contents (relative path -> text),
    writing only the files whose content differs, so make sees the others as unchanged."""
    wanted = {p.relative_to(source): p.read_bytes() for p in source.rglob("*") if p.is_file()}
    wanted.update({pathlib.Path(rel): text.encode() for rel, text in overrides.items()})
    for rel, content in wanted.items():
        target = tree / rel
        if target.is_file() and target.read_bytes() == content:
            continue
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(content)
        if (source / rel).is_file():
            shutil.copymode(source / rel, target)
    for path in sorted(tree.rglob("*"), reverse=True):
        rel = path.relative_to(tree)
        if rel.parts[0] in KEEP:
            continue
        if path.is_file() and rel not in wanted:
            path.unlink()
        elif path.is_dir() and not any(path.iterdir()):
            path.rmdir()


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--work", required=True)
    args = ap.parse_args()
    work = pathlib.Path(args.work).resolve()
    staging, tree = work / "staging", work / "tree"

    # The student tree: Lab 1 written (the reference's files), Lab 2 with a syntax error.
    release = subprocess.run([sys.executable, str(ROOT / "tools" / "release.py"), str(staging), "--force"],
                             capture_output=True, text=True)
    if release.returncode != 0:
        print(release.stdout + release.stderr)
        return 1
    overrides = {f"labs/01_rope/{p.name}": p.read_text() for p in sorted((ROOT / "solutions" / "01_rope").glob("*.cpp"))}
    # Lab 2: 2.1 written, 2.2 with a sign error, 2.3 (normals.cpp) with a cross product written
    # as a * b, which Eigen refuses at compile time.
    net = ROOT / "solutions" / "02_net"
    overrides["labs/02_net/build_net.cpp"] = (net / "build_net.cpp").read_text()
    force = (net / "spring_force.cpp").read_text()
    overrides["labs/02_net/spring_force.cpp"] = force.replace("(-springConstant *", "(springConstant *")
    normals = (net / "normals.cpp").read_text()
    cross = "(pos[t.b] - pos[t.a]).cross(pos[t.c] - pos[t.a])"
    broken_rel = "labs/02_net/normals.cpp"
    overrides[broken_rel] = normals.replace(cross, "(pos[t.b] - pos[t.a]) * (pos[t.c] - pos[t.a])")
    broken_line = 1 + normals[:normals.index(cross)].count("\n")
    if overrides["labs/02_net/spring_force.cpp"] == force or overrides[broken_rel] == normals:
        print("the reference's spring_force.cpp or normals.cpp changed: update this test's edits")
        return 1
    tree.mkdir(parents=True, exist_ok=True)
    sync(staging, tree, overrides)

    # A student's environment: no display (run renders under Xvfb), warnings not errors, the
    # tree's own build folder; ccache keyed on the tree's relative paths.
    env = {k: v for k, v in os.environ.items()
           if k not in ("DISPLAY", "WAYLAND_DISPLAY", "SPRINGLAB_WARNINGS_AS_ERRORS", "SPRINGLAB_BUILD_DIR")}
    env["CCACHE_BASEDIR"] = str(tree)
    failures = []

    def springlab(*argv):
        proc = subprocess.run([str(tree / "springlab"), *argv], capture_output=True, text=True, env=env,
                              cwd=tree, timeout=1500)
        return proc, proc.stdout + proc.stderr

    def expect(what, proc, text, ok, *needles):
        if not ok:
            failures.append(f"{what}: exit code {proc.returncode}\n{text[-4000:]}")
        for needle in needles:
            if needle not in text:
                failures.append(f"{what}: output lacks {needle!r}\n{text[-4000:]}")

    # Lab 1 builds and runs beside the broken Lab 2: the first command configures the tree.
    proc, text = springlab("sim", "scenes/rope.json", "--steps", "10", "--out", "out/rope.json")
    expect("sim scenes/rope.json", proc, text, proc.returncode == 0, "sim: ")
    proc, text = springlab("check", "rope")
    expect("check rope", proc, text, proc.returncode == 0, "(100.0 %")
    viewer = "SPRINGLAB_BUILD_VIEWER:BOOL=ON" in (tree / "build" / "CMakeCache.txt").read_text()
    if viewer and shutil.which("Xvfb"):
        proc, text = springlab("run", "rope", "--frames", "2")
        expect("run rope", proc, text, proc.returncode == 0, "snapshot written")
    else:
        print("run rope: skipped (no viewer in this build, or no Xvfb)")

    # --reference in a student tree says at once that the tree has no solutions/ (exit 2),
    # instead of a build failure with no compiler message above it.
    proc, text = springlab("sim", "scenes/rope.json", "--reference", "--steps", "10", "--out", "out/ref.json")
    expect("sim --reference", proc, text, proc.returncode == 2 and "build failed" not in text,
           "solutions/, which a student tree does not have")

    # Lab 3 builds on Lab 1, not on Lab 2: its scene builds and runs (exit 3 names the first
    # of its exercises still a stub).
    proc, text = springlab("sim", "scenes/softbody_ball.json", "--steps", "2", "--out", "out/ball.json")
    expect("sim scenes/softbody_ball.json", proc, text, proc.returncode in (0, 3) and "build failed" not in text)

    # Lab 2 stops at its compile error, which names the file.
    proc, text = springlab("run", "net", "--frames", "2")
    expect("run net", proc, text, proc.returncode != 0, broken_rel, "build failed")

    # check net grades beside the broken file: 2.3 scores 0, 2.1 its public points; the summary
    # (file:line, the hint, where the full text is) comes first, the compiler's text only with
    # --verbose; 2.2's failure reads as sentences, GoogleTest's text only with --verbose.
    manifest = json.loads((tree / "tests" / "02_net" / "exercises.json").read_text())
    build_points = sum(t["points"] for ex in manifest["exercises"] if ex["id"] == "2.1"
                       for t in ex["tests"] if t["visibility"] == "visible")
    summary = f"{broken_rel}:{broken_line}:"
    proc, text = springlab("check", "net")
    expect("check net", proc, text, proc.returncode == 0,
           "normals.cpp does not compile, so it is graded as the released skeleton's normals.cpp: exercise 2.3 "
           "scores 0", summary, "hint: a * b of two Vec3 is no product Eigen defines: use a.dot(b)",
           "The compiler's full text: ./springlab check net --verbose, or build/check-net.log",
           f"public {build_points}/{build_points}", "expected: ", "came: ", "check: ",
           "GoogleTest's own text of each failure: ./springlab check net --verbose")
    for needle in ("required from", "In instantiation of", "GoogleTest: "):
        if needle in text:
            failures.append(f"check net: {needle!r} without --verbose\n{text[-4000:]}")
    if summary in text and "Exercise 2.1" in text and text.index("Exercise 2.1") < text.index(summary):
        failures.append(f"check net: the compile summary comes after the exercises\n{text[-4000:]}")
    proc, text = springlab("check", "net", "--verbose")
    expect("check net --verbose", proc, text, proc.returncode == 0, summary, "required from", "GoogleTest: ")
    if summary in text and "required from" in text and text.index("required from") < text.index(summary):
        failures.append(f"check net --verbose: the compiler's text comes before the summary\n{text[:4000]}")

    for failure in failures:
        print(f"FAILED: {failure}", file=sys.stderr)
    if not failures:
        print(f"with {broken_rel} broken: rope runs and scores 100 %, softbody runs, net names the file, and "
              f"check net scores the other files with the first error and a hint first")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
