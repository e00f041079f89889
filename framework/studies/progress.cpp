#include "springlab/studies/progress.hpp"

#include <cmath>
#include <iostream>
#include <sstream>

namespace springlab::studies {

namespace {

// "45 s", "3 min 20 s".
std::string duration(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  std::ostringstream os;
  if (s >= 60) os << s / 60 << " min " << s % 60 << " s";
  else os << s << " s";
  return os.str();
}

}  // namespace

RunProgress::RunProgress(std::string label, bool enabled)
    : label_(std::move(label)), enabled_(enabled), start_(std::chrono::steady_clock::now()) {}

void RunProgress::plan(int runs, double work) {
  std::lock_guard<std::mutex> lock(mutex_);
  planned_ += runs;
  workPlanned_ += work;
}

void RunProgress::dropped(int runs, double work) {
  std::lock_guard<std::mutex> lock(mutex_);
  planned_ -= runs;
  workPlanned_ -= work;
}

void RunProgress::finished(const std::string& what, double work) {
  std::lock_guard<std::mutex> lock(mutex_);
  ++done_;
  workDone_ += work;
  if (!enabled_) return;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const int left = std::max(0, planned_ - done_);
  std::ostringstream line;
  line << label_ << ": run " << done_ << " of at most " << planned_ << " (" << what << ") done after "
       << duration(elapsed);
  if (left > 0 && workDone_ > 0.0) {
    line << "; " << left << " left, about " << duration(elapsed * std::max(0.0, workPlanned_ - workDone_) / workDone_)
         << " at most";
  }
  std::cerr << line.str() << std::endl;
}

}  // namespace springlab::studies
