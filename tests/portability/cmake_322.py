#!/usr/bin/env python3
"""The build must configure with CMake 3.22 (Ubuntu 22.04's), and no 3.22 binary is at hand.

This scans the project's CMake code, its presets and the commands the `springlab` script and
CI give to cmake/ctest for what CMake added after 3.22 (each entry names the version that
added it, from CMake's release notes), and checks that the minimum stays 3.22 and the presets
schema stays at version 3 (version 4 needs 3.23). It fails naming FILE:LINE and the feature.

usage: cmake_322.py [--root DIR]
"""
import argparse
import json
import re
import sys
from pathlib import Path

# (pattern, what, added in). Patterns run on CMake code with comments removed.
CMAKE_CODE = [
    (r"^[ \t]*block\s*\(", "block()", "3.25"),
    (r"^[ \t]*endblock\s*\(", "endblock()", "3.25"),
    (r"\breturn\s*\(\s*PROPAGATE\b", "return(PROPAGATE)", "3.25"),
    (r"\badd_subdirectory\s*\([^)]*\bSYSTEM\b", "add_subdirectory(SYSTEM)", "3.25"),
    (r"\bcmake_language\s*\(\s*GET_MESSAGE_LOG_LEVEL\b", "cmake_language(GET_MESSAGE_LOG_LEVEL)", "3.25"),
    (r"\bcmake_language\s*\(\s*EXIT\b", "cmake_language(EXIT)", "3.29"),
    (r"\bfind_package\s*\([^)]*\bGLOBAL\b", "find_package(GLOBAL)", "3.24"),
    (r"\bif\s*\([^)]*\bPATH_EQUAL\b", "if(PATH_EQUAL)", "3.24"),
    (r"\bCMAKE_COMPILE_WARNING_AS_ERROR\b|\bCOMPILE_WARNING_AS_ERROR\b", "COMPILE_WARNING_AS_ERROR", "3.24"),
    (r"\bFIND_PACKAGE_ARGS\b|\bOVERRIDE_FIND_PACKAGE\b", "FetchContent's find_package integration", "3.24"),
    (r"\bDOWNLOAD_EXTRACT_TIMESTAMP\b", "DOWNLOAD_EXTRACT_TIMESTAMP", "3.24"),
    (r"\bmessage\s*\(\s*CONFIGURE_LOG\b", "message(CONFIGURE_LOG)", "3.26"),
    (r"\bcmake_file_api\s*\(", "cmake_file_api()", "3.27"),
    (r"\bFILE_SET\b|\btarget_sources\s*\([^)]*\bFILE_SET\b", "target_sources(FILE_SET)", "3.23"),
    (r"\bEXPORT_NO_SYSTEM\b|\bset_target_properties\s*\([^)]*\bSYSTEM\s+(ON|TRUE)\b", "SYSTEM target property", "3.25"),
    (r"\bLINKER_TYPE\b", "LINKER_TYPE", "3.29"),
    (r"\$<PATH:", "$<PATH:...>", "3.24"),
    (r"\$<PATH_EQUAL:", "$<PATH_EQUAL:...>", "3.24"),
    (r"\$<LINK_LIBRARY:", "$<LINK_LIBRARY:...>", "3.24"),
    (r"\$<LINK_GROUP:", "$<LINK_GROUP:...>", "3.24"),
    (r"\$<LIST:", "$<LIST:...>", "3.27"),
    (r"\$<COMPILE_ONLY:", "$<COMPILE_ONLY:...>", "3.27"),
    (r"\$<BUILD_LOCAL_INTERFACE:", "$<BUILD_LOCAL_INTERFACE:...>", "3.26"),
    (r"\$<TARGET_IMPORT_FILE", "$<TARGET_IMPORT_FILE...>", "3.27"),
    (r"\$<STRING:", "$<STRING:...>", "3.30"),
    (r"\$<QUOTE>", "$<QUOTE>", "3.30"),
    (r"-E\s+copy_directory_if_different\b", "cmake -E copy_directory_if_different", "3.26"),
    (r"-E\s+env\s+--modify\b", "cmake -E env --modify", "3.25"),
]

