// main() of a judge: the grading program of one exercise file that holds no student code. Its
// copies of that file's exercise functions replay what the student's functions did in the
// worker (call_trace.hpp); the checks, the reference "oracle" and the verdict are its own.
//   --springlab-report=PATH  where the outcome of each test goes, as one JSON object
//                            {"tests": [...], "trace_calls": N} (test_outcomes.hpp)
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "call_trace.hpp"
#include "test_outcomes.hpp"

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  std::string report;
  for (int i = 1; i < argc; ++i) {
    constexpr const char* kFlag = "--springlab-report=";
    if (std::strncmp(argv[i], kFlag, std::strlen(kFlag)) == 0) report = argv[i] + std::strlen(kFlag);
  }
  springlab::trace::Reader::instance();  // takes the trace's descriptor before any test runs
  const int code = RUN_ALL_TESTS();
  if (!report.empty()) {
    std::ofstream out(report);
    out << nlohmann::json{{"tests", springlab::testing::testOutcomes()},
                          {"trace_calls", springlab::trace::Reader::instance().calls()}}.dump()
        << "\n";
    if (!out) {
      std::fprintf(stderr, "judge: cannot write %s\n", report.c_str());
      return 2;
    }
  }
  return code;
}
