#!/usr/bin/env python3
"""Write a Gradescope autograder bundle: a zip with setup.sh and run_autograder at its root and
this instructor tree under springlab/ (Gradescope unzips it into /autograder/source).

    tools/autograder.py OUT.zip               every lab in one assignment
    tools/autograder.py OUT.zip --lab rope    one assignment per lab: this lab only

setup.sh installs the Debian packages, builds the grading cache once (framework, reference
oracle, test objects) and makes the whole tree unreadable to other users (build-grader/
included). run_autograder grades /autograder/submission with tools/submission.py as root,
which compiles the student's code in bubblewrap as `nobody` (seeing only the toolchain, the
framework's headers and the submission), runs it in bubblewrap as a user of its own and takes
every verdict from a judge program that runs no student code (as a user of its own too), and
always leaves
/autograder/results/results.json: when the grader itself fails, a zero score that says why.
(The bundle itself: tools/springlab_grader/gradescope.py.)
"""
import argparse
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tools"))
import release  # noqa: E402
from springlab_grader import gradescope  # noqa: E402


def main():
    ap = argparse.ArgumentParser(prog="springlab autograder", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", help="the bundle to write, e.g. autograder.zip")
    ap.add_argument("--lab", help="grade this lab only (its id: rope): one Gradescope assignment per lab")
    args = ap.parse_args()
    if not (ROOT / "solutions").is_dir():
        print("springlab autograder: this tree has no solutions/: bundle the instructor tree", file=sys.stderr)
        return 2
    if args.lab:
        from springlab_grader.labs import discover_labs  # noqa: PLC0415
        names = [n for lab in discover_labs() for n in (lab.name, lab.dir)]
        if args.lab not in names:
            print(f"springlab autograder: --lab {args.lab}: no such lab ({', '.join(names[::2])})", file=sys.stderr)
            return 2
    out, count = gradescope.bundle(args.out, release.source_files(), lab=args.lab)
    print(f"Gradescope autograder written to {out}{f' for {args.lab} only' if args.lab else ''}: setup.sh, "
          f"run_autograder and {count} files under springlab/")
    return 0


if __name__ == "__main__":
    sys.exit(main())
