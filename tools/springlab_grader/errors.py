"""The grader's error for bad input or a broken instructor tree: a clear message, exit code 2."""


class GradeError(Exception):
    """Bad input or a broken instructor tree: a clear message and exit code 2."""
