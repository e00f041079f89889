#!/usr/bin/env python3
"""Sabotage submissions: the grader must survive its students.

Each submission is the reference solutions/ with ONE exercise body of Lab 1 (the target
below) replaced by something hostile: a crash, a hang, a forged result, a call of the
reference, ... Everything else is honest. The class is graded with `grade-all`, and each
submission must get exactly the points of its honest parts: test by test, the outcome of the
"control" submission, which is solutions/ with the target file taken from the skeleton (the
exercise not done). A few have other expectations (an empty submission scores 0; a zip that
tries to escape keeps its honest files). The class is graded together (`grade-all --lab
rope`, two at a time), so an attack on the grader's caches or on other students' processes
shows as another student's changed outcome. The classes the grader's call check stops before
they run (BEHIND_THE_CALL_CHECK) are graded a second time with that check off, so that the
sandbox behind it is tested too.

    tests/grading/sabotage.py --cache build --work build/tests/sabotage      (run by ctest)
"""
import argparse
import csv
import json
import pathlib
import re
import shutil
import os
import stat
import subprocess
import sys
import uuid
import zipfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
from springlab_grader.labs import discover_labs  # noqa: E402

# The exercise every sabotage replaces: explicit Euler's step of Lab 1, called by its own
# tests and by the hidden whole-rope trajectory test, so a broken one fails the same tests
# whatever way it breaks.
TARGET_LAB, TARGET_EXERCISE = "01_rope", "1.4"
SIGNATURE = "PhasePoint explicitEulerStep(const PhasePoint& s, const Vec3& a, double dt)"

