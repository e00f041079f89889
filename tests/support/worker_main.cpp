// main() of a worker: the grading program that runs a test with a student's exercise file,
// in the grader's sandbox. Its verdict counts for nothing: it only writes the call trace
// (call_trace.hpp) of the student's functions, from which the judge (judge_main.cpp), a
// process without student code, decides.
//
// Every worker starts the same way, whatever it runs: no arguments but GoogleTest's colour,
// the same environment. The test to run comes on standard input (one line, the test's full
// name), read before any test starts; so the command line, /proc/self/cmdline and the
// environment say nothing about which test runs.
#include <gtest/gtest.h>

#include <iostream>
#include <string>

#include "call_trace.hpp"

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  std::string test;
  if (!std::getline(std::cin, test) || test.empty()) {
    std::cerr << "worker: expected the name of one test on standard input\n";
    return 2;
  }
  GTEST_FLAG_SET(filter, test);
  springlab::trace::Writer::instance();  // takes the trace's descriptor before any test runs
  const int code = RUN_ALL_TESTS();
  springlab::trace::Writer::instance().flush();
  return code;
}
