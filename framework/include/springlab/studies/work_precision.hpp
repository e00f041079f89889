#pragma once
// Work-precision: for each integrator, a sweep of dt; for each run the error (at the final
// time, and the largest over the run) against a reference run, and the cost (force
// evaluations, and wall time: a warm-up, then the median of several timed runs). The
// reference is RK4 at a step 8 times smaller than the smallest in the sweep. Unstable runs
// are kept and flagged. The dt values are the sample interval over powers of two, so every
// run samples at exactly the same times.
#include <string>
#include <vector>

#include "springlab/studies/run.hpp"

namespace springlab::studies {

struct WorkPrecisionOptions {
  std::vector<std::string> integrators;  // empty: every registered integrator
  double duration = 1.0;      // s of simulated time
  int samples = 20;           // error samples over the run
  int levels = 9;             // dt values per integrator, each half the previous
  double largestDt = 0.0;     // s; 0: about twice the largest predicted stable dt (RK4's)
  int repeats = 3;            // timed runs after the warm-up; the median is reported
  int threads = 0;            // 0: all cores
  bool progress = true;
};

struct WorkPrecisionPoint {
  std::string integrator;
  double dt = 0.0;            // s
  bool stable = true;
  long steps = 0;
  long forceEvaluations = 0;
  double wallSeconds = 0.0;   // median of the timed runs
  double finalError = 0.0;    // m, largest over masses at the last sample
  double maxError = 0.0;      // m, largest over masses and samples
};

struct WorkPrecision {
  std::string scene;
  double duration = 0.0;
  double referenceDt = 0.0;
  double maxAngularFrequency = 0.0;  // rad/s, Lanczos estimate at the start
  std::vector<WorkPrecisionPoint> points;
  std::vector<std::string> skipped;  // "integrator: why" (an exercise not written yet)
};

WorkPrecision workPrecision(const Registry& registry, const SceneDocument& scene, const WorkPrecisionOptions& options);

void writeCsv(const WorkPrecision& study, const std::string& path);

}  // namespace springlab::studies
