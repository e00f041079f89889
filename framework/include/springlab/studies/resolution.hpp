#pragma once
// Model no more than the scene needs. The resolution study runs the same physical object
// (Registry::atResolution) at increasing resolutions and compares an observable's history
// with the finest one's; the advisor then finds, at the coarsest resolution that is good
// enough, the integrator and dt that meet the tolerance with the fewest force evaluations.
//
// Errors are relative: the largest difference over the run's samples divided by the largest
// magnitude of the finest (or reference) history. Costs are counted, not timed (force
// evaluations x masses), so the answers are the same on every run; wall times are reported.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "springlab/studies/progress.hpp"
#include "springlab/studies/run.hpp"

namespace springlab::studies {

struct ResolutionOptions {
  std::string observable;        // empty: the scene's first observable
  double tolerance = 0.01;       // relative
  double duration = 2.0;         // s
  int samples = 40;
  std::vector<int> resolutions;  // empty: the scene's value x 2^-3 .. x 2^finerSteps
  int finerSteps = 1;            // doublings above the scene's value (advise: 0)
  std::string integrator;        // empty: the scene's
  int repeats = 3;               // timed runs after the first (the median wall time is reported)
  int threads = 0;
  bool progress = true;
  RunProgress* runProgress = nullptr;  // a line per finished run (advise's), when given
};

struct ResolutionRow {
  int resolution = 0;
  int masses = 0;
  double dt = 0.0;              // s: the scene's w_max dt kept at every resolution
  bool stable = true;
  long forceEvaluations = 0;
  double cost = 0.0;            // force evaluations x masses
  double wallSeconds = 0.0;     // median of the timed runs
  double error = 0.0;           // relative, against the finest
  std::vector<double> series;   // the observable at each sample
};

struct ResolutionStudy {
  std::string scene;
  std::string observable;
  std::string unit;
  std::string integrator;
  double tolerance = 0.0;
  std::vector<double> times;    // sample times, s
  std::vector<ResolutionRow> rows;  // coarse to fine
  int chosen = -1;              // index of the coarsest row within tolerance (it and every finer one)
};

ResolutionStudy resolutionStudy(const Registry& registry, const SceneDocument& scene, const ResolutionOptions& options);

// Relative difference of two histories: max |a - b| / max |b|.
double relativeError(const std::vector<double>& a, const std::vector<double>& b);

struct AdviseOptions {
  double tolerance = 0.01;  // relative, on the observable; half for resolution, half for time stepping
  std::string observable;   // empty: the scene's first observable
  double duration = 2.0;
  int samples = 40;
  std::vector<std::string> integrators;  // empty: every registered one
  std::vector<int> resolutions;
  int levels = 4;           // dt values tried per integrator, halving from about RK4's limit
                            // (methods stable at any dt start at the frame length); the RK4
                            // reference halves from half that limit until it converges
  int threads = 0;
  bool progress = true;
};

struct Candidate {
  std::string integrator;
  double dt = 0.0;             // s, the largest that met the tolerance; 0: none did
  double error = 0.0;          // at dt; when no dt met the tolerance, at the finest dt tried
  double evaluationsPerSecond = 0.0;  // force evaluations per simulated second
  std::string note;            // why it has no dt, or a missing exercise
};

struct Advice {
  ResolutionStudy resolution;
  int chosenResolution = 0;
  std::vector<Candidate> candidates;
  int best = -1;               // index into candidates
  double referenceDt = 0.0;    // s, the converged RK4 reference's step
  nlohmann::json snippet;      // the keys to paste into the scene
};

Advice advise(const Registry& registry, const SceneDocument& scene, const AdviseOptions& options);

void writeCsv(const ResolutionStudy& study, const std::string& summaryPath, const std::string& seriesPath);

}  // namespace springlab::studies
