#!/usr/bin/env python3
"""`./springlab` finds libraries with CMake; only setup, run and test call a package manager.

Every package manager (apt-get, apt, dpkg-query, dnf, pacman, brew, vcpkg) and sudo is
replaced on PATH by a spy that writes down its command line and fails, and the platform is
faked (an os-release file; `uname` for macOS and Windows). Then:

- the build, configured with one library missing (CLI11, hidden from CMake), calls no package
  manager, names the library and prints the install command of each platform: apt, dnf,
  pacman, Homebrew, vcpkg;
- `setup` elsewhere than apt prints the install line and installs nothing;
- `setup` as a user (not root) on apt: without a terminal it stops and prints the sudo
  command; with one it asks first, installs nothing on "n" and runs sudo apt-get on "y";
- `run` and `test`, the README's two commands, offer the install themselves: as root without
  a terminal (CI) they run apt-get install (every missing package of `setup`'s list) and say
  so; as a user without a terminal they print the sudo line and run nothing; on a terminal
  they ask and run sudo apt-get on "y"; without cmake on PATH, on Fedora as root, they run
  `dnf install -y cmake` (cmake is in the package table).

usage: package_managers.py --root SOURCE_TREE --work DIR
"""
import argparse
import os
import shutil
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

SPIED = ["apt-get", "apt", "dpkg-query", "dnf", "pacman", "brew", "vcpkg", "sudo"]

# os-release of each Linux family, and uname -s of the others.
PLATFORMS = {
    "apt": ("ID=ubuntu\nID_LIKE=debian\n", None, "sudo apt-get install libcli11-dev"),
    "dnf": ("ID=fedora\n", None, "sudo dnf install cli11-devel"),
    "pacman": ("ID=arch\n", None, "sudo pacman -S --needed cli11"),
    "brew": ("", "Darwin", "brew install cli11"),
    "vcpkg": ("", "MINGW64_NT-10.0", "vcpkg install cli11"),
}


def make_spies(folder: Path, log: Path, uname: str | None, uid: str | None) -> None:
    """Spies for every package manager (they log and fail; sudo logs and succeeds, so that a
    confirmed `setup` shows what it would run; so does `apt-get update`), and the faked uname
    and id."""
    folder.mkdir(parents=True, exist_ok=True)
    for name in SPIED:
        code = 0 if name == "sudo" else 1
        spy = folder / name
        # (apt-get's `update` succeeds, so that the install it comes before is reached.)
        update = 'if [ "$1" = update ]; then exit 0; fi\n' if name == "apt-get" else ""
        spy.write_text(f'#!/bin/sh\necho "{name} $*" >> "{log}"\n{update}exit {code}\n')
        spy.chmod(0o755)
    if uname:
        (folder / "uname").write_text(f"#!/bin/sh\necho {uname}\n")
        (folder / "uname").chmod(0o755)
    if uid:
        (folder / "id").write_text(f'#!/bin/sh\nif [ "$1" = -u ]; then echo {uid}; else exec /usr/bin/id "$@"; fi\n')
        (folder / "id").chmod(0o755)


def environment(spies: Path, release: Path, build: Path) -> dict:
    env = dict(os.environ)
    env["PATH"] = f"{spies}:{env['PATH']}"
    env["SPRINGLAB_OS_RELEASE"] = str(release)
    env["SPRINGLAB_BUILD_DIR"] = str(build)
    env["SPRINGLAB_NO_AUTHOR_WARNINGS"] = "1"
    env.pop("SPRINGLAB_WARNINGS_AS_ERRORS", None)
    return env


def case_folder(work: Path, name: str, uname=None, uid=None, release_text="ID=debian\n"):
    folder = work / name
    shutil.rmtree(folder, ignore_errors=True)
    log = folder / "calls.log"
    make_spies(folder / "bin", log, uname, uid)
    release = folder / "os-release"
    release.write_text(release_text)
    return folder, log, release


def calls(log: Path) -> str:
    return log.read_text() if log.exists() else ""