# name: (includes, code before the namespace, body, expectation)
SABOTAGES = {
    "segfault": ("<cstdint>", "", """
  volatile std::uintptr_t address = 16;
  *reinterpret_cast<volatile int*>(address) = 1;
  return {s.pos, s.vel};""", "control"),
    "abort": ("<cstdlib>", "", """
  std::abort();""", "control"),
    "uncaught_exception": ("<stdexcept>", """
namespace {
void fail() noexcept { throw std::runtime_error("escapes a noexcept function"); }
}  // namespace
""", """
  fail();
  return {s.pos, s.vel};""", "control"),
    "infinite_loop": ("", "", """
  for (volatile unsigned long spin = 0;; spin = spin + 1) {
  }""", "control"),
    "huge_allocation": ("<cstddef>\n#include <vector>", "", """
  std::vector<char> block(std::size_t{20} << 30, 1);  // 20 GiB
  return {s.pos + s.vel * dt * block[12345], s.vel + a * dt};""", "control"),
    "deep_recursion": ("", """
namespace {
int descend(long depth) {
  volatile char frame[4096];
  frame[depth % 4096] = 1;
  return depth < 0 ? 0 : descend(depth + 1) + frame[0];
}
}  // namespace
""", """
  return {s.pos + s.vel * dt * descend(1), s.vel + a * dt};""", "control"),
    "exit_zero": ("<cstdlib>", "", """
  std::exit(0);""", "control"),
    "fake_gtest_output": ("<cstdio>\n#include <cstdlib>", "", """
  std::printf("[       OK ] ExplicitEuler.UpdatesFromTheOldState (0 ms)\\n[----------] 1 test\\n"
              "[==========] 1 test from 1 test suite ran. (0 ms total)\\n[  PASSED  ] 1 test.\\n"
              "[  SKIPPED ] 0 tests, listed below:\\n");
  std::fflush(stdout);
  std::_Exit(0);""", "control"),
    "forged_channel": ("<cstdio>\n#include <cstdlib>\n#include <string>\n#include <unistd.h>", "", """
  // Guess the grader's channel: write a passing report to every descriptor, then leave.
  const std::string forged =
      "{\\"nonce\\":\\"0000\\",\\"tests\\":[{\\"name\\":\\"ExplicitEuler.UpdatesFromTheOldState\\","
      "\\"status\\":\\"passed\\",\\"failures\\":[]}]}\\n";
  for (int fd = 0; fd < 64; ++fd) {
    if (::write(fd, forged.data(), forged.size()) < 0) continue;
  }
  std::_Exit(0);""", "control"),
    "writes_result_files": ("<filesystem>\n#include <fstream>\n#include <stdexcept>\n#include <sstream>\n#include <string>\n#include <vector>"
                            "\n#include <unistd.h>", "", """
  // Forge full marks wherever results might be, delete what can be deleted, then give no
  // answer (the forged files would be the only way to score).
  namespace fs = std::filesystem;
  std::vector<fs::path> places = {".", "..", "../..", "/autograder/results"};
  for (const char* proc : {"/proc/self/cmdline", "/proc/self/environ"}) {
    std::ifstream in(proc);
    std::string arg;
    while (std::getline(in, arg, '\\0')) places.push_back(fs::path(arg).parent_path());
  }
  std::ifstream parent("/proc/" + std::to_string(::getppid()) + "/cmdline");
  std::string arg;
  while (std::getline(parent, arg, '\\0')) places.push_back(arg);
  for (const fs::path& place : places) {
    std::error_code ec;
    for (const char* name : {"results.json", "report.md", "junit.xml", "gradebook.csv"}) {
      fs::remove(place / name, ec);
      std::ofstream(place / name) << "{\\"score\\": 1000, \\"max_score\\": 50, \\"tests\\": []}";
    }
  }
  throw std::logic_error("no answer");""", "control"),
    "nan_and_inf": ("<limits>", "", """
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  return {Vec3(nan, nan, nan), Vec3(inf, -inf, inf)};""", "control"),
    "hard_coded_example": ("", "", """
  // Right only for one printed example, the start state unchanged otherwise.
  if (s.pos == Vec3(1, 0, 0) && s.vel == Vec3(0, 1, 0) && a == Vec3(0, -9.81, 0) && dt == 0.1) {
    return {Vec3(1, 0.1, 0), Vec3(0, 0.019, 0)};
  }
  return {s.pos, s.vel};""", "control"),
    "calls_reference": ("", """
namespace springlab::rope_reference {
struct PhasePoint {
  Vec3 pos;
  Vec3 vel;
};
PhasePoint explicitEulerStep(const PhasePoint& s, const Vec3& a, double dt);
}  // namespace springlab::rope_reference
""", """
  const auto answer = springlab::rope_reference::explicitEulerStep({s.pos, s.vel}, a, dt);
  return {answer.pos, answer.vel};""", "control"),
    # ---- attacks on the verdict and on other students (issue 13): each scores the control ----
    # A static initialiser runs before main(): it forges passing reports on every descriptor
    # and at exit, and turns exit codes into 0; the answers stay wrong.
    "code_before_main": ("<cstdlib>\n#include <string>\n#include <unistd.h>", """
namespace {
void forge() {
  const std::string forged = "{\\"tests\\":[{\\"name\\":\\"ExplicitEuler.UpdatesFromTheOldState\\","
                             "\\"status\\":\\"passed\\",\\"failures\\":[]}],\\"trace_calls\\":0}\\n";
  for (int fd = 0; fd < 256; ++fd) {
    if (::write(fd, forged.data(), forged.size()) < 0) continue;
  }
}
const bool kForged = [] {
  forge();
  std::atexit(forge);
  return true;
}();
}  // namespace
""", """
  return {s.pos * (kForged ? 1.0 : 2.0), s.vel};""", "control"),
    # Reads its own program: finds the reference "oracle"'s explicitEulerStep in the symbol
    # table of /proc/self/exe and calls it (the worker holds no reference of this exercise).
    "reads_own_memory": ("<cstdint>\n#include <cstring>\n#include <elf.h>\n#include <fstream>\n#include <iterator>\n#include <string>\n#include <vector>", """
extern "C" void springlab_sabotage_probe() {}
namespace {
struct Twin {
  springlab::Vec3 pos, vel;
};
using Step = Twin (*)(const Twin&, const springlab::Vec3&, double);
Step findOracle() {
  std::ifstream in("/proc/self/exe", std::ios::binary);
  const std::vector<char> elf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (elf.size() < sizeof(Elf64_Ehdr)) return nullptr;
  Elf64_Ehdr header;
  std::memcpy(&header, elf.data(), sizeof header);
  std::uintptr_t probe = 0, oracle = 0;
  for (int i = 0; i < header.e_shnum; ++i) {
    Elf64_Shdr section;
    std::memcpy(&section, elf.data() + header.e_shoff + i * sizeof section, sizeof section);
    if (section.sh_type != SHT_SYMTAB) continue;
    Elf64_Shdr strings;
    std::memcpy(&strings, elf.data() + header.e_shoff + section.sh_link * sizeof strings, sizeof strings);
    for (std::size_t k = 0; k < section.sh_size / sizeof(Elf64_Sym); ++k) {
      Elf64_Sym symbol;
      std::memcpy(&symbol, elf.data() + section.sh_offset + k * sizeof symbol, sizeof symbol);
      const std::string name = elf.data() + strings.sh_offset + symbol.st_name;
      if (name == "springlab_sabotage_probe") probe = symbol.st_value;
      if (name.find("rope_reference17explicitEulerStep") != std::string::npos) oracle = symbol.st_value;
    }
  }
  if (probe == 0 || oracle == 0) return nullptr;
  const std::uintptr_t base = reinterpret_cast<std::uintptr_t>(&springlab_sabotage_probe) - probe;
  return reinterpret_cast<Step>(base + oracle);
}
}  // namespace
""", """
  static const Step oracle = findOracle();
  static int depth = 0;
  if (oracle != nullptr && depth == 0) {
    ++depth;
    const Twin answer = oracle({s.pos, s.vel}, a, dt);
    --depth;
    return {answer.pos, answer.vel};
  }
  return {s.pos, s.vel};""", "control"),
    # Reads the grading tree: with the reference's file in reach it answers right (as a
    # student who copied it would), else wrong.
    "reads_grading_tree": ("<fstream>", """
namespace {
bool treeVisible() { return std::ifstream("@SOLUTION@").good(); }
}  // namespace
""", """
  if (treeVisible()) return {s.pos + s.vel * dt, s.vel + a * dt};
  return {s.pos, s.vel};""", "control"),
    # Leaves a process behind: a detached grandchild (its own session) that lives on.
    "leaves_process_behind": ("<csignal>\n#include <sys/prctl.h>\n#include <unistd.h>", "", """
  static bool forked = false;
  if (!forked) {
    forked = true;
    if (::fork() == 0) {
      ::setsid();
      if (::fork() == 0) {
        ::prctl(PR_SET_NAME, "springlab-left", 0, 0, 0);
        for (int i = 0; i < 600; ++i) ::sleep(1);
      }
      ::_exit(0);
    }
  }
  return {s.pos, s.vel};""", "control"),
    # Writes the grader's shared caches: every object and file it can reach under the cache
    # build is overwritten with garbage (the other students must not notice).
    "writes_shared_cache": ("<filesystem>\n#include <fstream>", "", """
  static bool done = false;
  if (!done) {
    done = true;
    std::error_code ec;
    for (const char* folder : {"@CACHE@/grader-objects", "@CACHE@/tests", "@CACHE@/grading", "@CACHE@/CMakeFiles"}) {
      for (auto it = std::filesystem::recursive_directory_iterator(folder, ec);
           it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
        if (it->is_regular_file(ec)) std::ofstream(it->path(), std::ios::trunc) << "poisoned";
      }
    }
  }
  return {s.pos, s.vel};""", "control"),
    # Detects grading (its environment: the call-trace channel and the seed; its command line:
    # /sandbox/test or a filter; the grader's folders)
    # and then tries everything it can; undetected it is wrong too. It must gain nothing.
    "detects_grading": ("<csignal>\n#include <cstdlib>\n#include <filesystem>\n#include <fstream>\n#include <string>\n#include <unistd.h>", """
namespace {
bool graded() {
  std::ifstream cmdline("/proc/self/cmdline");
  const std::string args((std::istreambuf_iterator<char>(cmdline)), std::istreambuf_iterator<char>());
  return std::getenv("SPRINGLAB_CALL_TRACE_FD") != nullptr || std::getenv("SPRINGLAB_SEED") != nullptr ||
         args.find("gtest_filter") != std::string::npos || args.find("/sandbox/") != std::string::npos || std::filesystem::exists("/autograder") ||
         std::filesystem::exists("@ROOT@");
}
}  // namespace
""", """
  static const bool grading = graded();
  if (grading) {
    ::kill(-1, 9);  // every process it may signal
    return {s.pos * 3.0, s.vel};
  }
  return {s.pos, s.vel};""", "control"),
    # Overrides GoogleTest: a strong CmpHelperLT<double, double> that always succeeds turns
    # every failed EXPECT_LT/ASSERT_LT on doubles into a pass in its own process.
    "overrides_gtest": ("<gtest/gtest.h>", """
namespace testing::internal {
template <>
AssertionResult CmpHelperLT<double, double>(const char*, const char*, const double&, const double&) {
  return AssertionSuccess();
}
}  // namespace testing::internal
""", """
  return {s.pos + s.vel, s.vel * 2.0};""", "control"),
    # Sleeps just under the per-test limit in every test program, then answers wrong: the
    # budget, not the class's patience, bounds it.
    "sleeps_near_limit": ("<chrono>\n#include <thread>", "", """
  static bool slept = false;
  if (!slept) {
    slept = true;
    std::this_thread::sleep_for(std::chrono::milliseconds(@SLEEP_MS@));
  }
  return {s.pos, s.vel};""", "control"),
    # ---- attacks on the compiler (issue 28): it runs sealed, sees nothing of the grader ----
    # .incbin of the reference's compiled object: were it readable, a loader would run it
    # (here: the right answer whenever the bytes arrived).
    "incbin_grader_object": ("", """
asm(".pushsection .rodata\\n.global springlab_stolen\\nspringlab_stolen:\\n.incbin \\"@OBJECT@\\"\\n"
    ".global springlab_stolen_end\\nspringlab_stolen_end:\\n.popsection");
extern "C" const char springlab_stolen[], springlab_stolen_end[];
""", """
  if (springlab_stolen_end - springlab_stolen > 0) return {s.pos + s.vel * dt, s.vel + a * dt};
  return {s.pos, s.vel};""", "control"),
    # .incbin of the reference's source, of a hidden test and of a classmate's file, printed
    # into the visible tests' messages: none of their text may reach any output.
    **{f"incbin_{what}": ("<stdexcept>\n#include <string>", f"""
asm(".pushsection .rodata\\n.global springlab_stolen\\nspringlab_stolen:\\n.incbin \\"{path}\\"\\n"
    ".global springlab_stolen_end\\nspringlab_stolen_end:\\n.popsection");
extern "C" const char springlab_stolen[], springlab_stolen_end[];
""", """
  throw std::runtime_error(std::string(springlab_stolen, springlab_stolen_end));""", "control")
       for what, path in (("reference_source", "@SOLUTION@"), ("hidden_test", "@HIDDEN@"), ("classmate", "@CLASSMATE@"))},
    # The compiler reading a device without end: its memory limit stops it.
    "includes_dev_zero": ('"/dev/zero"', "", """
  return {s.pos, s.vel};""", "control"),
    # Probing the grading tree at compile time: the right answer only where the reference is seen.
    "has_include_probe": ("", "", """
#if __has_include("@SOLUTION@") || __has_include("@HIDDEN@")
  return {s.pos + s.vel * dt, s.vel + a * dt};
#else
  return {s.pos, s.vel};
#endif""", "control"),
    # A 200 MB object (the assembler's .fill): the compiler's output limit stops it; nothing
    # of it reaches the object cache.
    "fill_200mb": ("", """
asm(".pushsection .rodata\\n.fill 200000000, 1, 0\\n.popsection");
""", """
  return {s.pos + s.vel * dt, s.vel + a * dt};""", "control"),
    # Weak definitions: of a framework function (keeps the library's out of the link) and of
    # another exercise's function (the reference's is linked beside it).
    "weak_framework_symbol": ("<springlab/diagnostics.hpp>", """
namespace springlab {
__attribute__((weak)) double springGershgorinBound(const Simulation&) { return 0.0; }
}  // namespace springlab
""", """
  return {s.pos + s.vel * dt, s.vel + a * dt};""", "control"),
    "weak_other_exercise": ("", """
namespace springlab::rope {
__attribute__((weak)) Vec3 springDamperForce(const Vec3&, const Vec3&, const Vec3&, const Vec3&, double, double,
                                             double) {
  return Vec3::Zero();
}
}  // namespace springlab::rope
""", """
  return {s.pos + s.vel * dt, s.vel + a * dt};""", "control"),
    "does_not_compile": ("", "", """
  return {s.pos + s.vel * dt, s.vel + a * dt}  // a missing semicolon
  undeclared_variable += 1;""", "control"),
}


