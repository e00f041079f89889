// main() of every grading suite. Run by hand or by ctest it is GoogleTest's usual main. Run
// by the grader (tools/grade.py), it also reports each test's outcome on a channel the
// grader trusts instead of the program's output or exit code, which student code controls:
//   SPRINGLAB_RESULT_CHANNEL=IN:OUT  two pipe file descriptors;
//   IN   carries a secret nonce from the grader, read here once, before any test runs;
//   OUT  receives one JSON line {"nonce", "tests": [{"name", "status", "failures"}]}.
// A test that crashes, hangs, calls exit() or prints fake GoogleTest output never writes a
// line with the nonce, and the grader scores it 0.
#include <gtest/gtest.h>

#ifdef _WIN32
// Windows (the MinGW-w64 build of `./springlab portability mingw`): the grader and its result
// channel are Linux-only (pipes, unsetenv), so there this is GoogleTest's usual main.
int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
#else
#include <unistd.h>

#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>

namespace {

// Caps keep the report line small enough for a pipe's buffer.
constexpr std::size_t kMaxFailures = 5;
constexpr std::size_t kMaxMessage = 2000;

// The nonce: 64 hex characters from the IN descriptor, which is then closed.
std::string readNonce(int fd) {
  std::string nonce;
  char buffer[64];
  while (nonce.size() < sizeof(buffer)) {
    const ssize_t got = ::read(fd, buffer, sizeof(buffer) - nonce.size());
    if (got <= 0) break;
    nonce.append(buffer, static_cast<std::size_t>(got));
  }
  ::close(fd);
  return nonce;
}

// Every test that ran: its full name, passed / failed / skipped, its first failure messages.
nlohmann::json outcomes() {
  nlohmann::json tests = nlohmann::json::array();
  const testing::UnitTest& unit = *testing::UnitTest::GetInstance();
  for (int s = 0; s < unit.total_test_suite_count(); ++s) {
    const testing::TestSuite& suite = *unit.GetTestSuite(s);
    for (int t = 0; t < suite.total_test_count(); ++t) {
      const testing::TestInfo& info = *suite.GetTestInfo(t);
      if (!info.should_run()) continue;
      const testing::TestResult& result = *info.result();
      nlohmann::json failures = nlohmann::json::array();
      for (int p = 0; p < result.total_part_count() && failures.size() < kMaxFailures; ++p) {
        const testing::TestPartResult& part = result.GetTestPartResult(p);
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

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  const char* channel = std::getenv("SPRINGLAB_RESULT_CHANNEL");
  if (channel == nullptr) return RUN_ALL_TESTS();

  // Take the nonce before any test runs, and leave no trace of the channel in the environment.
  const std::string spec = channel;
  const auto colon = spec.find(':');
  const int in = std::atoi(spec.substr(0, colon).c_str());
  const int out = colon == std::string::npos ? -1 : std::atoi(spec.substr(colon + 1).c_str());
  ::unsetenv("SPRINGLAB_RESULT_CHANNEL");
  const std::string nonce = readNonce(in);

  const int code = RUN_ALL_TESTS();

  // Report only after every test has returned: a test that never returns reports nothing.
  const std::string line = nlohmann::json{{"nonce", nonce}, {"tests", outcomes()}}.dump() + "\n";
  std::size_t written = 0;
  while (written < line.size()) {
    const ssize_t n = ::write(out, line.data() + written, line.size() - written);
    if (n <= 0) break;
    written += static_cast<std::size_t>(n);
  }
  ::close(out);
  return code;
}
#endif  // _WIN32
