"""What a student reads first when an exercise file does not compile, the same in `grade` (the
report's note, lab_grader.py) and `check` (student_build.py): the first error, placed in the
student's file (an error deep inside Eigen is placed at the student's line that instantiated it),
the source line, and a one-line hint for the common cases; then where the compiler's full text is.
Shipped in the student release (it reads text only)."""
import dataclasses
import pathlib
import re

# A diagnostic's location at the start of a line: FILE:LINE:COLUMN: (GCC and Clang).
_LOCATION = re.compile(r"^(?P<path>[^\s:][^:]*):(?P<line>\d+):(?:(?P<column>\d+):)?\s?(?P<rest>.*)$")
_ERROR = re.compile(r"^(?:fatal )?error:\s*(?P<message>.*)$")

# Common first errors and what to do about them: (pattern on the error's message, hint). The first
# match wins; HINT_ELSE when none does.
HINTS = [
    (re.compile(r"INVALID_(VECTOR_VECTOR|MATRIX)_PRODUCT|Eigen::Product<[^>]*Matrix<double, 3, 1>, "
                r"Eigen::Matrix<double, 3, 1>"),
     "a * b of two Vec3 is no product Eigen defines: use a.dot(b) (a number), a.cross(b) (a Vec3) or "
     "a.cwiseProduct(b) (component by component)"),
    (re.compile(r"YOU_MIXED_MATRICES_OF_DIFFERENT_SIZES|YOU_MIXED_DIFFERENT_NUMERIC_TYPES"),
     "the two sides of this operation differ in size or scalar type (a Vec3 with a Vec2, a vector with a matrix, "
     "float with double): check each operand's type"),
    (re.compile(r"THIS_METHOD_IS_ONLY_FOR_VECTORS_OF_A_SPECIFIC_SIZE"),
     "cross() is defined for two Vec3 only: check that both operands are 3-vectors"),
    (re.compile(r"has no member named .length|has no member named .len\b|has no member named .magnitude"),
     "an Eigen vector's length is v.norm() (its square v.squaredNorm(), its direction v.normalized())"),
    (re.compile(r"has no member named"),
     "this type has no such member: check the spelling and the type (the lab's types are declared in its "
     "exercises.hpp; Eigen's vectors have norm(), dot(), cross(), normalized())"),
    (re.compile(r"was not declared in this scope|use of undeclared identifier|does not name a type|"
                r"unknown type name|is not a member of"),
     "a name the compiler does not know here: check its spelling, that it is declared above this line, and its "
     "namespace (the lab's types and functions are in springlab::<lab>, see exercises.hpp; the standard "
     "library's in std::)"),
    (re.compile(r"no return statement in function returning non-void|control reaches end of non-void|"
                r"non-void function does not return a value"),
     "a path through this function ends without `return`: every path of a function that returns a value must "
     "return one"),
    (re.compile(r"expected .;.|expected .,. or .;.|expected ';'"),
     "a statement is not finished: a `;` is missing at the end of the line before (or a bracket is not closed)"),
    (re.compile(r"expected .\}. at end of input|expected '}'"),
     "a `{` is never closed: count the braces of the function"),
    (re.compile(r"read-only|discards qualifiers|assignment of read-only|cannot assign to variable .* with "
                r"const-qualified type|no match for .operator=. \(operand types are .const"),
     "this writes into something const, such as an input parameter: write into the output parameter or a local "
     "copy"),
    (re.compile(r"invalid use of void expression"),
     "this function returns nothing (void): it writes its result into one of its parameters instead"),
    (re.compile(r"no matching function for call|no matching member function|too (few|many) arguments"),
     "no function of this name takes these arguments: compare their number and types with the declaration "
     "(the lab's exercises.hpp)"),
    (re.compile(r"redefinition of|conflicting declaration|redeclared as different kind"),
     "this name is defined twice: keep one definition (a helper function needs a name of its own)"),
    (re.compile(r"cannot convert|invalid conversion|no viable conversion|could not convert"),
     "the value has another type than the variable, parameter or return value it goes to: check both types"),
    (re.compile(r"no match for .operator|invalid operands"),
     "no such operator for these operand types: check the types on each side"),
]
HINT_ELSE = "read this first error only: later errors often follow from it"


def hint(message):
    """The one-line hint for an error message."""
    return next((text for pattern, text in HINTS if pattern.search(message)), HINT_ELSE)


@dataclasses.dataclass
class FirstError:
    path: str     # the student's file, as the compiler's text names it
    line: int
    column: int
    message: str  # the error's own words (the first error, wherever it is)
    source: str   # the student's line, as the compiler quoted it ("" when it did not)
    inside: str   # where the error itself is when that is not the student's file ("" when it is)

    def text(self):
        where = f"{self.path}:{self.line}" + (f":{self.column}" if self.column else "")
        inside = f" (inside {self.inside}, from this line)" if self.inside else ""
        return f"{where}: error: {self.message}{inside}"


