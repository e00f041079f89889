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

    @property
    def score(self):
        return sum(r.score for r in self.results)

    @property
    def max_score(self):
        return sum(r.test["points"] for r in self.results)

    def exercise_score(self, ex):
        return sum(r.score for r in self.results if r.exercise is ex)


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
