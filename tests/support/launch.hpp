#pragma once
// How the grader starts every program that runs student code (tools/springlab_grader/
// judged_run.py launch_worker): a `grade` worker (worker_main.cpp) and a `check` test process
// (grading_main.cpp) alike. The command line is the same for every test (GoogleTest's colour
// only); the test to run comes as one line on standard input, read here before any test
// starts; the channel back to the grader is the descriptor in SPRINGLAB_CALL_TRACE_FD.
#include <gtest/gtest.h>

#include <cstdlib>
#include <iostream>
#include <string>

namespace springlab::launch {

// The channel's descriptor named by SPRINGLAB_CALL_TRACE_FD, or -1 when the program was not
// launched by the grader (run by hand, by ctest, or listing its tests).
inline int channelFromEnvironment() {
  const char* text = std::getenv("SPRINGLAB_CALL_TRACE_FD");
  if (text == nullptr || *text == '\0') return -1;
  char* end = nullptr;
  const long fd = std::strtol(text, &end, 10);
  return (*end == '\0' && fd >= 0 && fd < 1024) ? static_cast<int>(fd) : -1;
}

// Run only the test named on standard input; false (with a message) when none is named.
inline bool runOnlyTheTestOnStandardInput(const char* program) {
  std::string test;
  if (!std::getline(std::cin, test) || test.empty()) {
    std::cerr << program << ": expected the name of one test on standard input\n";
    return false;
  }
  GTEST_FLAG_SET(filter, test);
  return true;
}

}  // namespace springlab::launch
