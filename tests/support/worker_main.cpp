// main() of a worker: the grading program that runs a test with a student's exercise file,
// in the grader's sandbox. Its verdict counts for nothing: it only writes the call trace
// (call_trace.hpp) of the student's functions, from which the judge (judge_main.cpp), a
// process without student code, decides.
#include <gtest/gtest.h>

#include "call_trace.hpp"

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  springlab::trace::Writer::instance();  // takes the trace's descriptor before any test runs
  const int code = RUN_ALL_TESTS();
  springlab::trace::Writer::instance().flush();
  return code;
}
