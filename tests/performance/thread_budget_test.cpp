// Parallel loops back off while other processes keep the cores busy (thread_budget.hpp).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <thread>
#include <vector>

#ifdef __linux__
#include <sys/wait.h>
#include <unistd.h>
#endif
#ifdef _OPENMP
#include <omp.h>
#endif

#include "fast/thread_budget.hpp"

namespace springlab {
namespace {

TEST(ThreadBudget, NeverMoreThanOpenMPAllowsNorLessThanOne) {
  const int budget = threadBudget();
  EXPECT_GE(budget, 1);
#ifdef _OPENMP
  EXPECT_LE(budget, omp_get_max_threads());
#else
  EXPECT_EQ(budget, 1);
#endif
}

#if defined(__linux__) && defined(_OPENMP)
TEST(ThreadBudget, BacksOffWhileAnotherProcessKeepsEveryCoreBusy) {
  // One busy child process per core: no core is free, so the loops run serially.
  const int cores = omp_get_num_procs();
  std::vector<pid_t> children;
  for (int c = 0; c < cores; ++c) {
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      std::atomic<unsigned long> spin{0};
      for (;;) spin.fetch_add(1, std::memory_order_relaxed);
    }
    children.push_back(child);
  }
  // Past the sampling interval, twice.
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  threadBudget();
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const int budget = threadBudget();
  const int others = otherRunnableTasks();
  for (const pid_t child : children) {
    kill(child, SIGKILL);
    waitpid(child, nullptr, 0);
  }
  EXPECT_GE(others, cores) << "the busy children are runnable tasks of other processes";
  EXPECT_EQ(budget, 1) << "with every core busy elsewhere, a second thread would only wait for its turn";
}
#endif

}  // namespace
}  // namespace springlab