# Command lines the script and CI run (bash): options cmake/ctest learned after 3.22.
COMMAND_LINES = [
    (r"\bcmake\b[^\n]*\s--fresh\b", "cmake --fresh", "3.24"),
    (r"\bcmake\b[^\n]*\s--debug-find-pkg\b", "cmake --debug-find-pkg", "3.23"),
    (r"\bctest\b[^\n]*\s--output-junit\b.*\s--test-output-size", "ctest --test-output-size-*", "3.24"),
    (r"\bcmake\b[^\n]*\s--workflow\b", "cmake --workflow", "3.25"),
]

MINIMUM = (3, 22)
PRESETS_MAX_SCHEMA = 3  # version 4 needs 3.23, 5 needs 3.24, 6 needs 3.25


def cmake_files(root: Path):
    """Our CMake code: every CMakeLists.txt and *.cmake outside build folders and third_party/."""
    for path in sorted(root.rglob("*")):
        rel = path.relative_to(root)
        if rel.parts[0].startswith(("build", ".git", "out")) or rel.parts[0] == "third_party":
            continue
        if path.is_file() and (path.name == "CMakeLists.txt" or path.suffix == ".cmake"):
            yield path


def strip_comment(line: str) -> str:
    """The line without its `#` comment (a `#` inside quotes is kept)."""
    quoted = False
    for i, ch in enumerate(line):
        if ch == '"':
            quoted = not quoted
        elif ch == "#" and not quoted:
            return line[:i]
    return line


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", default=str(Path(__file__).resolve().parents[2]))
    root = Path(parser.parse_args().root)
    problems = []

    checked = 0
    for path in cmake_files(root):
        checked += 1
        # Joined per command: a command's arguments may span lines.
        lines = [strip_comment(line) for line in path.read_text().splitlines()]
        text = "\n".join(lines)
        for pattern, what, version in CMAKE_CODE:
            for match in re.finditer(pattern, text, re.MULTILINE):
                line = text.count("\n", 0, match.start()) + 1
                problems.append(f"{path.relative_to(root)}:{line}: {what} needs CMake {version}")

    top = (root / "CMakeLists.txt").read_text()
    found = re.search(r"cmake_minimum_required\s*\(\s*VERSION\s+(\d+)\.(\d+)", top)
    if not found or (int(found[1]), int(found[2])) != MINIMUM:
        problems.append(f"CMakeLists.txt: cmake_minimum_required must say VERSION {MINIMUM[0]}.{MINIMUM[1]}")

    for name in ("CMakePresets.json", "CMakeUserPresets.json"):
        presets_path = root / name
        if not presets_path.exists():
            continue
        try:
            presets = json.loads(presets_path.read_text())
        except json.JSONDecodeError as error:
            problems.append(f"{name}: not valid JSON ({error})")
            continue
        if presets.get("version", 0) > PRESETS_MAX_SCHEMA:
            problems.append(f"{name}: field 'version' is {presets['version']}; CMake 3.22 reads up to "
                            f"{PRESETS_MAX_SCHEMA}")
        if "include" in presets:
            problems.append(f"{name}: field 'include' needs presets version 4 (CMake 3.23)")
        needed = presets.get("cmakeMinimumRequired", {})
        if (needed.get("major", 0), needed.get("minor", 0)) > MINIMUM:
            problems.append(f"{name}: field 'cmakeMinimumRequired' asks for more than 3.22")
        for kind in ("configurePresets", "buildPresets", "testPresets"):
            for preset in presets.get(kind, []):
                if "${fileDir}" in json.dumps(preset):
                    problems.append(f"{name}: preset '{preset.get('name')}' uses ${{fileDir}} (CMake 3.23)")
        if "packagePresets" in presets or "workflowPresets" in presets:
            problems.append(f"{name}: package/workflow presets need CMake 3.25")

    for name in ("springlab", ".ci/run"):
        script = root / name
        if not script.exists():
            continue
        for number, line in enumerate(script.read_text().splitlines(), 1):
            for pattern, what, version in COMMAND_LINES:
                if re.search(pattern, line):
                    problems.append(f"{name}:{number}: {what} needs CMake {version}")

    if checked == 0:
        problems.append(f"no CMake files found under {root}")
    for problem in problems:
        print(problem, file=sys.stderr)
    if problems:
        print(f"cmake 3.22: {len(problems)} feature(s) newer than CMake 3.22", file=sys.stderr)
        return 1
    print(f"cmake 3.22: {checked} CMake files, the presets and the scripts use nothing newer than 3.22")
    return 0


if __name__ == "__main__":
    sys.exit(main())