# Text only the grader holds: the reference's comment in the target exercise, a line of a hidden
# test, a classmate's marker. None may appear in any output of any student.
MARKERS = {"reference": "Both updates use the state at the start of the step.",
           "hidden": "name the quantity and the inputs, never the reference's answer",
           "classmate": f"springlab-classmate-marker-{uuid.uuid4().hex}"}


def hidden_test_file():
    files = sorted((ROOT / "tests" / TARGET_LAB / "hidden").glob("*.cpp"))
    hits = [f for f in files if MARKERS["hidden"] in f.read_text()]
    if not hits or MARKERS["reference"] not in (ROOT / "solutions" / TARGET_LAB / target_file()).read_text():
        raise SystemExit("sabotage.py: a marker is gone from the reference or the hidden tests; update MARKERS")
    return hits[0]


# Forged call records (tests/support/call_trace.hpp) that buildRope's worker writes to the
# grader's channel itself, then leaves: a spring joining a mass far past the rope's end, a
# record cut short, a count of 2^40 masses. The judge must fail exercise 1.7's tests with a
# sentence and never crash: they score the control of build_rope.cpp (the skeleton's file).
FORGERIES = {
    "index": """
  putCount(frame, rope.masses.size());
  for (const Mass& m : rope.masses) putValue(frame, m.m), putValue(frame, static_cast<unsigned char>(m.pinned));
  putCount(frame, rope.springs.size());
  for (std::size_t i = 0; i < rope.springs.size(); ++i) {
    const Spring& sp = rope.springs[i];
    putValue(frame, sp.mass1), putValue(frame, i + 1 == rope.springs.size() ? 1000000000 : sp.mass2);
    putValue(frame, sp.springConstant), putValue(frame, sp.springLength), putValue(frame, sp.frictionConstant);
    putValue(frame, static_cast<int>(sp.kind));
  }
  for (const auto* v : {&rope.pos, &rope.vel}) {
    putCount(frame, v->size());
    for (const Vec3& x : *v) putValue(frame, x.x()), putValue(frame, x.y()), putValue(frame, x.z());
  }""",
    "truncated": """
  putCount(frame, rope.masses.size());
  putValue(frame, 1.0);""",
    "huge_count": """
  putCount(frame, std::size_t{1} << 40);""",
}


