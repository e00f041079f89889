#include "springlab/calm_run.hpp"

#include <algorithm>
#include <exception>
#include <utility>
#include <vector>

namespace springlab {

namespace {

// compute() (a stability computation that resets and steps the scene), leaving the run as it
// found it (Simulation::saveRun: the state, the lab's data, the blow-up check's watch); NaN when
// it throws. Called from inside check(): resumeRun puts that very check's members back too.
template <class Compute>
double leavingTheRun(Simulation& sim, Compute compute) {
  const Simulation::SavedRun run = sim.saveRun();
  double value = NAN;
  try {
    value = compute();
  } catch (const std::exception&) {
    value = NAN;
  }
  sim.resumeRun(run);
  return value;
}

// The step's spectral radius at dt linearised at `at`, leaving the run as it found it; NaN when
// it cannot be computed or the step is not smooth there.
double radiusAt(Simulation& sim, const State& at, double dt) {
  StepStabilityOptions o;
  o.at = at;
  return radiusLeavingTheRun(sim, dt, o);
}

}  // namespace

double limitLeavingTheRun(Simulation& sim, const StepStabilityOptions& options) {
  return leavingTheRun(sim, [&] { return stepStableDt(sim, options); });
}

double radiusLeavingTheRun(Simulation& sim, double dt, const StepStabilityOptions& options) {
  return leavingTheRun(sim, [&] { return stepSpectralRadius(sim, dt, options).radius; });
}

double stepLimitAt(Simulation& sim, const State& at) {
  StepStabilityOptions o;
  o.at = at;
  return limitLeavingTheRun(sim, o);
}

CalmRun calmRun(Simulation& sim, double dt, double margin, double from, double until, int samples, int limits) {
  const Simulation::SavedRun run = sim.saveRun();
  const bool checking = sim.blowUpCheckEnabled();
  CalmRun out;
  std::vector<std::pair<double, State>> suspects;  // (radius, NaN where not smooth; state)
  const double calmDt = 0.5 * dt;
  try {
    sim.reset();
    sim.setBlowUpCheck(false);
    for (int k = 1; k <= samples; ++k) {
      const double t = from + (until - from) * k / samples;
      while (sim.state.time < t - 0.5 * calmDt) sim.operate(calmDt);
      if (firstNonFiniteMass(sim.state) >= 0) break;
      ++out.states;
      const double radius = radiusAt(sim, sim.state, dt / margin);
      if (radius <= 1.0) {
        ++out.cleared;
      } else {
        suspects.emplace_back(radius, sim.state);
      }
    }
    // The largest radii first, the states that are not smooth (NaN) last, in time.
    std::stable_sort(suspects.begin(), suspects.end(), [](const auto& a, const auto& b) {
      return !std::isnan(a.first) && (std::isnan(b.first) || a.first > b.first);
    });
    for (std::size_t j = 0; j < suspects.size() && static_cast<int>(j) < limits; ++j) {
      const State& state = suspects[j].second;
      const double limit = stepLimitAt(sim, state);
      if (!(std::isfinite(limit) && limit >= calmDt)) continue;
      if (limit * margin >= dt) {
        ++out.cleared;
      } else if (!(limit >= out.limit)) {
        out.limit = limit;
        out.time = state.time;
      }
    }
  } catch (const std::exception&) {
    // A calm run that cannot go on says what it found so far.
  }
  sim.setBlowUpCheck(checking);
  sim.resumeRun(run);
  return out;
}

}  // namespace springlab
