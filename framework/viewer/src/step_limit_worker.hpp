#pragma once
// The viewer's dt warning needs the stability limit of the step that runs (stepStableDt):
// the largest dt at which the scene's own step, dampers, contacts and pressure included, does
// not grow. Computing it takes up to seconds (the 64 x 64 cloth) and resets the simulation it
// runs on, so it runs on a copy of the scene, on a thread of its own; the viewer asks for the
// result each frame. The browser's build has no threads: there it computes nothing (no
// warning), since the page would freeze for as long as the computation takes.
#include <atomic>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "springlab/simulation.hpp"

namespace springlab::viewer {

class StepLimitWorker {
 public:
  StepLimitWorker() = default;
  StepLimitWorker(const StepLimitWorker&) = delete;
  StepLimitWorker& operator=(const StepLimitWorker&) = delete;
  ~StepLimitWorker();  // cancels a computation under way and waits for it to stop

  // Computes the limit of `copy`'s integrator on `copy`'s scene (the worker owns the copy),
  // cancelling the computation under way, whose result is then never reported.
  void start(std::unique_ptr<Simulation> copy);
  // s: the limit once computed (+inf: none, 0: no stable dt); nullopt while computing, before
  // any start, or when the computation failed (a missing exercise, a broken scene).
  std::optional<double> limit() const;
  bool computing() const;
  // Waits up to `seconds` for the computation under way (the last frame of a --frames run,
  // whose snapshot shows the warning).
  void wait(double seconds);

 private:
  void stop();

  std::thread thread_;
  std::atomic<bool> cancel_{false};
  mutable std::mutex mutex_;  // guards the three below
  bool computing_ = false;
  std::optional<double> limit_;
  std::unique_ptr<Simulation> copy_;
};

}  // namespace springlab::viewer
