#include "springlab/studies/stability.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <memory>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "parallel.hpp"
#include "springlab/calm_run.hpp"
#include "springlab/step_stability.hpp"
#include "springlab/studies/rest_check.hpp"

namespace springlab::studies {

namespace {

// Fewest steps of a trial: at a dt near the trial's duration a few steps cannot show a
// growth (projective dynamics with 10 iterations on the 8 x 8 fabric grows past 0.77 s; one
// step of 1 s looks calm, 200 crumple the cloth to 9.5 J from 0 J).
constexpr long kFewestTrialSteps = 200;
constexpr double kTwinOffset = 1e-6;  // the relative dt of a stable trial's twin

// What a series of trials (one bisection, one row of the map) holds its runs to, measured at
// swingDt (half the stability limit; 0: none) when a trial first needs it: the stable run's
// swing over the trials' duration (and the rest before it), and whether the scene rests there,
// which holds a trial past the limit to the rest check; and the step limit its detectors read.
class HalfLimitRuns {
 public:
  HalfLimitRuns(const Registry& registry, const SceneDocument& scene, const std::string& integrator,
                double stiffnessScale, double swingDt, double duration, double restTime = 0.0,
                double restCheckDuration = 0.0)
      : registry_(registry), scene_(scene), integrator_(integrator), stiffnessScale_(stiffnessScale),
        swingDt_(swingDt), duration_(duration), restTime_(restTime),
        restCheckDuration_(restCheckDuration > 0.0 ? restCheckDuration : duration) {}

  // How long the rest check's runs last: the growth's time, from the rest they start at (not
  // the arrival a trial from the start needs first: over 17 s the resting ball's own slow drift,
  // 1.1 /s, separates runs at half the limit 5559 times, and the check would not apply).
  double restCheckDuration() const { return restCheckDuration_; }

  std::shared_ptr<const StableSwing> swing() {
    std::call_once(swingOnce_, [&] {
      if (swingDt_ > 0.0) {
        swing_ = std::make_shared<const StableSwing>(
            measureStableSwing(registry_, scene_, integrator_, stiffnessScale_, swingDt_, restTime_ + duration_));
      }
    });
    return swing_;
  }

  // The scene's step limit, computed once for every trial (RunSpec::knownStepLimit): NaN where
  // it cannot be computed, as the blow-up check itself says then.
  double stepLimit() {
    std::call_once(limitOnce_, [&] {
      try {
        limit_ = sceneStepStableDt(registry_, scene_, integrator_, stiffnessScale_);
      } catch (const std::exception&) {
        limit_ = NAN;
      }
    });
    return limit_;
  }

  // Whether a trial at dt is held to the rest check: only past the step's limit (twice the
  // swing's dt), as detectors 5 and 6, and where the scene rests at half the limit. Below the
  // limit it was tried when the settling stopped a falling body in the air: the ball dropped on
  // its floor, settled in the air (1.78 ms under symplectic Euler), rests on the floor, and held
  // to that rest the chart measured 0.84 times the prediction. The settling now follows a fall
  // to its rest (1.47 ms); the check below the limit has not been tried again.
  bool restCheckApplies(double dt) {
    if (!(swingDt_ > 0.0) || dt <= 2.0 * swingDt_) return false;
    std::call_once(restOnce_, [&] {
      rests_ = studies::restCheckApplies(
          measureRestGrowth(registry_, scene_, integrator_, stiffnessScale_, swingDt_, restCheckDuration_));
    });
    return rests_;
  }

