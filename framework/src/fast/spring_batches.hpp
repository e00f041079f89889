#pragma once
// Springs split for two or more threads without locks and with results that do not depend
// on the thread count. A grid's springs are listed in the order of their lower mass index;
// cut that list into batches of B consecutive lower indices, B at least the largest index
// distance a spring spans. Then batch b touches masses [b B, (b + 2) B) only, so batches two
// apart share no mass: all even batches run at once, then all odd ones. Every mass receives
// its springs' forces in the same order however many threads run, so sums are bitwise equal.
// A list in any other order gets a single batch (a serial loop), which is still correct.
#include <array>
#include <vector>

#include "fast/loop_exceptions.hpp"
#include "fast/thread_budget.hpp"
#include "springlab/spring.hpp"

namespace springlab {

// Below these sizes a loop is too short to pay for waking a second thread; every parallel
// loop of the framework and the labs uses them.
inline constexpr int kParallelMasses = 4096;
inline constexpr int kParallelSprings = 8192;

class SpringBatches {
 public:
  SpringBatches() = default;
  // Batches for `springs`, each at least `minimumSpan` lower indices wide.
  explicit SpringBatches(const std::vector<Spring>& springs, int minimumSpan = 64);
  // The same for any list of index pairs (a Jacobian's pairs, say).
  explicit SpringBatches(const std::vector<std::array<int, 2>>& ends, int minimumSpan = 64);

  int count() const { return static_cast<int>(begin_.size()) - 1; }
  // Springs [begin(b), end(b)) form batch b.
  int begin(int b) const { return begin_[static_cast<std::size_t>(b)]; }
  int end(int b) const { return begin_[static_cast<std::size_t>(b) + 1]; }
  // Whether these batches were made for a list of this many springs.
  bool fits(std::size_t springs) const { return static_cast<std::size_t>(begin_.back()) == springs; }

  // perBatch(first, last) for the springs [first, last) of every batch: even batches in
  // parallel, then odd ones. perBatch may add to both ends' entries of per-mass arrays.
  template <class PerBatch>
  void forEachBatch(PerBatch&& perBatch) const {
    const int batches = count();
    // perBatch calls exercises, which may throw: carried out of the parallel region.
    LoopExceptions exceptions;
    // Fewer threads, down to a serial loop, while other processes keep the cores busy.
    const int threads = parallel_ ? threadBudget() : 1;
    for (int parity = 0; parity < 2; ++parity) {
#pragma omp parallel for schedule(static) if (threads > 1) num_threads(threads)
      for (int b = parity; b < batches; b += 2) exceptions.run([&] { perBatch(begin(b), end(b)); });
      exceptions.rethrow();
    }
  }

 private:
  std::vector<int> begin_{0};  // [batches + 1]
  bool parallel_ = false;  // threads: more than two batches and at least kParallelSprings springs
};

}  // namespace springlab
