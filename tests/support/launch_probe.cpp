// A test that records what its process sees, for tests/grading/launch_probe.py: linked once
// with a worker's main (worker_main.cpp) and once with the check's (grading_main.cpp), it must
// see the same whether `grade` or `check` launched it (judged_run.py launch_worker). It fails
// on purpose: the failure message ("LAUNCH-VIEW {json}") carries what it saw to the grader.
#include <dirent.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <climits>
#include <fstream>
#include <iostream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace {

// The NUL-separated strings of a /proc file (the command line, the environment at exec).
std::vector<std::string> procStrings(const char* path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<std::string> parts;
  std::string part;
  while (std::getline(in, part, '\0')) parts.push_back(part);
  return parts;
}

// Each open descriptor and what kind of thing it is (the kind, not the inode or the path,
// which differ from run to run).
nlohmann::json openDescriptors() {
  nlohmann::json open = nlohmann::json::object();
  DIR* dir = ::opendir("/proc/self/fd");
  if (dir == nullptr) return open;
  while (const dirent* entry = ::readdir(dir)) {
    const std::string name = entry->d_name;
    if (name == "." || name == ".." || std::stoi(name) == ::dirfd(dir)) continue;
    char target[PATH_MAX] = {};
    const ssize_t n = ::readlink(("/proc/self/fd/" + name).c_str(), target, sizeof(target) - 1);
    const std::string link(target, n > 0 ? static_cast<std::size_t>(n) : 0);
    open[name] = link.rfind("pipe:", 0) == 0 ? "pipe" : link == "/dev/null" ? "/dev/null" : "file";
  }
  ::closedir(dir);
  return open;
}

nlohmann::json limit(int which) {
  rlimit value{};
  ::getrlimit(which, &value);
  return {value.rlim_cur == RLIM_INFINITY ? -1.0 : static_cast<double>(value.rlim_cur),
          value.rlim_max == RLIM_INFINITY ? -1.0 : static_cast<double>(value.rlim_max)};
}

}  // namespace

TEST(LaunchProbe, RecordsWhatItsProcessSees) {
  char cwd[PATH_MAX] = {};
  const bool hasCwd = ::getcwd(cwd, sizeof(cwd)) != nullptr;
  // What standard input holds after the test's name (main() read that line).
  const std::string rest((std::istreambuf_iterator<char>(std::cin)), std::istreambuf_iterator<char>());
  const nlohmann::json view = {
      {"argv", procStrings("/proc/self/cmdline")},
      {"environment", procStrings("/proc/self/environ")},
      {"cwd", hasCwd ? std::string(cwd) : std::string("?")},
      {"stdin_after_the_name", rest},
      {"uid", ::getuid()},
      {"gid", ::getgid()},
      {"pid", ::getpid() <= 2 ? nlohmann::json(::getpid()) : nlohmann::json("outside a PID namespace")},
      {"descriptors", openDescriptors()},
      {"limits", {{"cpu", limit(RLIMIT_CPU)}, {"address_space", limit(RLIMIT_AS)}, {"files", limit(RLIMIT_NOFILE)},
                  {"stack", limit(RLIMIT_STACK)}, {"file_size", limit(RLIMIT_FSIZE)}}},
  };
  ADD_FAILURE() << "LAUNCH-VIEW " << view.dump();
}