def make_forged_frames(folder, solutions_copy, expect, cache_path):
    record = cache_path / "tests" / "call_layer" / "rope" / "build_rope.record.cpp"
    found = re.search(r"buildRope[^{]*\{\s*return trace::recorded\((\d+)u", record.read_text()) if record.exists() else None
    if not found:
        raise SystemExit(f"sabotage.py: {record}: no buildRope record to read its function id from")
    reference = (ROOT / "solutions" / TARGET_LAB / "build_rope.cpp").read_text()
    end = "  return rope;\n  // END EXERCISE 1.7"
    if end not in reference:
        raise SystemExit("sabotage.py: build_rope.cpp no longer ends exercise 1.7 with `return rope;`")
    expect["_control_build_rope"] = "control_build_rope"
    shutil.copy(ROOT / "labs" / TARGET_LAB / "build_rope.cpp", solutions_copy("_control_build_rope") / "build_rope.cpp")
    helpers = """#include <cstdint>
#include <cstdlib>
#include <string>
#include <unistd.h>

namespace {
template <class T>
void putValue(std::string& out, const T& v) { out.append(reinterpret_cast<const char*>(&v), sizeof v); }
void putCount(std::string& out, std::size_t n) { putValue(out, static_cast<std::uint64_t>(n)); }
}  // namespace
"""
    for kind, body in FORGERIES.items():
        text = reference.replace("#include <springlab/rope/exercises.hpp>\n",
                                 "#include <springlab/rope/exercises.hpp>\n" + helpers, 1)
        text = text.replace(end, f"""  std::string frame;
  putValue(frame, std::uint32_t{{{found[1]}}});
  putValue(frame, std::uint8_t{{0}});
{body.strip(chr(10))}
  if (::write(3, frame.data(), frame.size()) < 0) std::_Exit(1);
  std::_Exit(0);
  return rope;
  // END EXERCISE 1.7""")
        (solutions_copy(f"forged_frame_{kind}") / "build_rope.cpp").write_text(text)
        expect[f"forged_frame_{kind}"] = "control_build_rope"