def missing_library(root: Path, work: Path, platform: str) -> list[str]:
    """A configure without CLI11 on PLATFORM: the message, and no package manager called."""
    release_text, uname, expected = PLATFORMS[platform]
    folder, log, release = case_folder(work, f"missing-{platform}", uname=uname, release_text=release_text)
    run = subprocess.run([str(root / "springlab"), "build", "-DCMAKE_DISABLE_FIND_PACKAGE_CLI11=ON"],
                         env=environment(folder / "bin", release, folder / "build"),
                         capture_output=True, text=True, timeout=300)
    problems = []
    if run.returncode == 0:
        problems.append(f"{platform}: the build went on without CLI11")
    if "cli11" not in run.stderr or expected not in run.stderr:
        problems.append(f"{platform}: expected the library named and `{expected}`; got:\n{run.stderr}")
    if calls(log):
        problems.append(f"{platform}: the build called a package manager:\n{calls(log)}")
    return problems


def setup_elsewhere(root: Path, work: Path) -> list[str]:
    folder, log, release = case_folder(work, "setup-fedora", release_text=PLATFORMS["dnf"][0])
    run = subprocess.run([str(root / "springlab"), "setup"], stdin=subprocess.DEVNULL,
                         env=environment(folder / "bin", release, folder / "build"),
                         capture_output=True, text=True, timeout=60)
    problems = []
    if "sudo dnf install" not in run.stderr:
        problems.append(f"setup on Fedora: no dnf line in:\n{run.stderr}")
    if calls(log):
        problems.append(f"setup on Fedora called:\n{calls(log)}")
    return problems


