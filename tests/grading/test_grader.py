#!/usr/bin/env python3
"""Unit tests of the grader's pieces (tools/springlab_grader/): manifests, handout agreement,
hidden-test redaction, zip safety, outputs (Gradescope results.json, JUnit XML), submission
folders, the link file CMake writes."""
import json
import pathlib
import re
import stat
import sys
import tempfile
import unittest
import xml.etree.ElementTree as ET
import zipfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
from springlab_grader import build_cache, errors, gtest_runner, integrity, labs, manifest, reports, results  # noqa: E402
from springlab_grader import submission  # noqa: E402

MANIFEST = {"lab": "09_toy", "title": "Lab 9: toy", "handout": "handouts/09_toy.md", "exercises": [
    {"id": "9.1", "title": "one", "tests": [{"name": "A.B", "points": 2, "visibility": "visible"},
                                           {"name": "H.B", "points": 1, "visibility": "hidden"}]}]}


class Temp(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.tmp = pathlib.Path(self.dir.name)

    def tearDown(self):
        self.dir.cleanup()

    def manifest(self, data):
        path = self.tmp / "exercises.json"
        path.write_text(json.dumps(data))
        return path


class ManifestErrorsNameFileAndField(Temp):
    def test_valid(self):
        m = manifest.load_manifest(self.manifest(MANIFEST))
        self.assertEqual(m["points"], 3)
        self.assertEqual(m["exercises"][0]["points"], 3)

    def test_missing_points(self):
        data = json.loads(json.dumps(MANIFEST))
        del data["exercises"][0]["tests"][1]["points"]
        with self.assertRaisesRegex(manifest.ManifestError, r"exercises.json: exercises\[0\]\.tests\[1\]\.points: missing"):
            manifest.load_manifest(self.manifest(data))

    def test_bad_visibility(self):
        data = json.loads(json.dumps(MANIFEST))
        data["exercises"][0]["tests"][0]["visibility"] = "secret"
        with self.assertRaisesRegex(manifest.ManifestError, r"tests\[0\]\.visibility: must be one of"):
            manifest.load_manifest(self.manifest(data))

    def test_duplicate_and_negative(self):
        data = json.loads(json.dumps(MANIFEST))
        data["exercises"][0]["tests"][1]["name"] = "A.B"
        with self.assertRaisesRegex(manifest.ManifestError, "declared twice"):
            manifest.load_manifest(self.manifest(data))
        data["exercises"][0]["tests"][1]["points"] = -1
        with self.assertRaisesRegex(manifest.ManifestError, "must be >= 0"):
            manifest.load_manifest(self.manifest(data))

    def test_not_json(self):
        path = self.tmp / "exercises.json"
        path.write_text("{")
        with self.assertRaisesRegex(manifest.ManifestError, "exercises.json: not valid JSON"):
            manifest.load_manifest(path)

    def test_handout_points_must_agree(self):
        m = manifest.load_manifest(self.manifest(MANIFEST))
        handout = self.tmp / "h.md"
        handout.write_text("Worth 3 points.\n### Exercise 9.1: one (2 points)\n")
        self.assertIn("missing the heading line '### Exercise 9.1: one (3 points)'", manifest.check_handout(m, handout)[0])
        handout.write_text("Worth 3 points.\n### Exercise 9.1: one (3 points)\n")
        self.assertEqual(manifest.check_handout(m, handout), [])

    def test_every_lab_of_this_tree_agrees(self):
        for lab in labs.discover_labs():
            self.assertEqual(manifest.check_handout(lab.manifest, ROOT / lab.manifest["handout"]), [])

    def test_builds_on_names_other_labs(self):
        # The programs of a lab register the labs it builds on (the rope's integrators in the
        # net's scenes); an id that names no other lab stops with the file and the field.
        for lab in labs.discover_labs():
            folder = self.tmp / "tests" / lab.dir
            folder.mkdir(parents=True)
            (folder / "exercises.json").write_text(json.dumps(lab.manifest if lab.name != "net" else
                                                              {**lab.manifest, "builds_on": ["cloth"]}))
        with self.assertRaisesRegex(errors.GradeError, r"02_net/exercises.json: builds_on: 'cloth' is not another lab's id"):
            labs.discover_labs(self.tmp)
        net = json.loads((self.tmp / "tests" / "02_net" / "exercises.json").read_text())
        (self.tmp / "tests" / "02_net" / "exercises.json").write_text(json.dumps({**net, "builds_on": "rope"}))
        with self.assertRaisesRegex(errors.GradeError, r"02_net/exercises.json: builds_on: must be a list of lab ids"):
            labs.discover_labs(self.tmp)
        self.assertEqual([lab.manifest.get("builds_on", []) for lab in labs.discover_labs()], [[], ["rope"], ["rope"]])


class HiddenMessagesShowNoValues(unittest.TestCase):
    def test_gtest_value_lines_dropped(self):
        eq = ("Expected equality of these values:\n  got.masses.size()\n    Which is: 3\n  want.masses.size()\n"
              "    Which is: 4\nwrong number of masses for a rope of 4 masses (seed 1)")
        self.assertEqual(gtest_runner.redact(eq), "wrong number of masses for a rope of 4 masses (seed 1)")
        lt = "Expected: (relativeError(a, b)) < (kTolerance), actual: 0.25 vs 1e-09\nspring force is wrong for x = (1, 2, 3)"
        self.assertEqual(gtest_runner.redact(lt), "spring force is wrong for x = (1, 2, 3)")
        near = ("The difference between a.k and b.k is 2, which exceeds 1e-9, where\na.k evaluates to 3,\n"
                "b.k evaluates to 5, and\n1e-9 evaluates to 1e-09.\nspring 2 has the wrong stiffness")
        self.assertEqual(gtest_runner.redact(near), "spring 2 has the wrong stiffness")
        truth = "Value of: sameEnds\n  Actual: false\nExpected: true\nspring 1 joins the wrong masses"
        self.assertEqual(gtest_runner.redact(truth), "spring 1 joins the wrong masses")

    def test_no_message_left(self):
        self.assertIn("values are not shown", gtest_runner.redact("Expected: (x) < (y), actual: 1 vs 2"))


class ZipsStayInside(Temp):
    def test_escaping_entries_skipped(self):
        archive = self.tmp / "s.zip"
        with zipfile.ZipFile(archive, "w") as zf:
            zf.writestr("labs/01_rope/a.cpp", "ok")
            zf.writestr("../evil.txt", "x")
            zf.writestr("/abs.txt", "x")
            zf.writestr("labs/../../evil2.txt", "x")
            link = zipfile.ZipInfo("labs/01_rope/link.hpp")
            link.external_attr = (stat.S_IFLNK | 0o777) << 16
            zf.writestr(link, "/etc/passwd")
        into = self.tmp / "x" / "into"
        into.mkdir(parents=True)
        notes = []
        submission.safe_extract(archive, into, notes)
        self.assertEqual(sorted(p.relative_to(into).as_posix() for p in into.rglob("*") if p.is_file()),
                         ["labs/01_rope/a.cpp"])
        self.assertEqual(len(notes), 4)
        self.assertFalse((self.tmp / "x" / "evil.txt").exists())

    def test_not_a_zip(self):
        bad = self.tmp / "bad.zip"
        bad.write_text("no")
        with self.assertRaisesRegex(errors.GradeError, "bad.zip: not a readable zip file"):
            submission.safe_extract(bad, self.tmp, [])


class Outputs(unittest.TestCase):
    def lab(self):
        m = json.loads(json.dumps(MANIFEST))
        m["points"] = 3
        ex = m["exercises"][0]
        ex["points"] = 3
        outcomes = [results.TestResult(ex, ex["tests"][0], True, "", 0.1),
                    results.TestResult(ex, ex["tests"][1], False, "wrong for x = 1", 0.2)]
        return results.LabResult(m, outcomes, ["a note"])

    def test_results_json_has_gradescope_fields(self):
        data = reports.gradescope_results([self.lab()], 1.5, 42)
        self.assertEqual((data["score"], data["max_score"], data["execution_time"]), (2, 3, 1.5))
        t = data["tests"][1]
        self.assertEqual({k: t[k] for k in ("number", "score", "max_score", "visibility", "status")},
                         {"number": "9.1", "score": 0, "max_score": 1, "visibility": "hidden", "status": "failed"})
        self.assertEqual(t["tags"], ["09_toy", "exercise 9.1"])
        self.assertIn("SPRINGLAB_SEED=42", data["output"])

    def test_junit(self):
        root = ET.fromstring(reports.junit_xml([self.lab()], 1.0).split("?>", 1)[1])
        suite = root.find("testsuite")
        self.assertEqual((suite.get("tests"), suite.get("failures")), ("2", "1"))
        self.assertEqual(root.findall(".//failure")[0].text, "wrong for x = 1")

    def test_markdown_per_exercise(self):
        text = reports.report_markdown([self.lab()], "Grade of x", 1)
        self.assertIn("### Exercise 9.1: one (2 / 3 points: public 2/2, hidden 0/1)", text)
        self.assertIn("a note", text)

    def test_public_and_hidden_apart(self):
        lab = self.lab()
        self.assertEqual(lab.split(), (2, 2, 0, 1, 0))
        # A student's own build (`check`) has no hidden tests: their points are "not run here".
        check = results.LabResult(lab.manifest, lab.results[:1])
        self.assertEqual(check.split(), (2, 2, 0, 0, 1))
        self.assertEqual(results.split_text(check.split()),
                         "public 2/2, hidden 1 point not run here, the grader runs them")
        import io
        out = io.StringIO()
        reports.print_lab(check, file=out)
        self.assertIn("Exercise 9.1: one  2/3  (public 2/2, hidden 1 point not run here", out.getvalue())


class ReportsCarryEveryNote(Temp):
    def test_report_md_has_the_notes_of_results_json(self):
        m = manifest.load_manifest(self.manifest(MANIFEST))
        lab = results.LabResult(m, [results.TestResult(m["exercises"][0], t, False, "failed", 0.0)
                                    for t in m["exercises"][0]["tests"]], ["a lab note\nits second line"])
        zip_note = "skipped zip entry '../../x': its path leads outside the submission"
        reports.write_outputs(self.tmp / "out", [lab], "Grade of x", 1.0, 7, [zip_note])
        data = json.loads((self.tmp / "out" / "results.json").read_text())
        report = (self.tmp / "out" / "report.md").read_text()
        for note in (zip_note, "a lab note", "its second line"):
            self.assertIn(note, data["output"])
            self.assertIn(note, report)


class StudentReadmeStatesTheLimits(unittest.TestCase):
    """The student README's limits are the grader's (a changed limit changes the README)."""

    def test_limits_and_forbidden_calls(self):
        from springlab_grader import lab_grader, sandbox, sealed_compile  # noqa: PLC0415
        text = (ROOT / "tools" / "templates" / "README.student.md").read_text()
        limits = sandbox.Sandbox()
        for stated in (f"{limits.timeout:g} s of wall time, {limits.timeout + 2:g} s of CPU time",
                       f"{limits.memory_mb} MiB per test", f"{limits.file_mb} MiB per test",
                       f"the stack {limits.stack_mb} MiB",
                       f"{sealed_compile.MEMORY_MB} MiB of memory, {sealed_compile.CPU_SECONDS} s of CPU time, "
                       f"{sealed_compile.WALL_SECONDS:g} s of wall time, {sealed_compile.OUTPUT_MB} MiB of object file",
                       f"its compiles {lab_grader.COMPILE_BUDGET:g} s of CPU time",
                       f"{lab_grader.BUDGET_FACTOR:g} times the reference's CPU time plus {lab_grader.BUDGET_FLOOR:g} s",
                       f"{lab_grader.LAB_WALL_LIMIT:g} s of wall time in all"):
            self.assertIn(stated, " ".join(text.split()))
        # Each call the README names is one the check refuses (by its symbol).
        symbols = {"getenv": "getenv", "fopen": "fopen", "std::filesystem": "_ZNSt10filesystem4pathC1Ev",
                   "fork": "fork", "system": "system", "kill": "kill", "syscall": "syscall", "socket": "socket",
                   "dlopen": "dlopen", "backtrace": "backtrace", "mprotect": "mprotect"}
        for call, symbol in symbols.items():
            self.assertTrue(integrity.forbidden_calls({symbol}), call)
            self.assertIn(f"`{call}", text)


class TimeBudget(unittest.TestCase):
    def test_lab_and_submission_budgets(self):
        total = gtest_runner.Budget(10, what="submission")
        lab_a, lab_b = gtest_runner.Budget(8, parent=total), gtest_runner.Budget(None, parent=total)
        lab_a.spend(7)
        self.assertIsNone(lab_a.exhausted())
        lab_a.spend(2)
        self.assertIs(lab_a.exhausted(), lab_a)
        self.assertIn("time budget spent", lab_a.exhausted().message())
        self.assertIsNone(lab_b.exhausted())
        lab_b.spend(1.5)  # the submission's 10 s: 9 + 1.5
        self.assertIs(lab_b.exhausted(), total)

    def test_shares_follow_the_reference_time_not_the_test_count(self):
        reference = {"Slow.Drape": 6.8, **{f"Quick.T{k}": 0.01 for k in range(10)}}
        rule = gtest_runner.BudgetRule(120.0, 10.0, reference)
        slow = rule.share(["Slow.Drape"], 2)
        quick = rule.share([f"Quick.T{k}" for k in range(10)], 2)
        self.assertGreater(slow, quick + 60)
        self.assertAlmostEqual(slow + quick, rule.limit)

    def test_cpu_time_is_counted_and_a_wall_limit_bounds_waiting(self):
        # A process that sleeps costs no CPU time; one that computes does (sandbox.reap).
        import subprocess  # noqa: PLC0415
        import time  # noqa: PLC0415
        from springlab_grader.sandbox import reap  # noqa: PLC0415
        sleeper = subprocess.Popen(["sleep", "0.3"])
        code, cpu = reap(sleeper, time.monotonic() + 10)
        self.assertEqual(code, 0)
        self.assertLess(cpu, 0.2)
        spinner = subprocess.Popen([sys.executable, "-c", "import time\nt = time.process_time()\n"
                                                          "while time.process_time() - t < 0.5: pass"])
        code, cpu = reap(spinner, time.monotonic() + 30)
        self.assertEqual(code, 0)
        self.assertGreater(cpu, 0.45)
        hanging = subprocess.Popen(["sleep", "5"])
        self.assertEqual(reap(hanging, time.monotonic() + 0.1), (None, None))
        hanging.kill()
        reap(hanging)
        # The wall limit: spent by waiting alone, named in the message.
        budget = gtest_runner.Budget(100.0, wall=0.05)
        self.assertIsNone(budget.exhausted())
        time.sleep(0.1)
        self.assertIs(budget.exhausted(), budget)
        self.assertIs(gtest_runner.Budget(None, parent=budget).past_wall_limit(), budget)
        self.assertIn("wall-time limit", budget.message())

    def test_spent_budget_fails_the_remaining_tests(self):
        m = json.loads(json.dumps(MANIFEST))
        budget = gtest_runner.Budget(1)
        budget.spend(2)
        got = gtest_runner.grade_binary("/nonexistent", m, 1, None, 1, present={"A.B", "H.B"}, budget=budget)
        self.assertEqual([(r.passed, "time budget spent" in r.message) for r in got], [(False, True), (False, True)])
        got = gtest_runner.grade_binary("/nonexistent", m, 1, None, 1, present={"A.B", "H.B"}, budget=budget,
                                        only={"H.B"})
        self.assertEqual([r.test["name"] for r in got], ["H.B"])


class SubmissionFolders(Temp):
    def test_duplicate_students(self):
        (self.tmp / "ann").mkdir()
        (self.tmp / "ann.zip").write_bytes(b"")
        with self.assertRaisesRegex(errors.GradeError, "two submissions for ann"):
            submission.submissions_in(self.tmp)

    def test_empty_class(self):
        with self.assertRaisesRegex(errors.GradeError, "holds no submission"):
            submission.submissions_in(self.tmp)

    def exercise_files(self, lab, folder, count=None):
        folder.mkdir(parents=True, exist_ok=True)
        for name in sorted(submission.exercise_names(lab))[:count]:
            (folder / name).write_text("// mine\n")

    def test_lab_found_at_any_depth(self):
        lab = labs.discover_labs()[0]
        self.exercise_files(lab, self.tmp / "repo" / "labs" / lab.dir)
        self.exercise_files(lab, self.tmp / "deeper" / "x" / lab.dir)
        self.assertEqual(submission.find_lab_folder(self.tmp, lab), self.tmp / "repo" / "labs" / lab.dir)

    def test_whole_repository_is_not_taken_for_its_tests(self):
        # A student's clone: tests/01_rope (no exercise files) sits beside labs/01_rope.
        lab = labs.discover_labs()[0]
        (self.tmp / "clone" / "tests" / lab.dir / "public").mkdir(parents=True)
        (self.tmp / "clone" / "tests" / lab.dir / "exercises.json").write_text("{}")
        self.exercise_files(lab, self.tmp / "clone" / "labs" / lab.dir, 2)
        self.assertEqual(submission.find_lab_folder(self.tmp, lab), self.tmp / "clone" / "labs" / lab.dir)
        (self.tmp / "clone" / "labs" / lab.dir).rename(self.tmp / "clone" / "labs" / "elsewhere")
        self.assertIsNone(submission.find_lab_folder(self.tmp, lab))

    def test_flat_files_go_to_one_lab(self):
        all_labs = labs.discover_labs()
        rope, net = all_labs[0], all_labs[1]
        self.exercise_files(rope, self.tmp / "wrapped")  # a zip's top folder around flat files
        notes = []
        found = submission.locate_labs(self.tmp, all_labs, notes)
        self.assertEqual(found[rope.dir], self.tmp / "wrapped")
        self.assertTrue(all(found[lab.dir] is None for lab in all_labs[1:]), found)
        # --lab: only that lab, even when another lab's names would match better.
        found = submission.locate_labs(self.tmp, all_labs, notes, only=net.name)
        self.assertEqual(list(found), [net.dir])
        shared = submission.exercise_names(rope) & submission.exercise_names(net)
        self.assertEqual(found[net.dir], self.tmp / "wrapped" if shared else None)

    def test_ambiguous_flat_files_ask_for_lab(self):
        all_labs = labs.discover_labs()
        shared = sorted(submission.exercise_names(all_labs[0]) & submission.exercise_names(all_labs[1]))
        if not shared:
            self.skipTest("no file name shared by Labs 1 and 2")
        (self.tmp / shared[0]).write_text("// mine\n")
        notes = []
        found = submission.locate_labs(self.tmp, all_labs, notes)
        self.assertTrue(all(v is None for v in found.values()))
        self.assertIn("--lab", notes[0])

    def test_depfile(self):
        self.assertEqual(integrity.parse_depfile("obj/a.o: src/a.cpp \\\n /usr/x\\ y.h src/b.hpp\n"),
                         ["src/a.cpp", "/usr/x y.h", "src/b.hpp"])


LINK = {"about": "test", "lab": "toy", "compiler": "/usr/bin/c++", "flags": ["-O3", "", "SHELL:-a b", "LINKER:-z,defs"],
        "test_objects": ["/b/t1.o", "/b/main.o"], "given_objects": ["/b/g.o"], "oracle": "/b/liboracle.a",
        "libraries": ["/b/libgtest.a", "/b/liboracle.a", "", "/b/libcore.a"], "skeleton_program": "/b/toy_grading_student"}


class LinkFileFromCMake(Temp):
    def write(self, data):
        path = self.tmp / "toy_link.json"
        path.write_text(data if isinstance(data, str) else json.dumps(data))
        return path

    def test_link_line(self):
        link = build_cache.read_link_file(self.write(LINK))
        self.assertEqual(link.flags, ["-O3", "-a", "b", "-Wl,-z,defs"])  # empty items dropped, CMake prefixes expanded
        self.assertEqual((link.oracle, link.given_objects), ("/b/liboracle.a", ["/b/g.o"]))
        self.assertEqual(link.argv("/w/libstudent.a", "/w/out"),
                         ["/usr/bin/c++", "-O3", "-a", "b", "-Wl,-z,defs", "/b/t1.o", "/b/main.o", "-o", "/w/out",
                          "/w/libstudent.a", "/b/libgtest.a", "/b/liboracle.a", "/b/libcore.a"])

    def test_per_file_objects(self):
        link = build_cache.read_link_file(self.write(LINK))
        self.assertEqual((link.solution_objects, link.skeleton_objects, link.reference_program), ([], [], ""))
        link = build_cache.read_link_file(self.write(dict(LINK, solution_objects=["/b/s/a.cpp.o"],
                                                          skeleton_objects=["/b/k/a.cpp.o"],
                                                          reference_program="/b/toy_grading_reference")))
        self.assertEqual((link.solution_objects, link.reference_program), (["/b/s/a.cpp.o"], "/b/toy_grading_reference"))

    def test_no_oracle(self):
        self.assertEqual(build_cache.read_link_file(self.write(dict(LINK, oracle=""))).oracle, "")

    def test_missing_file(self):
        with self.assertRaisesRegex(errors.GradeError, r"nowhere_link\.json: missing; .*configure the build again"):
            build_cache.read_link_file(self.tmp / "nowhere_link.json")

    def test_not_json(self):
        path = self.write('{"compiler": "/usr/bin/c++", "flags": ["-O3",]}')
        with self.assertRaisesRegex(errors.GradeError, r"toy_link\.json: not valid JSON"):
            build_cache.read_link_file(path)
        with self.assertRaisesRegex(errors.GradeError, r"toy_link\.json: not a JSON object"):
            build_cache.read_link_file(self.write("[1]"))

    def test_bad_fields(self):
        without = {k: v for k, v in LINK.items() if k != "compiler"}
        with self.assertRaisesRegex(errors.GradeError, r"toy_link\.json: compiler: missing, or not a string"):
            build_cache.read_link_file(self.write(without))
        with self.assertRaisesRegex(errors.GradeError, r"toy_link\.json: libraries: missing, or not a list of strings"):
            build_cache.read_link_file(self.write(dict(LINK, libraries="/b/libcore.a")))
        with self.assertRaisesRegex(errors.GradeError, r"toy_link\.json: test_objects: empty"):
            build_cache.read_link_file(self.write(dict(LINK, test_objects=[""])))



class ObjectCacheChecksItsEntries(Temp):
    def test_a_tampered_entry_is_not_used(self):
        cache = build_cache.ObjectCache(self.tmp / "cache")
        (self.tmp / "a.o").write_bytes(b"object")
        (self.tmp / "a.d").write_text("a.o: a.cpp\n")
        cache.store("k", self.tmp / "a.o", self.tmp / "a.d")
        out = self.tmp / "out"
        out.mkdir()
        self.assertEqual(cache.fetch("k", out, "a.cpp"), out / "a.cpp.o")
        (self.tmp / "cache" / "k.o").write_bytes(b"poisoned")
        self.assertIsNone(cache.fetch("k", out, "a.cpp"))
        self.assertIsNone(cache.fetch("missing", out, "a.cpp"))

    def test_size_cap_evicts_the_least_recently_used_and_huge_objects_stay_out(self):
        import os  # noqa: PLC0415
        cache = build_cache.ObjectCache(self.tmp / "cache", cap=3000)
        (self.tmp / "a.d").write_text("a.o: a.cpp\n")
        out = self.tmp / "out"
        out.mkdir()
        for number, key in enumerate(("old", "used", "new")):
            (self.tmp / "a.o").write_bytes(b"x" * 1000)
            cache.store(key, self.tmp / "a.o", self.tmp / "a.d")
            os.utime(self.tmp / "cache" / f"{key}.sha256", (1000 + number, 1000 + number))
        self.assertIsNotNone(cache.fetch("used", out, "a.cpp"))  # now the most recent
        (self.tmp / "a.o").write_bytes(b"y" * 1000)
        cache.store("newest", self.tmp / "a.o", self.tmp / "a.d")
        self.assertIsNone(cache.fetch("old", out, "a.cpp"))
        self.assertIsNotNone(cache.fetch("used", out, "a.cpp"))
        self.assertIsNotNone(cache.fetch("newest", out, "a.cpp"))
        self.assertLessEqual(sum(p.stat().st_size for p in (self.tmp / "cache").iterdir()), 3000)
        huge = self.tmp / "huge.o"
        with open(huge, "wb") as f:
            f.truncate(build_cache.ObjectCache.OBJECT_LIMIT + 1)
        cache.store("huge", huge, self.tmp / "a.d")
        self.assertIsNone(cache.fetch("huge", out, "a.cpp"))

    def test_a_compile_is_reused_only_where_its_include_places_are_allowed(self):
        # An object's dependency file names the places its compile read headers from. Sealed,
        # those are the sandbox's neutral paths, the same for every grader; without bubblewrap
        # they are each grader's own staged copies, which another grader's include check does
        # not allow: it must compile again, never take the other's object (which would grade an
        # honest file as the skeleton's for "including a file outside the framework").
        from springlab_grader import lab_grader, sealed_compile  # noqa: PLC0415
        cache = build_cache.ObjectCache(self.tmp / "cache")
        inside = sealed_compile.NEUTRAL / "framework/include"

        def key(staged, sealed):
            compiler = sealed_compile.SealedCompiler(["g++"], [(self.tmp / staged, inside)], ["g++"], sealed)
            return lab_grader.object_key(cache, ["g++", "-O2"], compiler, "wind.cpp", b"code", b"headers")

        self.assertEqual(key("stage-a", True), key("stage-b", True))
        self.assertNotEqual(key("stage-a", False), key("stage-b", False))
        self.assertEqual(key("stage-a", False), key("stage-a", False))
        self.assertNotEqual(key("stage-a", True), key("stage-a", False))

class CallLayerFromTheManifest(Temp):
    """tools/make_call_layer.py: the worker's record and forward files and the judge's replay
    files follow the manifest's exercise files and declarations, one function per name."""
    MANIFEST = {"lab": "toy", "values": {"Hit": ["touching", "normal"]}, "exercises": [
        {"id": "9.1", "file": "probe.cpp", "functions": ["Hit probe(const Vec3& x, double radius)"]},
        {"id": "9.2", "file": "smooth.cpp", "functions": [
            "void smooth(std::vector<Vec3>& pos, const std::vector<std::pair<int, int>>& pairs, int passes)"]}]}

    def generate(self, manifest=None):
        sys.path.insert(0, str(ROOT / "tools"))
        import make_call_layer  # noqa: PLC0415
        path = self.manifest(manifest or self.MANIFEST)
        make_call_layer.generate(path, self.tmp / "out")
        return self.tmp / "out"

    def test_functions_by_file(self):
        out = self.generate()
        self.assertEqual(json.loads((out / "functions.json").read_text()),
                         {"probe.cpp": ["probe"], "smooth.cpp": ["smooth"]})

    def test_record_writes_the_result_and_written_arguments(self):
        out = self.generate()
        record = (out / "smooth.record.cpp").read_text()
        self.assertIn('asm("springlab_student_smooth")', record)
        self.assertIn("put(w, pos);", record)
        self.assertNotIn("put(w, pairs);", record)  # read, not written
        replay = (out / "smooth.replay.cpp").read_text()
        self.assertIn('trace::replayCall(1u, "smooth")', replay)
        self.assertIn("get(r, pos);", replay)

    def test_values_bind_every_field_and_forward_reads_the_same_layout(self):
        out = self.generate()
        values = (out / "values.hpp").read_text()
        self.assertIn("put(w, v.touching);", values)
        self.assertIn("put(w, v.normal);", values)
        self.assertIn("auto& [field0, field1] = v;", values)  # another field count does not compile
        forward = (out / "probe.forward.cpp").read_text()
        self.assertIn("namespace springlab::toy_reference", forward)
        self.assertIn("forwardCall<Hit>(&::springlab::toy::student_probe, x, radius)", forward)

    def test_a_function_declared_twice_is_refused(self):
        manifest = json.loads(json.dumps(self.MANIFEST))
        manifest["exercises"][1]["functions"].append("Hit probe(const Vec3& x)")
        with self.assertRaisesRegex(SystemExit, "declared twice \\(probe\\)"):
            self.generate(manifest)

    def test_a_malformed_declaration_names_file_and_field(self):
        manifest = json.loads(json.dumps(self.MANIFEST))
        manifest["exercises"][0]["functions"] = ["probe"]
        with self.assertRaisesRegex(SystemExit, r"exercises.json: exercises\[0\]\.functions: `probe` is not a declaration"):
            self.generate(manifest)


class JudgedOutcomes(unittest.TestCase):
    """What a student reads when the judge's report or the worker's fate decides."""

    def run_of(self, report, judge_code=0, worker_code=0, output="", judge_output=""):
        from springlab_grader import judged_run  # noqa: PLC0415
        return judged_run.JudgedRun(report, judge_code, judge_output, judged_run.Fate(worker_code, output), 0.1)

    def test_pass(self):
        from springlab_grader.judged_run import outcome_of  # noqa: PLC0415
        run = self.run_of({"tests": [{"name": "A.B", "status": "passed", "failures": []}]})
        self.assertEqual(outcome_of(run, "A.B", 20), (True, ""))

    def test_worker_crash_is_named(self):
        from springlab_grader.judged_run import TRACE_ENDED, outcome_of  # noqa: PLC0415
        failure = "x.cpp:12\nFailed\n" + TRACE_ENDED + "your code did not return from its call of f (call 3)"
        run = self.run_of({"tests": [{"name": "A.B", "status": "failed", "failures": [failure]}]}, worker_code=-11)
        passed, message = outcome_of(run, "A.B", 20)
        self.assertFalse(passed)
        self.assertIn("segmentation fault", message)
        self.assertNotIn(TRACE_ENDED, message)

    def test_judge_timeout_blames_a_hanging_worker(self):
        from springlab_grader.judged_run import outcome_of  # noqa: PLC0415
        passed, message = outcome_of(self.run_of(None, judge_code=None, worker_code=None), "A.B", 20)
        self.assertFalse(passed)
        self.assertIn("timed out after 20 s", message)
        self.assertIn("infinite loop", message)

    def test_no_report_fails(self):
        from springlab_grader.judged_run import outcome_of  # noqa: PLC0415
        self.assertFalse(outcome_of(self.run_of(None, judge_code=-6), "A.B", 20)[0])
        self.assertFalse(outcome_of(self.run_of({"tests": []}), "A.B", 20)[0])


    def test_judge_assertion_names_the_index_past_the_end(self):
        # What libstdc++ prints before abort() in a judge built with -D_GLIBCXX_ASSERTIONS.
        from springlab_grader.judged_run import outcome_of  # noqa: PLC0415
        printed = ("[ RUN      ] BuildRope.FirstMassIsFixedAtTheConnectionPoint\n/usr/include/c++/12/bits/stl_vector.h:"
                   "1123: std::vector<_Tp, _Alloc>::reference std::vector<_Tp, _Alloc>::operator[](size_type) [with "
                   "_Tp = Eigen::Matrix<double, 3, 1>; size_type = long unsigned int]: Assertion '__n < this->size()' "
                   "failed.")
        passed, message = outcome_of(self.run_of(None, judge_code=-6, judge_output=printed), "A.B", 20)
        self.assertFalse(passed)
        self.assertIn("index past the end of what your code returned (std::vector::operator[], "
                      "__n < this->size())", message)
        # A crash without an assertion keeps the general message.
        passed, message = outcome_of(self.run_of(None, judge_code=-11, judge_output="[ RUN ] A.B"), "A.B", 20)
        self.assertIn("judge crashed (segmentation fault", message)


class LaunchedLikeAWorker(unittest.TestCase):
    """The one launch of student code (judged_run.launch_worker) that `grade` and `check` share."""

    def test_the_command_line_names_no_test(self):
        from springlab_grader import judged_run  # noqa: PLC0415
        argv = judged_run.worker_argv("/somewhere/worker", {"SPRINGLAB_SEED": "7"})
        self.assertEqual(argv[-2:], [judged_run.PROGRAM_NAME, *judged_run.WORKER_ARGS])
        self.assertFalse(any("gtest_filter" in a for a in argv))

    def test_the_environment_is_the_workers(self):
        from springlab_grader import judged_run  # noqa: PLC0415
        env = judged_run.worker_env({"SPRINGLAB_SEED": "7"})
        self.assertEqual(set(env), {*judged_run.WORKER_ENV, "SPRINGLAB_SEED", "SPRINGLAB_CALL_TRACE_FD"})
        self.assertEqual(env["SPRINGLAB_CALL_TRACE_FD"], str(judged_run.CHANNEL_FD))

    def test_a_bubblewrap_exit_above_128_is_a_signal(self):
        from springlab_grader.judged_run import crash_signal  # noqa: PLC0415
        self.assertEqual(crash_signal(-11), 11)
        self.assertEqual(crash_signal(128 + 6), 6)
        self.assertIsNone(crash_signal(1))
        self.assertIsNone(crash_signal(None))


class StudentReadmePointsTable(unittest.TestCase):
    """The student README's table of public and hidden points per lab is the manifests' sum."""

    def test_table_matches_the_manifests(self):
        text = (ROOT / "tools" / "templates" / "README.student.md").read_text()
        rows = {int(m[1]): (int(m[2]), int(m[3]), int(m[4])) for m in
                re.finditer(r"^\| (\d) \| (\d+) \| (\d+) \| (\d+) \|$", text, flags=re.MULTILINE)}
        for number, lab in enumerate(labs.discover_labs(), start=1):
            tests = [t for ex in lab.manifest["exercises"] for t in ex["tests"]]
            public = sum(t["points"] for t in tests if t["visibility"] == "visible")
            hidden = sum(t["points"] for t in tests if t["visibility"] != "visible")
            with self.subTest(lab.dir):
                self.assertEqual(rows.get(number), (public, hidden, public + hidden))


class ForbiddenCallsOfExerciseCode(Temp):
    """The calls an exercise file may not make (integrity.FORBIDDEN_CALLS), read from the
    undefined symbols of real objects: honest code passes, each way out is named."""

    def compiled(self, name, code):
        import subprocess  # noqa: PLC0415
        source = self.tmp / f"{name}.cpp"
        source.write_text(code)
        obj = self.tmp / f"{name}.o"
        subprocess.run(["g++", "-std=c++20", "-O2", "-c", str(source), "-o", str(obj)], check=True)
        return integrity.forbidden_calls(integrity.undefined_symbols(obj))

    def test_honest_code_computes_allocates_and_prints(self):
        self.assertEqual(self.compiled("honest", """
#include <cmath>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>
std::vector<double> f(const std::vector<double>& x) {
  std::vector<double> y;
  for (double v : x) y.push_back(std::sqrt(v) / std::pow(v, 0.3));
  if (y.empty()) throw std::invalid_argument("empty: " + std::to_string(x.size()));
  std::cout << y.size() << std::endl;
  return y;
}"""), [])

    def test_each_way_out_is_named(self):
        cases = {
            "environment": ('#include <cstdlib>\nbool f() { return std::getenv("HOME") != nullptr; }',
                            "environment"),
            "file": ('#include <fstream>\nbool f() { return std::ifstream("/proc/self/cmdline").good(); }',
                     "files"),
            "framework": ('#include <gtest/gtest.h>\n'
                          'const char* f() { return testing::UnitTest::GetInstance()->current_test_info()->name(); }',
                          "test framework"),
            "process": ('#include <unistd.h>\nint f() { return ::fork(); }', "processes"),
        }
        for name, (code, what) in cases.items():
            with self.subTest(name):
                found = self.compiled(name, code)
                self.assertTrue(found, f"{name}: nothing found")
                self.assertTrue(any(what in reached for _, reached in found), found)

    def test_weak_definitions_count_as_definitions(self):
        import subprocess  # noqa: PLC0415
        source = self.tmp / "weak.cpp"
        source.write_text("namespace testing::internal { __attribute__((weak)) bool IsTrue(bool c) { return !c; } }\n"
                          "__attribute__((weak)) int weakData = 3;\nint strong() { return 1; }\n")
        obj = self.tmp / "weak.o"
        subprocess.run(["g++", "-std=c++20", "-O2", "-c", str(source), "-o", str(obj)], check=True)
        defined = integrity.symbols_by_file([obj])[str(obj)]
        self.assertIn("_ZN7testing8internal6IsTrueEb", defined)
        self.assertIn("weakData", defined)
        self.assertIn("_Z6strongv", defined)

    def test_check_makes_the_call_check_of_grade_with_its_sentence(self):
        # A student's build: compile_commands.json names the exercise objects of the program.
        import subprocess  # noqa: PLC0415
        from springlab_grader import student_check  # noqa: PLC0415
        lab = labs.discover_labs()[0]
        build = self.tmp / "build"
        (build / "tests").mkdir(parents=True)
        (build / "tests" / f"{lab.name}_grading_student").write_text("")
        objects = build / f"springlab_{lab.name}_student_objects.dir"
        objects.mkdir()
        name = sorted(submission.exercise_names(lab))[0]
        source = self.tmp / name
        source.write_text('#include <cstdlib>\nbool debugging() { return std::getenv("DEBUG") != nullptr; }\n')
        subprocess.run(["g++", "-O2", "-c", str(source), "-o", str(objects / f"{name}.o")], check=True)
        (build / "compile_commands.json").write_text(json.dumps([{
            "directory": str(build), "file": str(source),
            "command": f"/usr/bin/c++ -O2 -o {objects.name}/{name}.o -c {source}"}]))
        flagged = student_check.forbidden_call_notes(build / "tests" / f"{lab.name}_grading_student", ROOT, lab.dir)
        note, exercises = flagged[name]
        self.assertEqual(exercises, labs.exercises_in(lab.solution / name))
        why = integrity.forbidden_call_reason(integrity.undefined_symbols(objects / f"{name}.o"))
        self.assertEqual(note, integrity.replaced_note(name, why, exercises))
        self.assertIn("calls getenv, which reach the environment or command line", note)
        # A student tree (no solutions/) finds the file's exercises in the lab folder's README.
        self.assertEqual(student_check.exercises_by_file(self.tmp / "nowhere", lab.dir), {})
        (self.tmp / "student" / "labs").mkdir(parents=True)
        import shutil  # noqa: PLC0415
        shutil.copytree(lab.skeleton, self.tmp / "student" / "labs" / lab.dir)
        self.assertEqual(student_check.exercises_by_file(self.tmp / "student", lab.dir)[name], exercises)


class SealedCompile(Temp):
    """The compiler's sandbox (sealed_compile.py) against a grading tree of mode 700: the
    framework's headers are found (staged), nothing of the tree is (`#include`, `__has_include`,
    `.incbin`), and each limit stops the compiler with a sentence naming it."""

    def setUp(self):
        super().setUp()
        from springlab_grader import judged_run, sealed_compile  # noqa: PLC0415
        if judged_run.bubblewrap() is None:
            self.skipTest("bubblewrap cannot create namespaces here")
        self.sc = sealed_compile
        self.tree = self.tmp / "tree"
        (self.tree / "framework" / "include" / "springlab").mkdir(parents=True)
        (self.tree / "framework" / "include" / "springlab" / "seven.hpp").write_text("inline int seven() { return 7; }\n")
        (self.tree / "solutions").mkdir()
        self.secret = self.tree / "solutions" / "secret.cpp"
        self.secret.write_text("SPRINGLAB_REFERENCE_MARKER\n")
        self.tmp.chmod(0o700)
        self.tree.chmod(0o700)
        self.work = pathlib.Path(tempfile.mkdtemp(prefix="springlab-sealed-test-"))
        self.addCleanup(__import__("shutil").rmtree, self.work, True)
        self.work.chmod(0o711)
        (self.work / "src").mkdir(mode=0o755)
        (self.work / "obj").mkdir()
        sandbox = sealed_compile.compile_sandbox()
        if sandbox.identity():
            import os  # noqa: PLC0415
            os.chown(self.work / "obj", *sandbox.identity())
        self.sandbox = sandbox
        self.compiler = sealed_compile.sealed_compiler(
            ["/usr/bin/c++", f"-I{self.tree / 'framework' / 'include'}", "-O1", "-std=c++20"], self.tree, True)

    def compile(self, name, code, sandbox=None):
        source = self.work / "src" / name
        source.write_text(code)
        source.chmod(0o644)
        return self.compiler.run(self.work, name, sandbox or self.sandbox)

    def test_headers_at_neutral_paths(self):
        self.assertIn("-I/springlab/framework/include", self.compiler.argv)
        run = self.compile("ok.cpp", "#include <springlab/seven.hpp>\n#include <vector>\nint f() { return seven(); }\n")
        self.assertEqual(run.returncode, 0, run.output)
        self.assertTrue((self.work / "obj" / "ok.cpp.o").is_file())
        self.assertIn("/springlab/framework/include/springlab/seven.hpp", (self.work / "obj" / "ok.cpp.d").read_text())

    def test_nothing_of_the_tree_is_visible(self):
        probe = f'#if __has_include("{self.secret}")\n#error the tree is visible\n#endif\nint f();\n'
        self.assertEqual(self.compile("probe.cpp", probe).returncode, 0)
        for name, code in (("incbin.cpp", f'asm(".incbin \\"{self.secret}\\"");\n'),
                           ("include.cpp", f'#include "{self.secret}"\n')):
            with self.subTest(name):
                run = self.compile(name, code)
                self.assertNotEqual(run.returncode, 0)
                self.assertNotIn("SPRINGLAB_REFERENCE_MARKER", run.output)
                self.assertNotIn(str(self.tree), self.sc.scrub(run.output, {self.tree: "<grading tree>"}))

    def test_limits_stop_it_with_a_sentence(self):
        import dataclasses  # noqa: PLC0415
        small = dataclasses.replace(self.sandbox, memory_mb=512, file_mb=4)
        run = self.compile("zero.cpp", '#include "/dev/zero"\n', small)
        self.assertIn("memory limit", self.sc.stop_reason(run, "zero.cpp") or "", run.output)
        run = self.compile("fill.cpp", 'asm(".fill 50000000, 1, 0");\n', small)
        self.assertIn("output limit", self.sc.stop_reason(run, "fill.cpp") or "", run.output)
        self.assertIsNone(self.sc.stop_reason(self.compile("typo.cpp", "int f() { return x; }\n"), "typo.cpp"))

    def test_an_include_folder_holding_the_tree_is_refused(self):
        with self.assertRaisesRegex(errors.GradeError, "solutions/"):
            self.sc.sealed_compiler(["/usr/bin/c++", f"-I{self.tree}"], self.tree, True)


class StagesOfEndedGradersGo(Temp):
    def test_a_stage_whose_grader_ended_is_removed(self):
        import subprocess  # noqa: PLC0415
        from springlab_grader import staging  # noqa: PLC0415
        ended = subprocess.Popen(["true"])
        ended.wait()
        for name, pid in (("springlab-stage-ended", ended.pid), ("springlab-stage-alive", __import__("os").getpid())):
            (self.tmp / name).mkdir()
            (self.tmp / name / "pid").write_text(str(pid))
        staging.remove_stale_stages(self.tmp)
        self.assertFalse((self.tmp / "springlab-stage-ended").exists())
        self.assertTrue((self.tmp / "springlab-stage-alive").exists())


class SymlinkedLabFolders(Temp):
    """A lab folder (or labs/) that is a symbolic link, absolute or relative, at any depth, is
    never followed, and the note does not print where it leads."""

    def test_links_are_refused_with_a_note(self):
        lab = labs.discover_labs()[0]
        outside = self.tmp / "outside" / lab.dir
        outside.mkdir(parents=True)
        for name in submission.exercise_names(lab):
            (outside / name).write_text("// the reference\n")
        for kind in ("absolute", "relative", "deep", "labs"):
            with self.subTest(kind):
                root = self.tmp / kind
                nested = root / "repo" / "deeper" if kind == "deep" else root
                nested.mkdir(parents=True)
                if kind == "labs":
                    (nested / "labs").symlink_to(outside.parent)
                elif kind == "relative":
                    (nested / lab.dir).symlink_to(pathlib.Path("..") / "outside" / lab.dir)
                else:
                    (nested / lab.dir).symlink_to(outside)
                notes = []
                found = submission.locate_labs(root, [lab], notes, lab.name)
                self.assertIsNone(found[lab.dir])
                self.assertTrue(any("symbolic link" in n and "refused" in n for n in notes), notes)
                self.assertFalse(any(str(self.tmp) in n for n in notes), notes)


# GCC 12's text for `const Vec3 n = a * b;` on two Vec3 (line 10 of normals.cpp), cut short: the
# error is in Eigen's header, the student's line only in "required from here" before it.
GCC_EIGEN_PRODUCT = """In file included from /usr/include/eigen3/Eigen/Core:164,
                 from /t/framework/labs/net/include/springlab/net/exercises.hpp:13,
                 from /t/labs/02_net/normals.cpp:1:
/usr/include/eigen3/Eigen/src/Core/GeneralProduct.h: In instantiation of 'const Eigen::Product<...>':
labs/02_net/normals.cpp:10:24:   required from here
/usr/include/eigen3/Eigen/src/Core/GeneralProduct.h:415:3: error: static assertion failed: \
INVALID_VECTOR_VECTOR_PRODUCT__IF_YOU_WANTED_A_DOT_OR_COEFF_WISE_PRODUCT_YOU_MUST_USE_THE_EXPLICIT_FUNCTIONS
  415 |   EIGEN_STATIC_ASSERT(ProductIsValid || !(AreVectors && SameSizes),
      |   ^~~~~~~~~~~~~~~~~~~
/usr/include/eigen3/Eigen/src/Core/CwiseBinaryOp.h:115:7: error: static assertion failed: YOU_MIXED_MATRICES
"""
# Clang places the student's line after the error, as a note.
CLANG_EIGEN_PRODUCT = """/usr/include/eigen3/Eigen/src/Core/GeneralProduct.h:415:3: error: static assertion failed due to \
requirement '...': INVALID_VECTOR_VECTOR_PRODUCT__IF_YOU_WANTED_A_DOT_OR_COEFF_WISE_PRODUCT
labs/02_net/normals.cpp:10:24: note: in instantiation of function template specialization requested here
    const Vec3 n = a * b;
"""


class CompileErrorsSayTheFirstErrorWhereTheStudentCanFixIt(Temp):
    def is_normals(self, path):
        return path.endswith("labs/02_net/normals.cpp")

    def test_eigen_error_is_placed_at_the_students_line_with_the_hint(self):
        from springlab_grader import compile_errors  # noqa: PLC0415
        (self.tmp / "labs" / "02_net").mkdir(parents=True)
        (self.tmp / "labs" / "02_net" / "normals.cpp").write_text("\n" * 9 + "    const Vec3 n = a * b;\n")
        for text in (GCC_EIGEN_PRODUCT.replace("\\\n", ""), CLANG_EIGEN_PRODUCT.replace("\\\n", "")):
            lines = compile_errors.summary(text, self.is_normals, root=self.tmp)
            self.assertTrue(lines[0].startswith("labs/02_net/normals.cpp:10:24: error: static assertion failed"), lines)
            self.assertIn("(inside GeneralProduct.h, from this line)", lines[0])
            self.assertEqual(lines[1].strip(), "const Vec3 n = a * b;")
            self.assertIn("use a.dot(b) (a number), a.cross(b) (a Vec3) or a.cwiseProduct(b)", lines[2])

    def test_common_errors_have_their_hints_and_others_the_general_one(self):
        from springlab_grader import compile_errors  # noqa: PLC0415
        cases = {"'foo' was not declared in this scope": "a name the compiler does not know",
                 "no return statement in function returning non-void [-Werror=return-type]": "without `return`",
                 "expected ';' before 'normals'": "a `;` is missing",
                 "'const Vec3' has no member named 'length'": "v.norm()",
                 "no matching function for call to 'f(int)'": "compare their number and types",
                 "assignment of read-only location 'pos[0]'": "something const",
                 "something no table knows": compile_errors.HINT_ELSE}
        for message, hint in cases.items():
            text = f"labs/01_rope/x.cpp:3:5: error: {message}\n    3 |   code;\n"
            with self.subTest(message):
                lines = compile_errors.summary(text, lambda p: p.endswith("x.cpp"))
                self.assertEqual(lines[0], f"labs/01_rope/x.cpp:3:5: error: {message}")
                self.assertEqual(lines[1], "    code;")
                self.assertIn(hint, lines[2])

    def test_grade_places_it_in_the_submitted_file(self):
        # `grade` compiles src/<file> in its sandbox and shows the file's name only.
        from springlab_grader import compile_errors  # noqa: PLC0415
        text = compile_errors.first_errors(GCC_EIGEN_PRODUCT.replace("\\\n", "").replace("labs/02_net/", "src/"))
        lines = compile_errors.summary(text, lambda path: pathlib.PurePath(path).name == "normals.cpp")
        self.assertTrue(lines[0].startswith("normals.cpp:10:24: error: static assertion failed"), lines)
        note = compile_errors.not_compiling_note("normals.cpp", ["2.3"], lines, "The compiler's first errors:\n" + text)
        self.assertTrue(note.startswith("normals.cpp does not compile, so it is graded as the released skeleton's "
                                        "normals.cpp: exercise 2.3 scores 0, the other exercises are graded.\n"
                                        "normals.cpp:10:24: error:"), note)
        self.assertLess(note.index("hint: "), note.index("The compiler's first errors:"))

    def test_a_builds_errors_by_file(self):
        from springlab_grader import compile_errors  # noqa: PLC0415
        text = GCC_EIGEN_PRODUCT.replace("\\\n", "") + "framework/labs/net/src/net.cpp:3:1: error: 'x' was not declared\n"
        self.assertEqual([path for path, _ in compile_errors.files_with_errors(text)],
                         ["framework/labs/net/src/net.cpp"])  # Eigen's own headers are not the student's

    def test_no_error_no_summary(self):
        from springlab_grader import compile_errors  # noqa: PLC0415
        self.assertEqual(compile_errors.summary("x.cpp:1:1: warning: unused\n", lambda p: True), [])


class FailedChecksReadAsSentences(unittest.TestCase):
    def test_each_kind_of_assertion(self):
        from springlab_grader.failures import sentences  # noqa: PLC0415
        cases = [
            ("Expected equality of these values:\n  normals.size()\n    Which is: 0\n  net.pos.size()\n"
             "    Which is: 16\none normal per mass",
             ["expected: normals.size() equal to net.pos.size()", "came:     normals.size() = 0, net.pos.size() = 16",
              "check:    one normal per mass"]),
            ("Expected: (err) < (1e-12), actual: 1.4142135623730951 vs 1e-12\nunit normals",
             ["expected: err below 1e-12", "came:     err = 1.41421", "check:    unit normals"]),
            ("The difference between total and surface is 0.25, which exceeds 1e-12, where\ntotal evaluates to 1.25,\n"
             "surface evaluates to 1, and\n1e-12 evaluates to 9.9999999999999998e-13.\na third of each area",
             ["expected: total within 1e-12 of surface = 1", "came:     total = 1.25 (a difference of 0.25)",
              "check:    a third of each area"]),
            ("Value of: std::isfinite(x)\n  Actual: false\nExpected: true\nstays finite",
             ["expected: std::isfinite(x) to be true", "came:     false", "check:    stays finite"]),
            ('C++ exception with description "index 7 out of range" thrown in the test body.',
             ["expected: no exception", "came:     an exception: index 7 out of range"]),
            ('C++ exception with description "not implemented: exercise 2.3" thrown in the test body.',
             ["not implemented: exercise 2.3"]),
        ]
        for raw, said in cases:
            with self.subTest(raw.splitlines()[0]):
                self.assertEqual(sentences(raw).splitlines(), said)
                verbose = sentences(raw, raw=True)
                self.assertIn("GoogleTest: " + raw.splitlines()[0], verbose)

    def test_a_repeated_failure_is_said_once_and_unknown_text_kept(self):
        from springlab_grader.failures import sentences  # noqa: PLC0415
        one = "Expected: (e) < (0.1), actual: 2 vs 0.1\nsmall"
        self.assertEqual(sentences(one + "\n" + one).splitlines()[1], "came:     e = 2 (2 times)")
        self.assertEqual(sentences("the rope sags by 3 cm"), "the rope sags by 3 cm")


if __name__ == "__main__":
    unittest.main()
