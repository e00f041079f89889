"""The link of a lab's grading program as CMake writes it down (grading/<name>_link.json,
tests/CMakeLists.txt file(GENERATE)), read the same way by the instructor's grader (build_cache.py)
and a student's `check` (student_build.py), which both link a lab's tests with exercise objects of
their choosing. Shipped in the student release."""
import dataclasses
import json
import pathlib
import shlex
import shutil

from .errors import GradeError


# ---- the link CMake writes -------------------------------------------------------------------
@dataclasses.dataclass
class LinkFile:
    """grading/<name>_link.json: the link of the lab's grading program, less the student's
    archive, which goes first among the libraries."""
    path: pathlib.Path
    compiler: str
    flags: list            # before the objects
    test_objects: list     # the public and hidden tests (no main)
    given_objects: list    # the lab's given code, archived with the student's exercise objects
    oracle: str            # the reference "oracle" library; "" when the tree has none
    libraries: list        # after the student's archive, in link order
    skeleton_program: str  # the grading program CMake linked with the released skeleton
    # The reference's exercise objects, one per file (springlab_<name>_solution_objects), and
    # the skeleton's (springlab_<name>_student_objects): a test of exercise X links the
    # student's file of X with the reference's other files; a file that does not compile is
    # the skeleton's. Empty in a build without them (then one program for the whole lab).
    solution_objects: list = dataclasses.field(default_factory=list)
    skeleton_objects: list = dataclasses.field(default_factory=list)
    reference_program: str = ""  # <name>_grading_reference: its run sets the time budget
    main_objects: list = dataclasses.field(default_factory=list)  # the whole-lab programs' main
    # The call layer (tests/support/call_trace.hpp): the worker's trace support, its main and
    # each exercise file's record and forward objects; the judge program of each exercise file;
    # the exercise functions of each file (functions.json). Empty in a tree without them.
    worker_objects: list = dataclasses.field(default_factory=list)
    layer_objects: list = dataclasses.field(default_factory=list)
    judges: dict = dataclasses.field(default_factory=dict)
    functions: str = ""
    worker_seccomp: str = ""  # the program that writes the workers' seccomp filter; "" without libseccomp

    def argv(self, student_archive, output):
        """The link of a whole-lab program (grading_main.cpp) with the student's archive."""
        return [self.compiler, *self.flags, *self.test_objects, *self.main_objects, "-o", str(output),
                str(student_archive), *self.libraries]

    def worker_argv(self, file, student_archive, output):
        """The link of the worker of one exercise file: the tests, the trace support, the worker's
        main and the file's record and forward objects, then the archive and the libraries."""
        stem = file[:-len(".cpp")]
        layer = [o for o in self.layer_objects
                 if pathlib.Path(o).name in ("worker_main.cpp.o", f"{stem}.record.cpp.o", f"{stem}.forward.cpp.o")]
        # gold links these programs about twice as fast as ld.bfd, where it is installed.
        faster = ["-fuse-ld=gold"] if shutil.which("ld.gold") else []
        return [self.compiler, *faster, *self.flags, *self.test_objects, *self.worker_objects, *layer, "-o",
                str(output), str(student_archive), *self.libraries]

    def exercise_functions(self):
        """{exercise file: [function names]} from the call layer's functions.json."""
        if not self.functions:
            return {}
        try:
            return json.loads(pathlib.Path(self.functions).read_text())
        except (OSError, ValueError) as error:
            raise GradeError(f"{self.functions}: cannot read the call layer's functions ({error}); build the "
                             f"grading build again") from None


def expand_link_option(option):
    """One entry of a CMake LINK_OPTIONS list as arguments: `SHELL:a b` is two arguments,
    `LINKER:a,b` goes to the linker (-Wl,a,b), anything else is itself."""
    if option.startswith("LINKER:"):
        rest = option[len("LINKER:"):]
        parts = shlex.split(rest[len("SHELL:"):]) if rest.startswith("SHELL:") else rest.split(",")
        return ["-Wl," + ",".join(parts)]
    if option.startswith("SHELL:"):
        return shlex.split(option[len("SHELL:"):])
    return [option]


def read_link_file(path):
    """Read and check a CMake-written grading/<name>_link.json; errors name the file."""
    path = pathlib.Path(path)
    again = "configure the build again (cmake -S <tree> -B <build>)"
    try:
        data = json.loads(path.read_text())
    except FileNotFoundError:
        raise GradeError(f"{path}: missing; is this a build of this tree? ({again})") from None
    except OSError as error:
        raise GradeError(f"{path}: cannot read: {error.strerror}") from None
    except ValueError as error:
        raise GradeError(f"{path}: not valid JSON ({error}); {again}") from None
    if not isinstance(data, dict):
        raise GradeError(f"{path}: not a JSON object; {again}")
    fields = {}
    for field in dataclasses.fields(LinkFile)[1:]:
        value = data.get(field.name)
        if value is None and field.default is not dataclasses.MISSING:
            continue
        if value is None and field.default_factory is not dataclasses.MISSING:
            continue
        if field.type is dict:
            if not isinstance(value, dict) or not all(isinstance(v, str) for v in value.values()):
                raise GradeError(f"{path}: {field.name}: not an object of strings; {again}")
        elif field.type is list:
            if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
                raise GradeError(f"{path}: {field.name}: missing, or not a list of strings; {again}")
            # An item CMake evaluated to nothing is an empty string.
            value = [arg for v in value if v for arg in expand_link_option(v)]
        elif not isinstance(value, str):
            raise GradeError(f"{path}: {field.name}: missing, or not a string; {again}")
        fields[field.name] = value
    for needed in ("compiler", "test_objects", "skeleton_program"):
        if not fields[needed]:
            raise GradeError(f"{path}: {needed}: empty; {again}")
    return LinkFile(path, **fields)
