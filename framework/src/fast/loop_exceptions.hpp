#pragma once
// An exception must not leave the body of an OpenMP loop: the runtime would call
// std::terminate (SIGABRT) instead of letting it reach the caller. A student's missing
// exercise (NotImplemented) or a bad value thrown inside a parallel loop would then abort
// the viewer or a test instead of being reported. Each iteration runs through run(), which
// keeps the first exception (or a catch block around a thread's whole share calls
// capture()); rethrow() after the loop throws it on the calling thread. The first thread to
// fail keeps its exception; the others are dropped.
#include <atomic>
#include <exception>

namespace springlab {

class LoopExceptions {
 public:
  // Run one iteration; once an iteration has thrown, the rest are skipped.
  template <class Body>
  void run(Body&& body) noexcept {
    if (thrown_.load(std::memory_order_relaxed)) return;
    try {
      body();
    } catch (...) {
      capture();
    }
  }
  // Keep the exception being handled (call inside a catch block that wraps a whole loop).
  void capture() noexcept {
    if (!thrown_.exchange(true)) first_ = std::current_exception();
  }
  // Throw the kept exception, if any (call after the loop, outside the parallel region).
  void rethrow() {
    if (thrown_.load()) std::rethrow_exception(first_);
  }

 private:
  std::atomic<bool> thrown_{false};
  std::exception_ptr first_;
};

}  // namespace springlab
