"""A lab's manifest (tests/<dir>/exercises.json), the one place points are declared: loading
and checking it, and checking that the lab's handout states the same points."""
import json
import pathlib

VISIBILITIES = ("visible", "hidden", "after_due_date", "after_published")


class ManifestError(Exception):
    pass


def load_manifest(path):
    """Read and check tests/<lab>/exercises.json; errors name the file and the field."""
    path = pathlib.Path(path)
    try:
        data = json.loads(path.read_text())
    except OSError as error:
        raise ManifestError(f"{path}: cannot read: {error.strerror}") from None
    except ValueError as error:
        raise ManifestError(f"{path}: not valid JSON: {error}") from None

    def need(obj, key, kind, where):
        if not isinstance(obj, dict) or key not in obj:
            raise ManifestError(f"{path}: {where}{key}: missing")
        if not isinstance(obj[key], kind) or isinstance(obj[key], bool):
            raise ManifestError(f"{path}: {where}{key}: must be a {kind.__name__ if isinstance(kind, type) else 'number'}")
        return obj[key]

    for key in ("lab", "title", "handout"):
        need(data, key, str, "")
    names = set()
    for i, ex in enumerate(need(data, "exercises", list, "")):
        where = f"exercises[{i}]."
        need(ex, "id", str, where)
        need(ex, "title", str, where)
        for j, t in enumerate(need(ex, "tests", list, where)):
            twhere = f"{where}tests[{j}]."
            name = need(t, "name", str, twhere)
            points = need(t, "points", (int, float), twhere)
            if points < 0:
                raise ManifestError(f"{path}: {twhere}points: must be >= 0, got {points}")
            if need(t, "visibility", str, twhere) not in VISIBILITIES:
                raise ManifestError(f"{path}: {twhere}visibility: must be one of {', '.join(VISIBILITIES)}, "
                                    f"got {t['visibility']!r}")
            if name in names:
                raise ManifestError(f"{path}: {twhere}name: {name} is declared twice")
            names.add(name)
        ex["points"] = sum(t["points"] for t in ex["tests"])
    data["points"] = sum(ex["points"] for ex in data["exercises"])
    return data


def check_handout(manifest, handout_path):
    text = pathlib.Path(handout_path).read_text()
    problems = []
    for ex in manifest["exercises"]:
        heading = f"### Exercise {ex['id']}: {ex['title']} ({ex['points']:g} points)"
        if heading not in text.splitlines():
            problems.append(f"{handout_path}: missing the heading line '{heading}' (points must agree with the manifest)")
    if f"{manifest['points']:g} points" not in text:
        problems.append(f"{handout_path}: never states the lab's total of {manifest['points']:g} points")
    return problems
