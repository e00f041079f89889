"""Where the sandbox users find what they must read or run: a folder of this grader's own in the
system's temporary folder (mode 711: they may enter known paths, never list), holding copies of
the programs it runs sandboxed (the skeleton's and the reference's grading programs) and of the
framework's public headers the compiler reads. The instructor's checkout may live anywhere, a
home folder of mode 700 included: nothing in it is ever opened as a sandbox user. Removed when
the grader ends."""
import atexit
import os
import pathlib
import secrets
import shutil
import tempfile
import threading

# Files of an include folder that are not headers: never staged (a compiler would not read
# them through #include, and an include folder is no place for them).
NOT_HEADERS = (".cpp", ".cc", ".cxx", ".c", ".o", ".a", ".so", ".json", ".py", ".txt", ".md")


class Staging:
    """This grader's folder of copies the sandbox may reach."""

    def __init__(self):
        remove_stale_stages()
        self.root = pathlib.Path(tempfile.mkdtemp(prefix=PREFIX))
        os.chmod(self.root, 0o711)
        (self.root / "pid").write_text(str(os.getpid()))
        self.lock = threading.Lock()
        self.programs = {}
        self.header_folders = {}
        atexit.register(shutil.rmtree, self.root, True)

    def _private(self):
        """A fresh folder under the stage with a name nobody can guess (the stage is not listable)."""
        folder = self.root / secrets.token_hex(12)
        folder.mkdir(mode=0o711)
        os.chmod(folder, 0o711)
        return folder

    def program(self, path):
        """A copy of the program at `path` that any user may run (0755), made once per version."""
        path = pathlib.Path(path)
        stat = path.stat()
        key = (str(path), stat.st_mtime_ns, stat.st_size)
        with self.lock:
            if key not in self.programs:
                copy = self._private() / path.name
                shutil.copyfile(path, copy)
                os.chmod(copy, 0o755)
                self.programs[key] = copy
            return self.programs[key]

    def headers(self, folder):
        """A copy of the headers of an include folder (every file but sources, objects and
        notes), readable by all: the compiler's sandbox binds it. Made once per grader."""
        folder = pathlib.Path(folder)
        with self.lock:
            if folder not in self.header_folders:
                copy = self._private() / "include"
                for source in sorted(folder.rglob("*")):
                    relative = source.relative_to(folder)
                    if any(part.startswith(".") for part in relative.parts) or source.is_symlink():
                        continue
                    target = copy / relative
                    if source.is_dir():
                        continue
                    if source.is_file() and source.suffix not in NOT_HEADERS:
                        target.parent.mkdir(parents=True, exist_ok=True)
                        shutil.copyfile(source, target)
                        os.chmod(target, 0o644)
                copy.mkdir(exist_ok=True)
                for sub in [copy, *(p for p in copy.rglob("*") if p.is_dir())]:
                    os.chmod(sub, 0o755)
                self.header_folders[folder] = copy
            return self.header_folders[folder]


PREFIX = "springlab-stage-"


def remove_stale_stages(folder=None):
    """Remove the stages of graders that ended without removing theirs (killed): each names
    its grader's process in its pid file."""
    for stale in pathlib.Path(folder or tempfile.gettempdir()).glob(f"{PREFIX}*"):
        try:
            if stale.stat().st_uid != os.geteuid():
                continue  # another user's grader
            pid = int((stale / "pid").read_text())
            os.kill(pid, 0)  # still running: its stage stays
        except ProcessLookupError:
            shutil.rmtree(stale, ignore_errors=True)
        except (OSError, ValueError, KeyError):
            continue


_stage = []
_stage_lock = threading.Lock()


def stage():
    """The one Staging of this grader process."""
    with _stage_lock:
        if not _stage:
            _stage.append(Staging())
        return _stage[0]
