#!/usr/bin/env python3
"""Every file a student's text cites exists in the student's tree.

    check_cited_paths.py ROOT [--list]

Builds the student release of ROOT (tools/release.py) in a temporary folder and reads what a
student reads there: handouts/0*.md, labs/*/README.md and README.md. A citation is a code span
or a Markdown link target that names a path: it holds a `/` or ends with a file extension
(`.cpp`, `.json`, `.md`, ...). Each must exist in the release, found as written from the tree's
root or from the citing file's folder, or, for a path given relative to a folder the text
names just before (`src/net.cpp` beside `framework/labs/net/`), as the end of a released path;
a bare file name (`net.cpp`) must be some released file's name. Not checked, and why: build
outputs (`build/`, `out/`), absolute paths (`/tmp/...`), URLs, placeholders (`<lab>`, `*`).
Fails listing each missing citation with its file and line: an instructor-only file
(`tools/make_skeleton.py`) or an author's note the release leaves out is such a case.
--list prints every citation and where it resolved.
"""
import pathlib
import re
import subprocess
import sys
import tempfile

EXTENSIONS = {"md", "cpp", "hpp", "h", "json", "py", "obj", "png", "csv", "txt", "sh", "yml",
              "cmake", "svg", "html"}
GENERATED = ("build", "out")
CODE_SPAN = re.compile(r"`([^`\n]+)`")
LINK = re.compile(r"\]\(([^)\s]+)\)")
# A path-like token: letters, digits and . _ - / only.
PATHLIKE = re.compile(r"^[A-Za-z0-9_.][A-Za-z0-9_./-]*$")
# A placeholder part of a path: `NN_name`, `LAB` (a word in capitals).
PLACEHOLDER = re.compile(r"(^|[_.-])[A-Z]{2,}($|[_.-])")


def candidates(token, folders):
    """The path a token cites, or None when it names no file (a formula such as `dF/dx` or
    `1/60`, an identifier, a flag, a placeholder). `folders`: the instructor tree's top-level
    names, which a path without an extension must start with."""
    token = token.strip().rstrip(".,:;")
    if token.startswith("./"):
        token = token[2:]
    if not token or not PATHLIKE.match(token) or ".." in token or token.startswith("."):
        return None
    parts = [part for part in token.split("/") if part]
    if any(PLACEHOLDER.search(part) for part in parts):
        return None
    if any(parts[0] == g or parts[0].startswith(g + "-") for g in GENERATED):
        return None
    name = parts[-1]
    has_ext = "." in name and name.rsplit(".", 1)[-1].lower() in EXTENSIONS
    if has_ext:
        return token
    if "/" in token and parts[0] in folders and "." not in name:
        return token
    return None


def citations(text, folders):
    """(line, path) for each cited path in a Markdown text."""
    found = []
    for pattern in (CODE_SPAN, LINK):
        for m in pattern.finditer(text):
            line = text.count("\n", 0, m.start()) + 1
            content = m.group(1)
            if "://" in content or content.startswith(("/", "#", "mailto:")):
                continue
            # A code span may be a command: check each word that names a path.
            for word in content.split():
                if word.startswith(("/", "-", "http")) or "=" in word:
                    continue
                path = candidates(word, folders)
                if path:
                    found.append((line, path))
    return sorted(set(found))


def resolve(path, citing, tree, released):
    """Where a cited path is in the release, or None."""
    bare = path.rstrip("/")
    for base in (tree, citing.parent):
        if (base / bare).exists():
            return (base / bare).relative_to(tree).as_posix()
    if "/" in bare:
        suffix = "/" + bare
        for rel in released:
            if ("/" + rel).endswith(suffix) or ("/" + rel).find(suffix + "/") >= 0:
                return rel
        return None
    for rel in released:
        if rel.rsplit("/", 1)[-1] == bare:
            return rel
    return None


def student_texts(tree):
    return ([tree / "README.md"] + sorted((tree / "handouts").glob("0*.md"))
            + sorted((tree / "labs").glob("*/README.md")))


def main():
    args = sys.argv[1:]
    listing = "--list" in args
    args = [a for a in args if a != "--list"]
    if len(args) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    root = pathlib.Path(args[0]).resolve()
    with tempfile.TemporaryDirectory() as work:
        tree = pathlib.Path(work) / "student"
        made = subprocess.run([sys.executable, str(root / "tools" / "release.py"), str(tree)],
                              capture_output=True, text=True)
        if made.returncode != 0:
            print(f"the release failed (exit {made.returncode}):\n{made.stdout}{made.stderr}", file=sys.stderr)
            return 1
        folders = {p.name for p in root.iterdir()} | {p.name for p in tree.iterdir()}
        released = sorted(p.relative_to(tree).as_posix() for p in tree.rglob("*"))
        texts = student_texts(tree)
        missing, count = [], 0
        for text in texts:
            if not text.is_file():
                missing.append(f"{text.relative_to(tree)}: not in the release")
                continue
            for line, path in citations(text.read_text(), folders):
                count += 1
                where = resolve(path, text, tree, released)
                if listing:
                    print(f"{text.relative_to(tree)}:{line}: {path} -> {where or 'MISSING'}")
                if where is None:
                    missing.append(f"{text.relative_to(tree)}:{line}: cites `{path}`, which the student tree does not have")
    if missing:
        print("Files a student's text cites but the student release lacks (ship them, or reword "
              "the text for students):", file=sys.stderr)
        for entry in missing:
            print("  " + entry, file=sys.stderr)
        return 1
    print(f"{count} citations in {len(texts)} student texts, each found in the release")
    return 0


if __name__ == "__main__":
    sys.exit(main())