def setup_as_user(root: Path, work: Path, answer: str | None) -> list[str]:
    """setup as uid 1000 on apt, every package missing (dpkg-query's spy lists none)."""
    label = f"setup-user-{answer or 'no-terminal'}"
    folder, log, release = case_folder(work, label, uid="1000")
    env = environment(folder / "bin", release, folder / "build")
    if answer is None:
        run = subprocess.run([str(root / "springlab"), "setup"], stdin=subprocess.DEVNULL, env=env,
                             capture_output=True, text=True, timeout=60)
        stderr = run.stderr
    else:
        # A terminal on stdin, so that setup may ask; the answer typed into it.
        master, slave = os.openpty()
        process = subprocess.Popen([str(root / "springlab"), "setup"], stdin=slave, env=env,
                                   stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        os.close(slave)
        os.write(master, f"{answer}\n".encode())
        _, stderr = process.communicate(timeout=60)
        os.close(master)
    sudo_calls = [line for line in calls(log).splitlines() if line.startswith("sudo ")]
    problems = []
    if answer is None:
        if sudo_calls or "sudo apt-get install" not in stderr:
            problems.append(f"{label}: expected the sudo command printed and nothing run; "
                            f"ran {sudo_calls}; said:\n{stderr}")
    elif answer == "n":
        if sudo_calls or "[y/N]" not in stderr:
            problems.append(f"{label}: expected a [y/N] question and nothing run; ran {sudo_calls}; said:\n{stderr}")
    elif not any(line.startswith("sudo apt-get install") for line in sudo_calls):
        problems.append(f"{label}: 'y' did not run sudo apt-get install; ran {sudo_calls}; said:\n{stderr}")
    return problems


def run_with_answer(command: list[str], env: dict, answer: str | None) -> str:
    """COMMAND's stderr: stdin not a terminal (answer None), or a terminal ANSWER is typed into."""
    if answer is None:
        return subprocess.run(command, stdin=subprocess.DEVNULL, env=env, capture_output=True,
                              text=True, timeout=300).stderr
    master, slave = os.openpty()
    process = subprocess.Popen(command, stdin=slave, env=env, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True)
    os.close(slave)
    os.write(master, f"{answer}\n".encode())
    _, stderr = process.communicate(timeout=300)
    os.close(master)
    return stderr


def offered_install(root: Path, work: Path, command: str, uid: str, answer: str | None) -> list[str]:
    """COMMAND (run or test) on apt with CLI11 hidden from CMake (a first `build` leaves the
    option in the cache), as UID, answering ANSWER on a terminal (None: no terminal)."""
    label = f"offer-{command}-uid{uid}-{answer or 'no-terminal'}"
    folder, log, release = case_folder(work, label, uid=uid)
    env = environment(folder / "bin", release, folder / "build")
    subprocess.run([str(root / "springlab"), "build", "-DCMAKE_DISABLE_FIND_PACKAGE_CLI11=ON"],
                   stdin=subprocess.DEVNULL, env=env, capture_output=True, text=True, timeout=300)
    before = calls(log)
    args = [str(root / "springlab"), command] + (["rope"] if command == "run" else [])
    stderr = run_with_answer(args, env, answer)
    made = [line for line in calls(log)[len(before):].splitlines() if not line.startswith("dpkg-query")]
    installs = [line for line in made if " install " in f" {line} "]
    problems = []
    if uid == "0" and answer is None:
        if not any(line.startswith("apt-get install") and "libcli11-dev" in line for line in installs) \
                or "installing" not in stderr:
            problems.append(f"{label}: expected `apt-get install` with libcli11-dev, said so; ran {made}; said:\n{stderr}")
    elif answer is None:
        if made or "sudo apt-get install libcli11-dev" not in stderr:
            problems.append(f"{label}: expected the sudo line printed and nothing run; ran {made}; said:\n{stderr}")
    elif not any(line.startswith("sudo apt-get install") and "libcli11-dev" in line for line in installs) \
            or "[y/N]" not in stderr:
        problems.append(f"{label}: expected a question, then sudo apt-get install; ran {made}; said:\n{stderr}")
    return problems


def cmake_missing(root: Path, work: Path) -> list[str]:
    """`run rope` as root on Fedora without cmake on PATH (every other program of PATH is
    linked into one folder, cmake's left out): it installs cmake with dnf."""
    folder, log, release = case_folder(work, "offer-cmake-dnf", uid="0", release_text=PLATFORMS["dnf"][0])
    tools = folder / "tools"
    tools.mkdir()
    for directory in os.environ["PATH"].split(os.pathsep):
        for program in Path(directory).glob("*") if Path(directory).is_dir() else []:
            target = tools / program.name
            if program.name not in ("cmake", "ctest", "cpack") and not target.exists() and not target.is_symlink():
                target.symlink_to(program.resolve() if program.is_symlink() else program)
    env = environment(folder / "bin", release, folder / "build")
    env["PATH"] = f"{folder / 'bin'}{os.pathsep}{tools}"
    stderr = run_with_answer([str(root / "springlab"), "run", "rope"], env, None)
    if not any(line.startswith("dnf install -y") and "cmake" in line.split() for line in calls(log).splitlines()):
        return [f"cmake missing on Fedora: expected `dnf install -y cmake`; ran {calls(log)!r}; said:\n{stderr}"]
    return []


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", required=True)
    parser.add_argument("--work", required=True)
    args = parser.parse_args()
    root, work = Path(args.root).resolve(), Path(args.work).resolve()
    work.mkdir(parents=True, exist_ok=True)

    problems = []
    with ThreadPoolExecutor(max_workers=len(PLATFORMS)) as pool:
        for found in pool.map(lambda p: missing_library(root, work, p), PLATFORMS):
            problems += found
    problems += setup_elsewhere(root, work)
    for answer in (None, "n", "y"):
        problems += setup_as_user(root, work, answer)
    offers = [("test", "0", None), ("test", "1000", None), ("run", "1000", "y")]
    with ThreadPoolExecutor(max_workers=len(offers)) as pool:
        for found in pool.map(lambda case: offered_install(root, work, *case), offers):
            problems += found
    problems += cmake_missing(root, work)

    for problem in problems:
        print(problem, file=sys.stderr)
    if problems:
        return 1
    print(f"package managers: the build called none on {len(PLATFORMS)} platforms and named the "
          "install command of each; setup, run and test asked before sudo; as root in CI run "
          "and test installed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
