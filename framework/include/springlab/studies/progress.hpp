#pragma once
// Progress of a long study (advise) on stderr: a line per finished run saying which run it
// was, how many are left at most, the time so far and an estimate of the time left. The
// estimate scales the time so far by the work left over the work done, a run's work being its
// steps times its masses (what a force pass costs), so a fine resolution counts for more than
// a coarse one. Runs may finish on several threads at once.
#include <chrono>
#include <mutex>
#include <string>

namespace springlab::studies {

class RunProgress {
 public:
  // label starts each line ("advise"); nothing is printed when !enabled.
  RunProgress(std::string label, bool enabled);

  // Runs still to come and their work (steps x masses).
  void plan(int runs, double work);
  // A run is done: one line, "advise: run 7 of at most 23 (what) done after 12 s; about 30 s left".
  void finished(const std::string& what, double work);
  // Planned runs that will not run (a dt ladder that stopped at its first good rung).
  void dropped(int runs, double work);

 private:
  std::string label_;
  bool enabled_;
  std::chrono::steady_clock::time_point start_;
  std::mutex mutex_;
  int planned_ = 0, done_ = 0;
  double workPlanned_ = 0.0, workDone_ = 0.0;
};

}  // namespace springlab::studies
