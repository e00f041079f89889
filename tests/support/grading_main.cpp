// main() of the whole-lab grading programs ctest builds (<lab>_grading_reference and
// <lab>_grading_student) and `check` runs. Run by hand or by ctest (its tests listed with
// --gtest_list_tests, each run with --gtest_filter) it is GoogleTest's usual main.
//
// Run by tools/grade.py (`check`), it is launched exactly as `grade` launches a worker
// (launch.hpp, tools/springlab_grader/judged_run.py launch_worker): the same command line and
// environment, the test to run as one line on standard input, and the grader's channel in
// SPRINGLAB_CALL_TRACE_FD. There a worker writes its call trace; this main writes, once every
// test has returned, one JSON object {"tests": [{"name", "status", "failures"}]} and closes it.
// So printed test output and exit codes do not count, and a test that never returns (exit()
// inside an exercise) reports nothing. That channel runs in the process of the code under
// test, so it is no defence against hostile code: `check` is the student's own tool, and
// submissions are graded by a judge that runs none of their code (judge_main.cpp).
#include <gtest/gtest.h>

#ifdef _WIN32
// Windows (the MinGW-w64 build of `./springlab portability mingw`): the grader is Linux-only
// (pipes, bubblewrap), so there this is GoogleTest's usual main.
int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
#else
#include <unistd.h>

#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>

#include "launch.hpp"
#include "test_outcomes.hpp"

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  // Take the channel before any test runs, and leave no trace of it in the environment.
  const int channel = springlab::launch::channelFromEnvironment();
  if (channel < 0) return RUN_ALL_TESTS();
  ::unsetenv("SPRINGLAB_CALL_TRACE_FD");
  if (!springlab::launch::runOnlyTheTestOnStandardInput("grading program")) return 2;

  const int code = RUN_ALL_TESTS();

  // Report only after every test has returned: a test that never returns reports nothing.
  const std::string report = nlohmann::json{{"tests", springlab::testing::testOutcomes()}}.dump() + "\n";
  std::size_t written = 0;
  while (written < report.size()) {
    const ssize_t n = ::write(channel, report.data() + written, report.size() - written);
    if (n <= 0) break;
    written += static_cast<std::size_t>(n);
  }
  ::close(channel);
  return code;
}
#endif  // _WIN32
