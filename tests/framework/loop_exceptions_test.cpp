// An exception thrown inside a parallel loop (a student's missing exercise) must reach the
// caller as that exception: OpenMP would otherwise call std::terminate and abort the process.
#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <vector>

#include "fast/loop_exceptions.hpp"
#include <springlab/not_implemented.hpp>
#include "fast/spring_batches.hpp"

namespace springlab {
namespace {

TEST(LoopExceptions, ExceptionInAParallelLoopReachesTheCaller) {
  const int n = 20000;
  LoopExceptions exceptions;
  std::atomic<int> ran{0};
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    exceptions.run([&] {
      ran.fetch_add(1, std::memory_order_relaxed);
      if (i == n / 2) throw NotImplemented("9.9", "a missing exercise", "handouts/x.md");
    });
  }
  try {
    exceptions.rethrow();
    FAIL() << "the exception thrown in the loop was lost";
  } catch (const NotImplemented& e) {
    EXPECT_EQ(e.exerciseId(), "9.9") << "another exception than the one thrown reached the caller";
  }
  EXPECT_GT(ran.load(), 0);
}

TEST(LoopExceptions, NothingThrownMeansNothingRethrown) {
  LoopExceptions exceptions;
  int sum = 0;
  for (int i = 0; i < 10; ++i) exceptions.run([&] { sum += i; });
  EXPECT_NO_THROW(exceptions.rethrow());
  EXPECT_EQ(sum, 45);
}

TEST(SpringBatches, ExceptionInABatchReachesTheCaller) {
  // Enough springs for the batches to run on threads where OpenMP is on.
  std::vector<std::array<int, 2>> ends;
  for (int i = 0; i < 40000; ++i) ends.push_back({i, i + 1});
  const SpringBatches batches(ends);
  EXPECT_THROW(batches.forEachBatch([](int first, int last) {
    if (first <= 20000 && 20000 < last) throw NotImplemented("2.2", "spring force", "handouts/02_net.md");
  }),
               NotImplemented);
}

}  // namespace
}  // namespace springlab