def patch(text, includes, prelude, body):
    """The reference file with the target exercise's body replaced."""
    block = re.compile(rf"(// BEGIN EXERCISE {re.escape(TARGET_EXERCISE)}\n).*?(\s*// END EXERCISE)", re.S)
    if not block.search(text) or SIGNATURE not in text:
        raise SystemExit(f"sabotage.py: the target {SIGNATURE} with exercise {TARGET_EXERCISE} is gone; update TARGET")
    text = block.sub(lambda m: m.group(1) + body.strip("\n") + m.group(2), text)
    head = "".join(f"#include {inc}\n" for inc in includes.split("\n#include ") if inc)
    text = text.replace('#include <springlab/rope/exercises.hpp>\n', '#include <springlab/rope/exercises.hpp>\n' + head, 1)
    return text.replace("namespace springlab::rope {", prelude.strip("\n") + "\n\nnamespace springlab::rope {", 1) \
        if prelude else text


def target_file():
    for path in sorted((ROOT / "solutions" / TARGET_LAB).glob("*.cpp")):
        if f"// BEGIN EXERCISE {TARGET_EXERCISE}" in path.read_text():
            return path.name
    raise SystemExit(f"sabotage.py: no file of solutions/{TARGET_LAB} marks exercise {TARGET_EXERCISE}")