 private:
  const Registry& registry_;
  const SceneDocument& scene_;
  std::string integrator_;
  double stiffnessScale_, swingDt_, duration_, restTime_, restCheckDuration_;
  std::once_flag swingOnce_, restOnce_, limitOnce_;
  std::shared_ptr<const StableSwing> swing_;
  bool rests_ = false;
  double limit_ = NAN;
};

// Does the scene survive `duration` (and at least kFewestTrialSteps) at dt, and so does its
// twin at a dt kTwinOffset smaller? (nullopt: too many steps to try)
// Where a run failed, *stoppedAt is the scene's time it was stopped (NaN: by the rest check).
std::optional<bool> survives(const Registry& registry, const SceneDocument& scene, const std::string& integrator,
                             double dt, double duration, long maxSteps, double stiffnessScale,
                             HalfLimitRuns& reference, double restTime, double restDt, double& stoppedAt) {
  stoppedAt = NAN;
  const long steps = std::max(kFewestTrialSteps, std::lround(std::ceil(duration / dt)));
  if (steps > maxSteps) return std::nullopt;
  RunSpec spec{scene, integrator, dt, steps, 1};
  spec.keepPositions = false;
  spec.stiffnessScale = stiffnessScale;
  spec.swing = reference.swing();
  spec.explainBlowUp = false;  // the bisection needs the verdict only
  spec.knownStepLimit = reference.stepLimit();
  spec.restTime = restTime;
  spec.restDt = restDt;
  if (const RunResult r = runScene(registry, spec); !r.stable) {
    stoppedAt = r.stoppedAt;
    return false;
  }
  // A verdict must not hang on round-off: a scene with contacts is chaotic, and past the limit a
  // run may miss its instability by luck (the midpoint rule on the dropped cloth at 1.09 times
  // its limit runs to the end at dt = 0.298335443 ms and fails by passivity at 0.298335 ms). So
  // a run that survives counts only when its twin at a dt one part in a million smaller does.
  spec.dt = dt * (1.0 - kTwinOffset);
  if (const RunResult r = runScene(registry, spec); !r.stable) {
    stoppedAt = r.stoppedAt;
    return false;
  }
  // A mode past its limit that something nonlinear caps (a contact, the wind's drag) leaves
  // the run bounded and within the check's allowances (the wind ball under velocity Verlet
  // survived 1.2 times its limit); where the scene rests, its rest must hold at dt too.
  if (reference.restCheckApplies(dt) &&
      restBroken(measureRestGrowth(registry, scene, integrator, stiffnessScale, dt, reference.restCheckDuration()))) {
    return false;
  }
  return true;
}

// The stiffest state on the way to where the trials failed: a calm run at half the predicted
// limit (the dt trials from the rest run there at first) from the scene's start up to the time
// the smallest failing trial was stopped, probed at 128 states after `from` (where the trials
// switch to their dt; the trampoline's catch lasts 6 ms of a failing trial's 0.06 s: with 64
// states 1 ms apart a build without OpenMP found its states there not smooth, and named 0.256 ms
// at 0.047 s for 0.240), at most 16 limits. A state counts where its limit is more than 1 % below the prediction at rest (the
// radius at that prediction drifts by round-off along a calm run). Returns (limit, time); time
// NaN: the rest's.
constexpr int kOnTheWaySamples = 128;
constexpr int kOnTheWayLimits = 16;
constexpr double kOnTheWayMargin = 1.01;
std::pair<double, double> stiffestOnTheWay(const Registry& registry, const SceneDocument& scene,
                                        const std::string& integrator, double predicted, double from,
                                        double failedAt, double work) {
  if (!(std::isfinite(predicted) && predicted > 0.0 && std::isfinite(failedAt) && failedAt > from)) return {NAN, NAN};
  LoadedScene loaded = registry.loadScene(scene);
  loaded.sim->setIntegrator(registry.makeIntegrator(integrator));
  if (failedAt / (0.5 * predicted) * loaded.sim->numOfMasses() > work) return {NAN, NAN};
  const CalmRun calm =
      calmRun(*loaded.sim, predicted, kOnTheWayMargin, from, failedAt, kOnTheWaySamples, kOnTheWayLimits);
  if (calm.states == 0) return {NAN, NAN};
  if (std::isfinite(calm.limit) && calm.limit < predicted) return {calm.limit, calm.time};
  return {predicted, NAN};
}

}  // namespace

double defaultStabilityDuration(double maxAngularFrequency) {
  return maxAngularFrequency > 0.0 ? 300.0 * 2.0 * std::numbers::pi / maxAngularFrequency : 1.0;
}

double restArrival(const Registry& registry, const SceneDocument& scene, double window, double until) {
  LoadedScene loaded = registry.loadScene(scene);
  loaded.sim->setIntegrator(registry.makeIntegrator("symplectic_euler"));
  const double limit = stepStableDt(*loaded.sim);
  if (!(std::isfinite(limit) && limit > 0.0)) return 0.0;
  Simulation& sim = *loaded.sim;
  sim.reset();
  sim.setBlowUpCheck(false);
  const double dt = 0.5 * limit;
  double peak = 0.0, arrival = 0.0;
  try {
    while (sim.state.time < until && sim.state.time < arrival + window) {
      sim.operate(dt);
      const double kinetic = sim.energies().kinetic;
      if (!std::isfinite(kinetic)) return 0.0;
      peak = std::max(peak, kinetic);
      if (kinetic > kRestKinetic * peak) arrival = sim.state.time;
    }
  } catch (const std::exception&) {
    return 0.0;
  }
  // Still moving at `until`: no rest to arrive at (the wind ball rolls on).
  return sim.state.time >= arrival + window ? arrival : 0.0;
}

double SceneRestArrival::get(const Registry& registry, const SceneDocument& scene, double window) {
  std::call_once(once_, [&] { arrival_ = restArrival(registry, scene, window, 10.0 * window); });
  return arrival_;
}

// Long enough for an instability just past the predicted limit to show: at 1.03 times the
// limit the linearised step grows a mode by its spectral radius per step; the trial lasts
// until that is 1e20 (46 e-foldings: from round-off to a visible motion), at least `atLeast`.
// Where the prediction is a fallen body's rest, counted from when a run gets there
// (restArrival): the self-colliding cloth comes to rest at 2.46 s, and its velocity Verlet,
// whose step at that rest grows 1.1 times a step at 1.03 times its limit, fails at 1.05 s,
// nearly at rest; with trials of 0.73 s (the growth's 18 ms, at least 300 periods) it measured
// 2.6 times its limit.
double stabilityTrialDuration(const Registry& registry, const SceneDocument& scene, const std::string& integrator,
                      double predicted, double atLeast, double* growthOnly, SceneRestArrival* sharedArrival) {
  if (growthOnly) *growthOnly = atLeast;
  if (!(std::isfinite(predicted) && predicted > 0.0)) return atLeast;
  LoadedScene loaded = registry.loadScene(scene);
  loaded.sim->setIntegrator(registry.makeIntegrator(integrator));
  const double dt = 1.03 * predicted;
  const StepSpectrum spectrum = stepSpectralRadius(*loaded.sim, dt);
  SceneRestArrival own;
  SceneRestArrival& rest = sharedArrival ? *sharedArrival : own;
  const double arrival = spectrum.restsAfterImpact ? rest.get(registry, scene, atLeast) : 0.0;
  const double radius = spectrum.radius;
  // At most 100 times `atLeast`: a radius within the finite differences' noise of 1 says
  // the instability grows too slowly to find by running.
  const double growth = radius > 1.0 ? std::log(1e20) / std::log(radius) * dt : 0.0;
  if (growthOnly) *growthOnly = std::clamp(growth, atLeast, 100.0 * atLeast);
  return std::clamp(arrival + growth, atLeast, 100.0 * atLeast);
}

CriticalDt criticalDt(const Registry& registry, const SceneDocument& scene, const std::string& integrator,
                      double duration, double firstGuess, double tolerance, long maxSteps, double stiffnessScale,
                      double swingDt, double restTime, double restCheckDuration) {
  CriticalDt out;
  out.integrator = integrator;
  // The rest is reached at swingDt: without a swing run there is none to start from.
  if (!(swingDt > 0.0)) restTime = 0.0;
  HalfLimitRuns reference(registry, scene, integrator, stiffnessScale, swingDt, duration, restTime, restCheckDuration);
  std::map<double, double> stoppedAt;  // s, each failing trial's dt: where it was stopped
  auto stable = [&](double dt) {
    ++out.trials;
    double at = NAN;
    const std::optional<bool> s =
        survives(registry, scene, integrator, dt, duration, maxSteps, stiffnessScale, reference, restTime, swingDt, at);
    if (s && !*s) stoppedAt[dt] = at;
    return s;
  };
  auto failedAt = [&](double hi) {
    const auto it = stoppedAt.find(hi);
    return it == stoppedAt.end() ? NAN : it->second;
  };

  // Bracket: double while stable, halve while unstable. Up to 2^20 (a million) times the first
  // guess: stable that far is "no limit found" (XPBD on the 32 x 32 cloth first fails at 6e5 s,
  // a runaway of one step far longer than the scene, which says nothing about the method).
  double lo = 0.0, hi = 0.0;
  std::optional<bool> s = stable(firstGuess);
  if (!s) {
    // Not even the first trial could be run: nothing measured (not "no stable dt").
    out.measured = NAN;
    return out;
  }
  if (*s) {
    lo = firstGuess;
    for (int k = 0; k < 20 && hi == 0.0; ++k) {
      const double dt = 2.0 * lo;
      if (stable(dt).value_or(false)) lo = dt; else hi = dt;
    }
    if (hi == 0.0) {
      out.measured = INFINITY;
      return out;
    }
  } else {
    hi = firstGuess;
    for (int k = 0; k < 40 && lo == 0.0; ++k) {
      const double dt = 0.5 * hi;
      const std::optional<bool> r = stable(dt);
      if (!r) {
        // Too many steps to try below hi: the limit lies below it, but where is not measured.
        out.measured = NAN;
        return out;
      }
      if (*r) lo = dt; else hi = dt;
    }
    if (lo == 0.0) {
      out.measured = 0.0;
      return out;
    }
  }

  // Bisect (geometrically) until the bracket is narrow.
  while (hi / lo > 1.0 + tolerance) {
    const double mid = std::sqrt(lo * hi);
    if (stable(mid).value_or(false)) lo = mid; else hi = mid;
  }
  out.measured = lo;
  out.failedAt = failedAt(hi);
  return out;
}

Stability stability(const Registry& registry, const SceneDocument& scene, const StabilityOptions& o) {
  Stability study;
  study.scene = scene.file;
  {
    LoadedScene loaded = registry.loadScene(scene);
    study.gershgorinBound = loaded.sim->angularFrequencyBound();
  }
  study.maxAngularFrequency = sceneLanczosEstimate(registry, scene);
  study.duration = o.duration > 0.0 ? o.duration : defaultStabilityDuration(study.maxAngularFrequency);
  const std::vector<std::string> names = studyIntegrators(registry, scene, o.integrators);

  // One prediction and one bisection per integrator, in parallel; the bisection starts at
  // the prediction (a method stable at every dt starts at 100 / w_max: stable there means no
  // limit within the doublings, reported as inf).
  std::vector<CriticalDt> results(names.size());
  std::vector<std::string> missing(names.size());
  SceneRestArrival arrival;  // the scene's, whichever method asks first
  parallelFor(static_cast<int>(names.size()), o.threads, [&](int i) {
    const double c = stabilityConstant(registry, names[i]);
    const double w = study.maxAngularFrequency;
    try {
      const double predicted = sceneStepStableDt(registry, scene, names[i]);
      const double guess = std::isfinite(predicted) && predicted > 0.0 ? predicted
                           : w > 0.0 ? (std::isinf(predicted) ? 100.0 / w : 2.0 / w)
                                     : 0.01;
      // The trial's time, and the rest check's (the growth's alone: it starts at the rest).
      double growth = o.duration;
      const double duration = o.duration > 0.0
                                  ? o.duration
                                  : stabilityTrialDuration(registry, scene, names[i], predicted, study.duration, &growth,
                                                           &arrival);
      const double swingDt = std::isfinite(predicted) && predicted > 0.0 ? 0.5 * predicted : 0.0;
      results[i] = criticalDt(registry, scene, names[i], duration, guess, o.tolerance, o.maxSteps, 1.0, swingDt,
                              o.fromRest, growth);
      results[i].predicted = predicted;
      results[i].duration = duration;
      if (o.stiffestOnTheWay) {
        std::tie(results[i].stiffestOnTheWay, results[i].stiffestOnTheWayAt) = stiffestOnTheWay(
            registry, scene, names[i], predicted, o.fromRest, results[i].failedAt, o.stiffestOnTheWayWork);
      }
    } catch (const NotImplemented& e) {
      missing[i] = e.what();
      return;
    }
    results[i].stabilityConstant = c;
    results[i].undamped = c > 0.0 && w > 0.0 ? c / w : 0.0;
  }, o.progress ? "stability bisections" : "");
  for (size_t i = 0; i < names.size(); ++i) {
    if (missing[i].empty()) study.methods.push_back(results[i]);
    else study.skipped.push_back(names[i] + ": " + missing[i]);
  }
  return study;
}

StabilityMap stabilityMap(const Registry& registry, const SceneDocument& scene, const StabilityMapOptions& o) {
  StabilityMap map;
  map.scene = scene.file;
  LoadedScene loaded = registry.loadScene(scene);
  map.integrator = o.integrator.empty() ? loaded.settings.integrator : o.integrator;
  map.stabilityConstant = stabilityConstant(registry, map.integrator);
  map.springConstant = loaded.sim->springs().empty() ? 0.0 : loaded.sim->springs().front().springConstant;
  map.scales = o.stiffnessScales;
  if (map.scales.empty()) {
    for (int k = -6; k <= 6; ++k) map.scales.push_back(std::pow(10.0, k / 3.0));
  }

  // The predicted boundary: the limit of the step at each stiffness (and w_max there).
  for (double s : map.scales) {
    map.maxAngularFrequency.push_back(sceneLanczosEstimate(registry, scene, s));
    map.predicted.push_back(sceneStepStableDt(registry, scene, map.integrator, s));
  }
  const double w1 = sceneLanczosEstimate(registry, scene, 1.0);
  map.duration = o.duration > 0.0 ? o.duration : defaultStabilityDuration(w1);
  const double atScale1 = sceneStepStableDt(registry, scene, map.integrator, 1.0);
  const double centre = std::isfinite(atScale1) && atScale1 > 0.0 ? atScale1 : 2.0 / std::max(w1, 1e-12);

  // Every cell is one run over the same simulated time, its passivity detector allowing the
  // swing measured at half the limit of its stiffness.
  std::vector<std::unique_ptr<HalfLimitRuns>> references;
  for (std::size_t r = 0; r < map.scales.size(); ++r) {
    const double limit = map.predicted[r];
    const double swingDt = std::isfinite(limit) && limit > 0.0 ? 0.5 * limit : 0.0;
    references.push_back(
        std::make_unique<HalfLimitRuns>(registry, scene, map.integrator, map.scales[r], swingDt, map.duration));
  }
  for (double s : map.scales) {
    for (int j = 0; j < o.dtCount; ++j) {
      const double exponent = -1.5 + 3.0 * j / std::max(1, o.dtCount - 1);
      map.cells.push_back({s, centre * std::pow(10.0, exponent), true, true});
    }
  }
  parallelFor(static_cast<int>(map.cells.size()), o.threads, [&](int i) {
    StabilityMapCell& cell = map.cells[i];
    const std::size_t row = static_cast<std::size_t>(i) / static_cast<std::size_t>(std::max(1, o.dtCount));
    double stoppedAt = NAN;  // a cell keeps its verdict only
    const std::optional<bool> ok = survives(registry, scene, map.integrator, cell.dt, map.duration, o.maxSteps,
                                            cell.stiffnessScale, *references[row], 0.0, 0.0, stoppedAt);
    cell.run = ok.has_value();
    cell.stable = ok.value_or(true);
  }, o.progress ? "stability map cells" : "");
  return map;
}

void writeCsv(const Stability& study, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write the CSV file");
  out << std::setprecision(10);
  out << "integrator,stability_constant,w_max_rad_s,gershgorin_rad_s,undamped_dt_s,predicted_dt_s,measured_dt_s,"
         "measured_over_predicted,duration_s,failed_at_s,stiffest_on_the_way_dt_s,stiffest_on_the_way_at_s,measured_over_stiffest\n";
  for (const CriticalDt& m : study.methods) {
    const bool finite = std::isfinite(m.predicted) && m.predicted > 0.0;
    out << m.integrator << ',' << m.stabilityConstant << ',' << study.maxAngularFrequency << ','
        << study.gershgorinBound << ',' << m.undamped << ',' << m.predicted << ',' << m.measured << ','
        << (finite ? m.measured / m.predicted : 0.0) << ',' << m.duration << ',' << m.failedAt << ','
        << m.stiffestOnTheWay << ',' << m.stiffestOnTheWayAt << ','
        << (std::isfinite(m.stiffestOnTheWay) ? m.measured / m.stiffestOnTheWay : NAN) << '\n';
  }
  if (!out) throw std::runtime_error(path + ": writing the CSV file failed");
}

void writeCsv(const StabilityMap& map, const std::string& cellsPath, const std::string& boundaryPath) {
  std::ofstream cells(cellsPath);
  if (!cells) throw std::runtime_error(cellsPath + ": cannot write the CSV file");
  cells << std::setprecision(10);
  cells << "stiffness_scale,spring_constant_N_m,dt_s,stable,run\n";
  for (const StabilityMapCell& c : map.cells) {
    cells << c.stiffnessScale << ',' << c.stiffnessScale * map.springConstant << ',' << c.dt << ','
          << (c.stable ? 1 : 0) << ',' << (c.run ? 1 : 0) << '\n';
  }
  std::ofstream boundary(boundaryPath);
  if (!boundary) throw std::runtime_error(boundaryPath + ": cannot write the CSV file");
  boundary << std::setprecision(10);
  boundary << "stiffness_scale,spring_constant_N_m,w_max_rad_s,undamped_dt_s,predicted_dt_s\n";
  for (size_t i = 0; i < map.scales.size(); ++i) {
    const double w = map.maxAngularFrequency[i];
    boundary << map.scales[i] << ',' << map.scales[i] * map.springConstant << ',' << w << ','
             << (map.stabilityConstant > 0.0 && w > 0.0 ? map.stabilityConstant / w : 0.0) << ','
             << map.predicted[i] << '\n';
  }
  if (!cells || !boundary) throw std::runtime_error(cellsPath + ": writing the CSV files failed");
}

}  // namespace springlab::studies
