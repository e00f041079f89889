#include "step_limit_worker.hpp"

#include <chrono>
#include <exception>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "springlab/step_stability.hpp"

namespace springlab::viewer {

namespace {

// The limit, or nullopt when it cannot be computed (the copy's step throws: a missing
// exercise) or the computation was cancelled.
std::optional<double> computeLimit(Simulation& sim, const std::atomic<bool>& cancel) {
  StepStabilityOptions options;
  options.cancelled = [&cancel] { return cancel.load(); };
  try {
    return stepStableDt(sim, options);
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

}  // namespace

StepLimitWorker::~StepLimitWorker() { stop(); }

void StepLimitWorker::stop() {
  cancel_ = true;
  if (thread_.joinable()) thread_.join();
  cancel_ = false;
}

void StepLimitWorker::start(std::unique_ptr<Simulation> copy) {
  stop();
  std::lock_guard<std::mutex> lock(mutex_);
  limit_.reset();
  copy_ = std::move(copy);
  if (!copy_) return;
#ifdef __EMSCRIPTEN__
  // The page's build has no threads, and computed here the limit would freeze the page for
  // seconds (the 64 x 64 cloth with implicit Euler: 13 s natively): the browser shows no dt
  // warning until the limit can be computed in slices between frames.
  copy_.reset();
#else
  computing_ = true;
  thread_ = std::thread([this] {
#ifdef _OPENMP
    // One thread: the physics the user watches keeps the others.
    omp_set_num_threads(1);
#endif
    const std::optional<double> result = computeLimit(*copy_, cancel_);
    std::lock_guard<std::mutex> done(mutex_);
    if (!cancel_) limit_ = result;
    computing_ = false;
  });
#endif
}

std::optional<double> StepLimitWorker::limit() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return limit_;
}

bool StepLimitWorker::computing() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return computing_;
}

void StepLimitWorker::wait(double seconds) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (computing() && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

}  // namespace springlab::viewer