def make(folder, escape_marks, cache=None, timeout=3.0):
    """Write every submission into folder; return {name: expectation}."""
    folder = pathlib.Path(folder)
    shutil.rmtree(folder, ignore_errors=True)
    folder.mkdir(parents=True)
    name = target_file()
    expect = {}

    def solutions_copy(student):
        target = folder / student / "labs"
        shutil.copytree(ROOT / "solutions", target)
        return target / TARGET_LAB

    expect["_reference"] = "reference"
    solutions_copy("_reference")
    expect["_skeleton"] = "all_zero"
    shutil.copytree(ROOT / "labs", folder / "_skeleton" / "labs")
    expect["_control"] = "control"
    shutil.copy(ROOT / "labs" / TARGET_LAB / name, solutions_copy("_control") / name)

    original = (ROOT / "solutions" / TARGET_LAB / name).read_text()
    cache_path = pathlib.Path(cache or ROOT / "build").resolve()
    # The classmate: the reference with a marker only the grader could leak.
    expect["_classmate"] = "reference"
    classmate = solutions_copy("_classmate") / name
    classmate.write_text(classmate.read_text() + f"// {MARKERS['classmate']}\n")
    objects = sorted(cache_path.glob(f"**/springlab_*_solution_objects.dir/**/{TARGET_LAB}/{name}.o"))
    places = {"@SOLUTION@": str(ROOT / "solutions" / TARGET_LAB / name), "@ROOT@": str(ROOT),
              "@CACHE@": str(cache_path), "@SLEEP_MS@": str(max(100, int(timeout * 1000) - 300)),
              "@HIDDEN@": str(hidden_test_file()), "@CLASSMATE@": str(classmate.resolve()),
              "@OBJECT@": str(objects[0] if objects else cache_path / "missing.o")}
    for sabotage, (includes, prelude, body, expectation) in SABOTAGES.items():
        text = patch(original, includes, prelude, body)
        for mark, value in places.items():
            text = text.replace(mark, value)
        (solutions_copy(sabotage) / name).write_text(text)
        expect[sabotage] = expectation
    # Whole-file sabotages: the reference source included by path; the file missing;
    # nothing at all; a zip whose entries try to leave it.
    (solutions_copy("includes_reference") / name).write_text(f'#include "{ROOT / "solutions" / TARGET_LAB / name}"\n')
    expect["includes_reference"] = "control"
    (solutions_copy("missing_file") / name).unlink()
    expect["missing_file"] = "control"
    # The lab's header edited (a field added to a type the given code shares, a declaration
    # changed): only exercise files are compiled, against the framework's header, so the
    # edit changes nothing (no ODR violation) and the report says the file was not graded.
    released = (ROOT / "labs" / TARGET_LAB / "exercises.hpp").read_text()
    edited = released.replace("  Vec3 vel;  // m/s\n};",
                              "  Vec3 vel;  // m/s\n  double extra[64];  // a field the given code does not know\n};", 1)
    if edited == released:
        raise SystemExit("sabotage.py: PhasePoint is gone from the released exercises.hpp; update edits_header")
    (solutions_copy("edits_header") / "exercises.hpp").write_text(edited)
    expect["edits_header"] = "reference"
    (folder / "empty").mkdir()
    expect["empty"] = "all_zero"
    # A lab folder that is a symbolic link to the reference (absolute, relative, and labs/
    # itself deeper in a repository): never followed, so the lab is not submitted.
    for kind in ("absolute", "relative", "deep"):
        student = folder / f"symlinked_lab_{kind}"
        labs_dir = student / "repo" / "deeper" if kind == "deep" else student / "labs"
        labs_dir.parent.mkdir(parents=True)
        if kind == "deep":
            labs_dir.mkdir()
            (labs_dir / "labs").symlink_to(ROOT / "solutions")
        else:
            labs_dir.mkdir()
            target = ROOT / "solutions" / TARGET_LAB
            (labs_dir / TARGET_LAB).symlink_to(os.path.relpath(target, labs_dir) if kind == "relative" else target)
        expect[student.name] = "all_zero"
    make_forged_frames(folder, solutions_copy, expect, cache_path)
    with zipfile.ZipFile(folder / "zip_escape.zip", "w") as zf:
        for path in sorted((ROOT / "solutions").rglob("*")):
            if path.is_file():
                zf.write(path, f"my-labs/{path.relative_to(ROOT / 'solutions')}")
        for mark in escape_marks:
            zf.writestr(mark if mark.startswith("/") else f"../../{mark}", "escaped\n")
        link = zipfile.ZipInfo(f"my-labs/{TARGET_LAB}/{name}.link.hpp")
        link.external_attr = (stat.S_IFLNK | 0o777) << 16
        zf.writestr(link, "/etc/passwd")
    expect["zip_escape"] = "reference"
    return expect


