#!/usr/bin/env python3
"""A compile error in one lab stops only that lab: in a student tree (tools/release.py) whose
Lab 1 exercises are written (the reference's copied in) and whose Lab 2 has a syntax error,
`./springlab sim` and `run` of a Lab 1 scene build and run, `./springlab check rope` scores
every point, a Lab 3 scene still builds and runs, while `run net` fails with the compiler's
error naming the broken file. The tree is configured by the script itself, as a student's
first command does, so CMake's configure must not trip on the broken file either.

    check_broken_lab.py --work DIR     (run by ctest; DIR keeps the tree and its build/)

DIR/tree is rewritten file by file, and only where a file's content changed, so its build
folder stays warm and a rerun rebuilds nothing but the broken file.
"""
import argparse
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
    broken = sorted((staging / "labs" / "02_net").glob("*.cpp"))[0]
    broken_rel = f"labs/02_net/{broken.name}"
    overrides[broken_rel] = broken.read_text() + "\nthis line is not C++\n"
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

    for failure in failures:
        print(f"FAILED: {failure}", file=sys.stderr)
    if not failures:
        print(f"with {broken_rel} broken: rope runs and scores 100 %, softbody runs, net names the file")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
