"""What grading found: each test's outcome and points (TestResult), a lab's (LabResult), a whole
submission's (Graded). Reports read these; nothing here runs anything."""
import dataclasses


@dataclasses.dataclass
class TestResult:
    exercise: dict
    test: dict
    passed: bool
    message: str
    seconds: float
    cpu_seconds: float = 0.0  # the test's processes' CPU time (sandbox.reap)

    @property
    def score(self):
        return self.test["points"] if self.passed else 0


@dataclasses.dataclass
class LabResult:
    manifest: dict
    results: list
    notes: list = dataclasses.field(default_factory=list)  # build errors, replaced files, ...
    seed: int = 0
    seconds: float = 0.0
    timing: dict = dataclasses.field(default_factory=dict)  # seconds compiling, linking, testing; links

    @property
    def score(self):
        return sum(r.score for r in self.results)

    @property
    def max_score(self):
        return sum(r.test["points"] for r in self.results)

    def exercise_score(self, ex):
        return sum(r.score for r in self.results if r.exercise is ex)

    def split(self, ex=None):
        """Public and hidden points apart, for one exercise or the lab: (public score, public
        points, hidden score, hidden points run, hidden points not run here). A student's own
        build (`check`) has no hidden tests: their points are "not run here"."""
        exercises = [ex] if ex is not None else self.manifest["exercises"]
        ran = {id(r.test): r for r in self.results}
        pub = pub_max = hid = hid_max = not_run = 0
        for e in exercises:
            for t in e["tests"]:
                r = ran.get(id(t))
                if t["visibility"] == "visible":
                    pub_max += t["points"]
                    pub += r.score if r else 0
                elif r is None:
                    not_run += t["points"]
                else:
                    hid_max += t["points"]
                    hid += r.score
        return pub, pub_max, hid, hid_max, not_run


def split_text(split):
    """'public 8/8, hidden 0/2' or 'public 8/8, hidden 2 points not run here'."""
    pub, pub_max, hid, hid_max, not_run = split
    parts = [f"public {pub:g}/{pub_max:g}"]
    if hid_max:
        parts.append(f"hidden {hid:g}/{hid_max:g}")
    if not_run:
        parts.append(f"hidden {not_run:g} point{'s' if not_run != 1 else ''} not run here, the grader runs them")
    return ", ".join(parts)


def failed_lab(manifest, message, notes=()):
    """Every test of a lab that could not be built scores 0, with the reason."""
    results = [TestResult(ex, t, False, message, 0.0) for ex in manifest["exercises"] for t in ex["tests"]]
    return LabResult(manifest, results, list(notes))


@dataclasses.dataclass
class Graded:
    name: str
    labs: list
    notes: list
    seconds: float

    @property
    def score(self):
        return sum(lab.score for lab in self.labs)

    @property
    def max_score(self):
        return sum(lab.max_score for lab in self.labs)