def check(out, expect, labs):
    """Each student's results against its expectation; returns a list of problems."""
    problems = []
    results = {}
    for student in expect:
        folder = out / student
        for name in ("report.md", "results.json", "junit.xml"):
            if not (folder / name).is_file():
                problems.append(f"{student}: no {name}")
        try:
            results[student] = json.loads((folder / "results.json").read_text())
        except (OSError, ValueError) as error:
            problems.append(f"{student}: results.json unreadable: {error}")
    if problems:
        return problems
    declared = [(lab.dir, t["name"]) for lab in labs if lab.dir == TARGET_LAB
                for ex in lab.manifest["exercises"] for t in ex["tests"]]

    def outcomes(student):
        tests = results[student]["tests"]
        # A test's first tag is its lab's id; the suite names labs by folder.
        folder_of = {lab.manifest["lab"]: lab.dir for lab in labs}
        return {(folder_of.get(t["tags"][0], t["tags"][0]), t["name"].split(" ", 1)[1]): t["status"] for t in tests}

    for student, data in results.items():
        problems += [f"{student}: {p}" for p in schema_problems(data)]
        got = outcomes(student)
        if sorted(got) != sorted(declared):
            problems.append(f"{student}: results.json does not list every test once")
            continue
        kind = expect[student]
        for key in declared:
            lab, _ = key
            if kind == "all_zero":
                want = "failed"
            elif kind == "lab_zero" and lab == TARGET_LAB:
                want = "failed"
            elif kind.startswith("control") and lab == TARGET_LAB:
                want = outcomes("_" + kind)[key]
            else:
                want = "passed" if kind != "all_zero" else "failed"
            if got[key] != want:
                problems.append(f"{student} ({kind}): {key[1]} is {got[key]}, expected {want}")
        score = sum(t["score"] for t in data["tests"])
        if abs(score - data["score"]) > 1e-9:
            problems.append(f"{student}: score {data['score']} is not the sum of its tests ({score})")
    control = results["_control"]
    if not 0 < control["score"] < control["max_score"]:
        problems.append(f"_control scores {control['score']}: the target exercise should cost some, not all, points")
    for student, data in results.items():
        for t in data["tests"]:
            if t["visibility"] != "visible" and re.search(r"Which is:|evaluates to|, actual: ", t["output"]):
                problems.append(f"{student}: hidden test {t['name']} prints compared values: {t['output'][:200]}")
    return problems


def schema_problems(data):
    """results.json against the Gradescope fields this project promises."""
    problems = []
    top = {"score": (int, float), "max_score": (int, float), "execution_time": (int, float), "tests": list}
    for key, kind in top.items():
        if not isinstance(data.get(key), kind):
            problems.append(f"results.json: {key} missing or not {kind}")
    fields = {"name": str, "number": str, "score": (int, float), "max_score": (int, float), "output": str,
              "visibility": str, "tags": list, "status": str}
    for i, t in enumerate(data.get("tests", [])):
        for key, kind in fields.items():
            if not isinstance(t.get(key), kind):
                problems.append(f"results.json: tests[{i}].{key} missing or not {kind}")
        if t.get("visibility") not in ("visible", "hidden", "after_due_date", "after_published"):
            problems.append(f"results.json: tests[{i}].visibility is {t.get('visibility')!r}")
        if t.get("status") not in ("passed", "failed"):
            problems.append(f"results.json: tests[{i}].status is {t.get('status')!r}")
    return problems


# The classes whose code calls what exercise code never needs (integrity.FORBIDDEN_CALLS).
BEHIND_THE_CALL_CHECK = {"reads_own_memory", "reads_grading_tree", "leaves_process_behind", "writes_shared_cache",
                         "detects_grading"}


def grade_all(folder, out, args, *extra):
    """`grade-all` of one class folder into out; False (and why, printed) if it failed."""
    shutil.rmtree(out, ignore_errors=True)
    run = subprocess.run([sys.executable, str(ROOT / "tools" / "submission.py"), "grade-all", str(folder),
                          "--out", str(out), "--cache", args.cache, "--no-build", "--seed", "12345",
                          "--jobs", str(args.jobs), "--timeout", str(args.timeout), "--lab", TARGET_LAB, *extra],
                         text=True, capture_output=True)
    print(run.stdout + run.stderr)
    if run.returncode != 0:
        print(f"grade-all {folder.name} failed with exit code {run.returncode}", file=sys.stderr)
    return run.returncode == 0


