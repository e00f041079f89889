// The grader's view of a finished GoogleTest run (see test_outcomes.hpp).
#include "test_outcomes.hpp"

#include <gtest/gtest.h>

#include <string>

namespace springlab::testing {
namespace {
// Caps keep a report small (it may travel through a pipe's buffer).
constexpr std::size_t kMaxFailures = 5;
constexpr std::size_t kMaxMessage = 2000;
}  // namespace

nlohmann::json testOutcomes() {
  nlohmann::json tests = nlohmann::json::array();
  const ::testing::UnitTest& unit = *::testing::UnitTest::GetInstance();
  for (int s = 0; s < unit.total_test_suite_count(); ++s) {
    const ::testing::TestSuite& suite = *unit.GetTestSuite(s);
    for (int t = 0; t < suite.total_test_count(); ++t) {
      const ::testing::TestInfo& info = *suite.GetTestInfo(t);
      if (!info.should_run()) continue;
      const ::testing::TestResult& result = *info.result();
      nlohmann::json failures = nlohmann::json::array();
      for (int p = 0; p < result.total_part_count() && failures.size() < kMaxFailures; ++p) {
        const ::testing::TestPartResult& part = result.GetTestPartResult(p);
        if (part.failed()) failures.push_back(std::string(part.message()).substr(0, kMaxMessage));
      }
      const char* status = result.Failed() ? "failed" : result.Skipped() ? "skipped" : "passed";
      tests.push_back({{"name", std::string(suite.name()) + "." + info.name()},
                       {"status", status},
                       {"failures", failures}});
    }
  }
  return tests;
}

}  // namespace springlab::testing
