"""What a submission is: a folder or a zip (extracted safely), the folder in it of each lab, and
the exercise files of that folder (the .cpp files of the released skeleton); anything else is
ignored and noted. Also the submissions of a class (grade-all)."""
import os
import pathlib
import re
import stat
import zipfile

from .errors import GradeError

SOURCE_SUFFIXES = (".cpp",)  # a lab folder's exercise files; headers are the framework's
MAX_FILE_BYTES = 1 << 20


def unpack(submission, base, notes):
    """The folder to read a submission from: itself, or its zip extracted under base."""
    submission = pathlib.Path(submission)
    if submission.is_dir():
        return submission
    if zipfile.is_zipfile(submission):
        root = base / "unpacked"
        root.mkdir()
        safe_extract(submission, root, notes)
        return root
    raise GradeError(f"{submission}: neither a folder nor a zip file")


def safe_extract(archive, into, notes):
    """Extract the regular files of a zip that stay inside `into`; skip and note the others."""
    try:
        zf = zipfile.ZipFile(archive)
    except (zipfile.BadZipFile, OSError) as error:
        raise GradeError(f"{archive}: not a readable zip file ({error})") from None
    total = 0
    with zf:
        for info in zf.infolist()[:5000]:
            name = info.filename
            kind = (info.external_attr >> 16) & 0o170000
            parts = pathlib.PurePosixPath(name.replace("\\", "/")).parts
            if name.startswith(("/", "\\")) or re.match(r"^[A-Za-z]:", name) or ".." in parts:
                notes.append(f"skipped zip entry '{name}': its path leads outside the submission")
                continue
            if kind == stat.S_IFLNK:
                notes.append(f"skipped zip entry '{name}': symbolic links are not accepted")
                continue
            if info.is_dir() or not parts:
                continue
            if info.file_size > MAX_FILE_BYTES or total + info.file_size > 50 * MAX_FILE_BYTES:
                notes.append(f"skipped zip entry '{name}': too large ({info.file_size} bytes)")
                continue
            target = into.joinpath(*parts)
            target.parent.mkdir(parents=True, exist_ok=True)
            with zf.open(info) as source:
                data = source.read(MAX_FILE_BYTES + 1)
            total += len(data)
            target.write_bytes(data[:MAX_FILE_BYTES])


def exercise_names(lab):
    return {p.name for p in lab.skeleton.iterdir() if p.suffix in SOURCE_SUFFIXES}


def find_lab_folder(root, lab):
    """The submission's folder for a lab: a folder named like the lab (01_rope) that holds
    some of its exercise files (so a repository's tests/01_rope is never taken), preferring
    one inside a labs/ folder, then the one with the most exercise files, then the shallowest;
    None when there is none (flat files are matched by locate_labs)."""
    names = exercise_names(lab)
    best, best_key = None, None
    for dirpath, dirnames, _ in os.walk(root):
        depth = len(pathlib.Path(dirpath).relative_to(root).parts)
        # A symbolic link is never followed (links_outside notes those that lead out).
        dirnames[:] = sorted(d for d in dirnames if not d.startswith((".", "__MACOSX")) and depth < 6
                             and not (pathlib.Path(dirpath) / d).is_symlink())
        if lab.dir in dirnames:
            candidate = pathlib.Path(dirpath) / lab.dir
            count = sum((candidate / n).is_file() for n in names)
            if not count:
                continue
            key = (pathlib.Path(dirpath).name != "labs", -count, len(candidate.parts))
            if best_key is None or key < best_key:
                best, best_key = candidate, key
    return best


def flat_folder(root):
    """The folder a submission's flat exercise files are in: root, or the single folder a zip
    wraps them in."""
    folder = pathlib.Path(root)
    for _ in range(3):
        entries = [p for p in folder.iterdir() if not p.name.startswith((".", "__MACOSX"))]
        if any(p.is_file() and p.suffix in SOURCE_SUFFIXES for p in entries):
            return folder
        dirs = [p for p in entries if p.is_dir() and not p.is_symlink()]
        if len(dirs) != 1:
            return folder
        folder = dirs[0]
    return folder