def first_error(output, is_student):
    """The first error of a compiler's text, placed in the student's file: when the error itself
    is in another file (a header such as Eigen's), at the student's line that led there (GCC's
    "required from here" before it, Clang's "requested here" after it). `is_student(path)` says
    whether a path is the student's. None when the text holds no error."""
    lines = output.splitlines()
    last_student = None  # the student's latest location before the error
    for i, text in enumerate(lines):
        where = _LOCATION.match(text)
        if not where:
            continue
        error = _ERROR.match(where["rest"])
        if is_student(where["path"]) and not error:
            last_student = (i, where)
        if not error:
            continue
        if is_student(where["path"]):
            return _placed(lines, i, where, error["message"], "")
        found = last_student
        if found is None:
            # Clang: the student's line comes after the error, as a note.
            for j in range(i + 1, len(lines)):
                after = _LOCATION.match(lines[j])
                if after and _ERROR.match(after["rest"]):
                    break
                if after and is_student(after["path"]):
                    found = (j, after)
                    break
        if found is None:
            return FirstError(where["path"], int(where["line"]), int(where["column"] or 0), error["message"],
                              _quoted(lines, i), "")
        return _placed(lines, found[0], found[1], error["message"], where["path"])
    return None


def files_with_errors(output):
    """The files a compiler's text (a whole build's) reports errors in, in order, without the
    system's headers: [(path, the first error's line)]."""
    found = {}
    for text in output.splitlines():
        where = _LOCATION.match(text)
        if where and _ERROR.match(where["rest"]) and not where["path"].startswith("/usr/"):
            found.setdefault(where["path"], text)
    return list(found.items())


def _placed(lines, i, where, message, inside):
    # A context line ("required from here") quotes no code: the next line is another file's.
    quoted = _quoted(lines, i, 1 if inside else 2)
    return FirstError(where["path"], int(where["line"]), int(where["column"] or 0), message, quoted,
                      pathlib.PurePath(inside).name if inside else "")


def _quoted(lines, i, within=2):
    """The source line GCC or Clang quotes under a diagnostic ("   12 |   code"), or ""."""
    for text in lines[i + 1:i + 1 + within]:
        quoted = re.match(r"^\s*\d+\s*\|(.*)$", text)
        if quoted:
            return quoted[1].rstrip()
    return ""


def summary(output, is_student, root=None):
    """The lines a student reads first ([] when the text holds no error): the first error placed
    in their file, its line of code (read from the file under `root` when the compiler did not
    quote it) and a hint."""
    found = first_error(output, is_student)
    if found is None:
        return []
    if not found.source.strip() and root is not None:
        try:
            found.source = (pathlib.Path(root) / found.path).read_text(errors="replace").splitlines()[found.line - 1]
        except (OSError, IndexError):
            pass
    lines = [found.text()]
    if found.source.strip():
        lines.append(f"    {found.source.strip()}")
    return lines + [f"hint: {hint(found.message)}"]


def first_errors(output, lines=25):
    """The compiler's first error lines, paths shortened to the file names students know."""
    text = re.sub(r"(^|\s)(?:\S*/)?src/", r"\1", output)
    keep = [line for line in text.splitlines() if line.strip()]
    first = next((i for i, line in enumerate(keep) if "error" in line), 0)
    return "\n".join(keep[max(0, first - 2):first + lines])


def not_compiling_note(name, exercises, summary_lines, details):
    """The note of an exercise file that does not compile, the same in `grade` and `check`:
    which exercises it costs, the summary (summary()), then `details` (the compiler's first
    errors, or where its full text is)."""
    lost = ", ".join(exercises) or "none"
    return "\n".join([f"{name} does not compile, so it is graded as the released skeleton's {name}: exercise {lost} "
                      f"scores 0, the other exercises are graded.", *summary_lines, *([details] if details else [])])


# The message of each test of such a file (it is not run).
NOT_COMPILING = "{name} does not compile (see the note): graded as the released skeleton's file"


def not_defined_note(name, missing):
    """The note of an exercise file that compiles but lacks a function as the lab's header
    declares it, the same in `grade` and `check`; its tests fail with NOT_DEFINED."""
    return (f"{name} does not define {', '.join(missing)} as the lab's exercises.hpp declares "
            f"{'it' if len(missing) == 1 else 'them'} (a changed signature?), so its exercises score 0")


NOT_DEFINED = "{name}: see the note"
