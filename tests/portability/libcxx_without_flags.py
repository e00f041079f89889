#!/usr/bin/env python3
"""A clang + libc++ build needs no flag: the C++ libraries built for libstdc++ are replaced.

A build with clang and libc++ (-stdlib=libc++, macOS's toolchain family) cannot link the
installed C++ libraries built with libstdc++ (Debian's libgtest-dev, tinyobjloader, Google
Benchmark): CMake links a small program against each, and where that fails builds GoogleTest
from its sources (/usr/src/googletest), takes the vendored tinyobjloader and leaves the
benchmarks out, saying so. This configures the tree with COMPILER and -stdlib=libc++ and no
other flag, and checks that

- the configure says it builds GoogleTest from source, and why (the installed one does not
  link), in its output and in the summary line; the summary names the vendored tinyobjloader
  and no benchmarks;
- a GoogleTest program of this build links and runs with libc++: the build's own
  `gtest_main` with a two-line test against it (a configure and one library, well under a
  minute of CPU);
- the default build (BUILD, the C++ compiler CMake picked) still uses the installed GoogleTest
  when it links there.

usage: gtest_stdlib.py --root SOURCE_TREE --build DEFAULT_BUILD --work DIR --compiler CLANG++
"""
import argparse
import re
import shutil
import subprocess
import sys
from pathlib import Path


def run(cmd, **kw):
    done = subprocess.run(cmd, capture_output=True, text=True, **kw)
    return done.returncode, done.stdout + done.stderr


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--root", required=True)
    ap.add_argument("--build", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--compiler", required=True)
    args = ap.parse_args()
    root, work = Path(args.root), Path(args.work)
    failures = []

    # The default build: its summary names where GoogleTest came from.
    summary = (Path(args.build) / "springlab-summary.txt").read_text()
    if "GoogleTest installed" not in summary and "GoogleTest built from" not in summary:
        failures.append(f"the default build's summary does not say where GoogleTest comes from: {summary.strip()}")

    # clang + libc++, no GoogleTest flag: only the libraries a GoogleTest program needs.
    shutil.rmtree(work, ignore_errors=True)
    code, out = run(["cmake", "-S", str(root), "-B", str(work), "-DCMAKE_BUILD_TYPE=Release",
                     f"-DCMAKE_CXX_COMPILER={args.compiler}", "-DCMAKE_CXX_FLAGS=-stdlib=libc++",
                     "-DSPRINGLAB_BUILD_VIEWER=OFF"])
    if code != 0:
        print(out[-4000:])
        print(f"FAIL: the configure with {args.compiler} -stdlib=libc++ failed (exit {code})")
        return 1
    said = re.search(r"GoogleTest: the installed one does not link with .*: building it from (\S+)", out)
    if not said:
        failures.append("the configure did not say that it builds GoogleTest from source because the "
                        "installed one does not link with libc++")
    summary = (work / "springlab-summary.txt").read_text()
    if "GoogleTest built from" not in summary:
        failures.append("the summary line does not say that GoogleTest is built from source")
    if "tinyobjloader vendored" not in summary:
        failures.append(f"the libc++ build does not take the vendored tinyobjloader: {summary.strip()}")
    if "benchmarks on" in summary:
        failures.append(f"the libc++ build builds benchmarks against a libstdc++ Google Benchmark: {summary.strip()}")

    # A GoogleTest program against this build's gtest_main links and runs with libc++.
    code, out = run(["cmake", "--build", str(work), "--target", "gtest_main", "-j", "2"])
    if code != 0:
        print(out[-4000:])
        failures.append(f"building GoogleTest from source with {args.compiler} failed (exit {code})")
    else:
        libs = sorted(work.glob("lib/libgtest*.a")) or sorted(work.glob("**/libgtest*.a"))
        by_name = {p.name: p for p in libs}
        program = work / "links_with_libcxx"
        source = work / "links_with_libcxx.cpp"
        source.write_text('#include <gtest/gtest.h>\n#include <string>\n'
                          'TEST(Links, WithLibcxx) { EXPECT_EQ(std::string("a") + "b", "ab"); }\n')
        include = next(Path(p) for p in ("/usr/src/googletest/googletest/include", "/usr/include") if Path(p, "gtest").is_dir())
        code, out = run([args.compiler, "-std=c++20", "-stdlib=libc++", f"-I{include}", str(source),
                         str(by_name.get("libgtest_main.a", "")), str(by_name.get("libgtest.a", "")),
                         "-pthread", "-o", str(program)])
        if code != 0:
            failures.append(f"a test program does not link against the GoogleTest built here:\n{out[-2000:]}")
        else:
            code, out = run([str(program)])
            if code != 0 or "1 test from 1 test suite ran" not in out:
                failures.append(f"the test program linked with libc++ did not pass (exit {code}):\n{out[-2000:]}")
    for failure in failures:
        print("FAIL: " + failure)
    if not failures:
        print(f"{args.compiler} -stdlib=libc++ without a flag: GoogleTest built from {said.group(1)} (a test "
              f"program links and passes), the vendored tinyobjloader, no benchmarks")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
