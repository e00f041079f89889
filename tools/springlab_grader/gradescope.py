"""The Gradescope autograder bundle: a zip with setup.sh and run_autograder at its root and the
instructor tree under springlab/ (Gradescope unzips it into /autograder/source). setup.sh builds
the grading cache once and hides the reference from other users; run_autograder grades
/autograder/submission with tools/submission.py and always leaves results/results.json."""
import pathlib
import stat
import zipfile

from .labs import ROOT

SETUP = r"""#!/usr/bin/env bash
# Gradescope: runs once, as root, when the autograder image is built.
set -euo pipefail
SRC=/autograder/source/springlab
chmod +x "$SRC/springlab"
"$SRC/springlab" setup
# Build the framework, the reference oracle and the grading tests once; each submission then
# compiles only its own lab files.
# (With --lab, that lab's only: one Gradescope assignment per lab.)
python3 "$SRC/tools/submission.py" prepare @LAB_ARGS@
# Student code and the compiler run in bubblewrap and see none of this tree; where namespaces
# are not allowed they run as users of their own. Nothing of the tree (the reference, the
# hidden tests, build-grader/ with its objects) is theirs to read: what the sandbox needs is
# staged by the grader (tools/springlab_grader/staging.py).
chmod -R go-rwx "$SRC"
"""

RUN = r"""#!/usr/bin/env bash
# Gradescope: runs as root for each submission. Always leaves results/results.json.
AUTOGRADER="${SPRINGLAB_AUTOGRADER_ROOT:-/autograder}"
SRC="$AUTOGRADER/source/springlab"
RESULTS="$AUTOGRADER/results"
mkdir -p "$RESULTS"
rm -f "$RESULTS/results.json"
LOG="$(mktemp)"
# shellcheck disable=SC2086
python3 "$SRC/tools/submission.py" grade "$AUTOGRADER/submission" --out "$RESULTS" @LAB_ARGS@ \
  ${SPRINGLAB_AUTOGRADER_ARGS:-} 2>&1 | tee "$LOG"
status="${PIPESTATUS[0]}"
if [[ "$status" != 0 || ! -s "$RESULTS/results.json" ]]; then
  # The grader could not grade: a zero that says why, so the student sees more than a blank.
  python3 - "$RESULTS/results.json" "$LOG" "$status" <<'PY'
import json, sys
log = open(sys.argv[2], errors="replace").read().strip().splitlines()[-30:]
json.dump({"score": 0, "execution_time": 0, "visibility": "visible", "stdout_visibility": "visible",
           "output": "The grader could not grade this submission (exit code " + sys.argv[3] + "). "
                     "Ask your instructor; the last lines of its log:\n" + "\n".join(log),
           "tests": []}, open(sys.argv[1], "w"), indent=1)
PY
fi
exit 0
"""


def bundle(out, source_files, lab=None):
    """Write the bundle to out (.zip) with the tree's files (paths relative to the tree, as
    tools/release.py's source_files() lists them); (its path, how many files). With `lab`
    (rope or 01_rope), the bundle grades that lab only (one Gradescope assignment per lab,
    flat exercise files taken as that lab's); else every lab."""
    lab_args = f"--lab {lab}" if lab else ""
    if lab and not all(c.isalnum() or c == "_" for c in lab):
        raise SystemExit(f"springlab autograder: --lab {lab}: not a lab name")
    out = pathlib.Path(out).resolve()
    if out.suffix != ".zip":
        raise SystemExit(f"springlab autograder: {out}: the bundle's name must end in .zip")
    out.parent.mkdir(parents=True, exist_ok=True)
    count = 0
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as zf:
        for name, text in (("setup.sh", SETUP), ("run_autograder", RUN)):
            info = zipfile.ZipInfo(name)
            info.external_attr = (stat.S_IFREG | 0o755) << 16
            zf.writestr(info, text.replace("@LAB_ARGS@", lab_args))
        for rel in source_files:
            if rel.parts[0] in (".ci",):
                continue
            path = ROOT / rel
            info = zipfile.ZipInfo.from_file(path, f"springlab/{rel.as_posix()}")
            info.compress_type = zipfile.ZIP_DEFLATED
            zf.writestr(info, path.read_bytes())
            count += 1
    return out, count
