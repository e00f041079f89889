// main() of the whole-lab grading programs ctest builds (<lab>_grading_reference and
// <lab>_grading_student) and `check` runs. Run by hand or by ctest it is GoogleTest's usual
// main. Run by tools/grade.py --binary, it also reports each test's outcome on a private
// channel, so that exit codes and printed test output do not count:
//   SPRINGLAB_RESULT_CHANNEL=IN:OUT  two pipe file descriptors;
//   IN   carries a nonce from the grader, read here once, before any test runs;
//   OUT  receives one JSON line {"nonce", "tests": [{"name", "status", "failures"}]}.
// That channel runs in the process of the code under test, so it is no defence against
// hostile code: submissions are graded by a judge that runs none of their code
// (judge_main.cpp and worker_main.cpp).
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

#include "test_outcomes.hpp"

namespace {

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
  const std::string line = nlohmann::json{{"nonce", nonce}, {"tests", springlab::testing::testOutcomes()}}.dump() + "\n";
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