def locate_labs(root, labs, notes, only=None):
    """{lab.dir: its folder in the submission, or None when the lab was not submitted}.
    Lab folders (labs/01_rope, 01_rope, ...) first; flat exercise files (no lab folder) go to
    the lab named by `only` (--lab), else to the one lab whose skeleton has the most of those
    file names (a tie is not guessed: the report asks for --lab)."""
    wanted = [lab for lab in labs if only is None or lab.name == only or lab.dir == only]
    notes.extend(links_outside(root, {lab.dir for lab in wanted} | {"labs"}))
    found = {lab.dir: find_lab_folder(root, lab) for lab in wanted}
    if any(found.values()):
        return found
    flat = flat_folder(root)
    present = {p.name for p in flat.iterdir() if p.is_file() and p.suffix in SOURCE_SUFFIXES}
    counts = {lab.dir: len(present & exercise_names(lab)) for lab in wanted}
    if only is not None:
        return {d: (flat if counts[d] else None) for d in found}
    top = max(counts.values(), default=0)
    winners = [d for d, c in counts.items() if c == top and c]
    if len(winners) > 1:
        notes.append(f"the submission's files ({', '.join(sorted(present))}) could belong to "
                     f"{' or '.join(winners)}: grade it with --lab NAME")
        return {d: None for d in found}
    return {d: (flat if d in winners else None) for d in found}


def links_outside(root, folder_names, depth=6):
    """A note for each symbolic link in the submission that leads outside it, and for each
    symbolic link named like a lab folder (or labs/), wherever it leads: none is followed,
    at any depth. The link's target is never printed (it may be a path of the grader's)."""
    root = pathlib.Path(root)
    inside = root.resolve()
    notes = []
    for dirpath, dirnames, filenames in os.walk(root):
        level = len(pathlib.Path(dirpath).relative_to(root).parts)
        dirnames[:] = sorted(d for d in dirnames if level < depth)
        for entry in sorted(dirnames + filenames):
            path = pathlib.Path(dirpath) / entry
            if not path.is_symlink():
                continue
            shown = path.relative_to(root).as_posix()
            try:
                leads_out = not path.resolve().is_relative_to(inside)
            except (OSError, RuntimeError):  # a loop of links
                leads_out = True
            if leads_out:
                notes.append(f"{shown}: a symbolic link that leads outside the submission: refused (submit the "
                             f"files themselves)")
            elif entry in folder_names:
                notes.append(f"{shown}: a symbolic link to a folder: refused (submit the folder itself)")
    return notes


def collect_sources(folder, notes, label, skeleton):
    """The submitted exercise files of a lab folder (the .cpp files of the released skeleton
    folder); any other file that differs from the release is noted and ignored."""
    exercise_files = {p.name for p in skeleton.iterdir() if p.suffix in SOURCE_SUFFIXES}
    files, ignored = {}, []
    for path in sorted(folder.iterdir()):
        if path.name not in exercise_files:
            released = skeleton / path.name
            if path.is_file() and not path.is_symlink() and not (
                    released.is_file() and released.read_bytes() == path.read_bytes()):
                ignored.append(path.name)
            continue
        if path.is_symlink():
            notes.append(f"{label}/{path.name}: a symbolic link, ignored (submit the file itself)")
            continue
        if not path.is_file():
            continue
        if path.stat().st_size > MAX_FILE_BYTES:
            notes.append(f"{label}/{path.name}: larger than {MAX_FILE_BYTES} bytes, ignored")
            continue
        files[path.name] = path.read_bytes()
    if ignored:
        notes.append(f"{label}: not graded (only the exercise files are compiled, against the framework's "
                     f"headers and given code): {', '.join(ignored)}")
    return files


def submissions_in(folder):
    folder = pathlib.Path(folder)
    if not folder.is_dir():
        raise GradeError(f"{folder}: not a folder of submissions")
    entries = [p for p in sorted(folder.iterdir()) if not p.name.startswith(".")
               and (p.is_dir() or (p.is_file() and p.suffix == ".zip"))]
    if not entries:
        raise GradeError(f"{folder}: holds no submission folders or .zip files")
    names = [p.stem if p.is_file() else p.name for p in entries]
    duplicate = sorted({n for n in names if names.count(n) > 1})
    if duplicate:
        raise GradeError(f"{folder}: two submissions for {', '.join(duplicate)} (a folder and a zip?)")
    return list(zip(names, entries))
