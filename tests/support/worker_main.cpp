// main() of a worker: the grading program that runs a test with a student's exercise file,
// in the grader's sandbox. Its verdict counts for nothing: it only writes the call trace
// (call_trace.hpp) of the student's functions, from which the judge (judge_main.cpp), a
// process without student code, decides.
//
// Every worker starts the same way, whatever it runs, and the same way as a `check`'s test
// process (launch.hpp): no arguments but GoogleTest's colour, the same environment, the test
// to run on standard input; so the command line, /proc/self/cmdline and the environment say
// nothing about which test runs, or whether it is graded.
#include <gtest/gtest.h>

#include "call_trace.hpp"
#include "launch.hpp"

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  if (!springlab::launch::runOnlyTheTestOnStandardInput("worker")) return 2;
  springlab::trace::Writer::instance();  // takes the trace's descriptor before any test runs
  const int code = RUN_ALL_TESTS();
  springlab::trace::Writer::instance().flush();
  return code;
}
