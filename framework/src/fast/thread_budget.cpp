// Thread counts that back off on a loaded machine (see thread_budget.hpp).
#include "fast/thread_budget.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>

#ifdef __linux__
#include <dirent.h>
#include <fcntl.h>
#include <unistd.h>
#endif

#ifdef _OPENMP
#include <omp.h>
#endif

namespace springlab {

namespace {

#ifdef __linux__
// A small file of /proc into buf (no allocation: steps must not allocate); length or -1.
int readSmallFile(const char* path, char* buf, int size) {
  const int fd = ::open(path, O_RDONLY | O_CLOEXEC);
  if (fd < 0) return -1;
  const ssize_t got = ::read(fd, buf, static_cast<std::size_t>(size - 1));
  ::close(fd);
  if (got < 0) return -1;
  buf[got] = '\0';
  return static_cast<int>(got);
}

// Runnable tasks on the machine: the fourth field of /proc/loadavg is "runnable/total".
int machineRunnable() {
  char buf[128];
  if (readSmallFile("/proc/loadavg", buf, sizeof buf) < 0) return -1;
  double a = 0, b = 0, c = 0;
  int runnable = -1;
  if (std::sscanf(buf, "%lf %lf %lf %d/", &a, &b, &c, &runnable) != 4) return -1;
  return runnable;
}

// This process's runnable threads (state R in /proc/self/task/*/stat): its own spinning
// OpenMP workers are not other work.
int ownRunnable() {
  DIR* dir = ::opendir("/proc/self/task");
  if (dir == nullptr) return -1;
  int count = 0;
  while (const dirent* entry = ::readdir(dir)) {
    if (entry->d_name[0] == '.') continue;
    char path[300], buf[512];
    std::snprintf(path, sizeof path, "/proc/self/task/%s/stat", entry->d_name);
    if (readSmallFile(path, buf, sizeof buf) < 0) continue;
    // "tid (name) S ...": the state follows the last ')'.
    const char* close = std::strrchr(buf, ')');
    if (close != nullptr && close[1] == ' ' && close[2] == 'R') ++count;
  }
  ::closedir(dir);
  return count;
}
#else
int machineRunnable() { return -1; }
int ownRunnable() { return -1; }
#endif

std::atomic<int> lastOthers{-1};

}  // namespace

int otherRunnableTasks() { return lastOthers.load(); }

int threadBudget() {
#ifdef _OPENMP
  using Clock = std::chrono::steady_clock;
  constexpr auto kSampleEvery = std::chrono::milliseconds(20);
  constexpr int kSamplesToGrow = 10;  // 0.2 s of free cores before threads come back

  const int wanted = omp_get_max_threads();
  if (wanted <= 1) return 1;
  static Clock::time_point lastSample{};
  static int budget = wanted;
  static int freeSamples = 0;  // consecutive samples that allowed more than `budget`
  static bool unknown = false;  // no /proc: trust OpenMP's count
  if (unknown) return wanted;

  const Clock::time_point now = Clock::now();
  if (now - lastSample < kSampleEvery) return std::min(budget, wanted);
  lastSample = now;

  // The cores the others leave free; this thread is one of the process's runnable threads.
  const int all = machineRunnable(), own = ownRunnable();
  if (all < 0 || own < 0) {
    unknown = true;
    return wanted;
  }
  const int others = std::max(0, all - own);
  lastOthers.store(others);
  const int allowed = std::clamp(omp_get_num_procs() - others, 1, wanted);

  // Down at once, up only after a while.
  if (allowed < budget) {
    budget = allowed;
    freeSamples = 0;
  } else if (allowed > budget && ++freeSamples >= kSamplesToGrow) {
    budget = allowed;
    freeSamples = 0;
  }
  return std::min(budget, wanted);
#else
  return 1;
#endif
}

}  // namespace springlab