def compile_time_problems(out, expect, cache):
    """What the attacks on the compiler and the judge must leave: no marker and no path of the
    grader in any output, each limit named, the judge never crashed."""
    problems = []
    for student in expect:
        text = "".join((out / student / n).read_text() for n in ("report.md", "results.json", "junit.xml"))
        for what, marker in MARKERS.items():
            if marker in text:
                problems.append(f"{student}: the {what}'s text reaches its outputs")
        for path in (str(ROOT), str(cache)):
            if path in text:
                problems.append(f"{student}: its outputs name the grader's path {path}")
        if re.search(r"judge crashed|judge stopped|judge ended without a report", text):
            problems.append(f"{student}: the judge crashed on what the student's code sent")

    def report(student):
        return " ".join((out / student / "report.md").read_text().split())

    wanted = {"includes_dev_zero": "memory limit", "fill_200mb": "output limit",
              "weak_framework_symbol": "redefines symbols", "weak_other_exercise": "defines functions of another",
              "incbin_grader_object": "does not compile", "symlinked_lab_absolute": "symbolic link",
              "symlinked_lab_relative": "symbolic link", "symlinked_lab_deep": "symbolic link",
              "forged_frame_index": "a spring's second mass is 1000000000",
              "forged_frame_huge_count": "a vector of 1099511627776 elements",
              "forged_frame_truncated": "stopped while giving back"}
    for student, phrase in wanted.items():
        if phrase not in report(student):
            problems.append(f"{student}: the report does not say '{phrase}'")
    oversized = [p.name for p in (cache / "grader-objects").glob("*.o") if p.stat().st_size > 32 << 20]
    if oversized:
        problems.append(f"fill_200mb: the object cache keeps objects above its limit: {oversized}")
    return problems


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cache", required=True, help="a build of this tree with the grading programs built")
    ap.add_argument("--work", required=True, help="scratch folder for the submissions and their reports")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=3.0, help="seconds per test (they take milliseconds)")
    args = ap.parse_args()
    work = pathlib.Path(args.work).resolve()
    marks = [f"springlab-escaped-{uuid.uuid4().hex}.txt", f"/tmp/springlab-escaped-{uuid.uuid4().hex}.txt"]
    expect = make(work / "class", marks, args.cache, args.timeout)
    out = work / "grades"
    if not grade_all(work / "class", out, args):
        return 1
    labs = discover_labs()
    problems = check(out, expect, labs)
    # The grader's first line against hostile code: a file that calls the test framework,
    # files, the environment or other processes is graded as the skeleton's before it runs.
    caught = sorted(s for s in expect if "which reach" in (out / s / "report.md").read_text())
    for student in sorted(BEHIND_THE_CALL_CHECK - set(caught)):
        problems.append(f"{student}: its forbidden calls were not caught before it ran")
    # The sandbox behind it: the same classes run (--no-call-check), and must still gain nothing.
    behind = work / "class-behind"
    shutil.rmtree(behind, ignore_errors=True)
    behind.mkdir()
    for student in ["_control", *caught]:
        shutil.copytree(work / "class" / student, behind / student, symlinks=True)
    if not grade_all(behind, work / "grades-behind", args, "--no-call-check"):
        return 1
    problems += [f"behind the call check: {p}" for p in
                 check(work / "grades-behind", {s: expect[s] for s in ["_control", *caught]}, labs)]
    for mark in marks:
        for place in (pathlib.Path(mark), work / mark, work.parent / mark, pathlib.Path("/tmp") / mark):
            if place.exists():
                problems.append(f"zip_escape: wrote {place} outside the submission")
    left = subprocess.run(["pgrep", "-x", "springlab-left"], capture_output=True, text=True).stdout.split()
    if left:
        problems.append(f"leaves_process_behind: {len(left)} process(es) still running after grading: {left}")
        subprocess.run(["pkill", "-9", "-x", "springlab-left"])
    rows = list(csv.DictReader(open(out / "gradebook.csv")))
    if sorted(r["student"] for r in rows) != sorted(expect):
        problems.append("gradebook.csv does not have one row per student")
    for row in rows:
        data = json.loads((out / row["student"] / "results.json").read_text())
        if float(row["total"]) != data["score"]:
            problems.append(f"gradebook.csv: {row['student']} total {row['total']} != results.json {data['score']}")
    report = (out / "does_not_compile" / "report.md").read_text()
    if "does not compile" not in report or "error" not in report or "explicit_euler.cpp" not in report:
        problems.append("does_not_compile: the report does not show the compiler's errors")
    if "not graded" not in (out / "edits_header" / "report.md").read_text():
        problems.append("edits_header: the report does not say the edited header was not graded")
    for student in ("calls_reference", "includes_reference"):
        if "graded as the released skeleton" not in (out / student / "report.md").read_text():
            problems.append(f"{student}: the report does not say the file was replaced by the skeleton's")
    problems += compile_time_problems(out, expect, pathlib.Path(args.cache).resolve())
    for problem in problems:
        print(f"PROBLEM: {problem}", file=sys.stderr)
    if problems:
        return 1
    print(f"{len(expect)} submissions graded as expected; control scores "
          f"{json.loads((out / '_control' / 'results.json').read_text())['score']:g}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
