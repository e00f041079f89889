#include "springlab/studies/stability.hpp"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <numbers>
#include <stdexcept>

#include "parallel.hpp"

namespace springlab::studies {

namespace {

// Does the scene survive `duration` at dt? (nullopt: too many steps to try)
std::optional<bool> survives(const Registry& registry, const SceneDocument& scene, const std::string& integrator,
                             double dt, double duration, long maxSteps, double stiffnessScale) {
  const long steps = std::max(1L, std::lround(std::ceil(duration / dt)));
  if (steps > maxSteps) return std::nullopt;
  RunSpec spec{scene, integrator, dt, steps, 1};
  spec.keepPositions = false;
  spec.stiffnessScale = stiffnessScale;
  return runScene(registry, spec).stable;
}

}  // namespace

double defaultStabilityDuration(double maxAngularFrequency) {
  return maxAngularFrequency > 0.0 ? 300.0 * 2.0 * std::numbers::pi / maxAngularFrequency : 1.0;
}

CriticalDt criticalDt(const Registry& registry, const SceneDocument& scene, const std::string& integrator,
                      double duration, double firstGuess, double tolerance, long maxSteps, double stiffnessScale) {
  CriticalDt out;
  out.integrator = integrator;
  auto stable = [&](double dt) {
    ++out.trials;
    return survives(registry, scene, integrator, dt, duration, maxSteps, stiffnessScale);
  };

  // Bracket: double while stable, halve while unstable.
  double lo = 0.0, hi = 0.0;
  std::optional<bool> s = stable(firstGuess);
  if (s && *s) {
    lo = firstGuess;
    for (int k = 0; k < 30 && hi == 0.0; ++k) {
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
      if (!r) break;  // too many steps: give up at this bracket
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

  // One bisection per integrator, in parallel; the first guess is the prediction (or, for a
  // method without an undamped limit, the symplectic Euler prediction).
  std::vector<CriticalDt> results(names.size());
  std::vector<std::string> missing(names.size());
  parallelFor(static_cast<int>(names.size()), o.threads, [&](int i) {
    const double c = stabilityConstant(registry, names[i]);
    const double w = study.maxAngularFrequency;
    const double predicted = c > 0.0 && w > 0.0 ? c / w : 0.0;
    // An unconditionally stable method (c = inf) starts at 100 / w_max: stable there means no
    // limit within the doublings (reported as inf).
    const double guess = std::isfinite(predicted) && predicted > 0.0 ? predicted
                         : w > 0.0 ? (std::isinf(c) ? 100.0 / w : 2.0 / w)
                                   : 0.01;
    try {
      results[i] = criticalDt(registry, scene, names[i], study.duration, guess, o.tolerance, o.maxSteps);
    } catch (const NotImplemented& e) {
      missing[i] = e.what();
      return;
    }
    results[i].stabilityConstant = c;
    results[i].predicted = predicted;
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

  // The predicted boundary: w_max at each stiffness.
  for (double s : map.scales) map.maxAngularFrequency.push_back(sceneLanczosEstimate(registry, scene, s));
  const double w1 = sceneLanczosEstimate(registry, scene, 1.0);
  map.duration = o.duration > 0.0 ? o.duration : defaultStabilityDuration(w1);
  const double centre = (map.stabilityConstant > 0.0 ? map.stabilityConstant : 2.0) / std::max(w1, 1e-12);

  // Every cell is one run over the same simulated time.
  for (double s : map.scales) {
    for (int j = 0; j < o.dtCount; ++j) {
      const double exponent = -1.5 + 3.0 * j / std::max(1, o.dtCount - 1);
      map.cells.push_back({s, centre * std::pow(10.0, exponent), true, true});
    }
  }
  parallelFor(static_cast<int>(map.cells.size()), o.threads, [&](int i) {
    StabilityMapCell& cell = map.cells[i];
    const std::optional<bool> ok =
        survives(registry, scene, map.integrator, cell.dt, map.duration, o.maxSteps, cell.stiffnessScale);
    cell.run = ok.has_value();
    cell.stable = ok.value_or(true);
  }, o.progress ? "stability map cells" : "");
  return map;
}

void writeCsv(const Stability& study, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write the CSV file");
  out << std::setprecision(10);
  out << "integrator,stability_constant,w_max_rad_s,gershgorin_rad_s,predicted_dt_s,measured_dt_s,measured_over_predicted,duration_s\n";
  for (const CriticalDt& m : study.methods) {
    out << m.integrator << ',' << m.stabilityConstant << ',' << study.maxAngularFrequency << ','
        << study.gershgorinBound << ',' << m.predicted << ',' << m.measured << ','
        << (m.predicted > 0.0 ? m.measured / m.predicted : 0.0) << ',' << study.duration << '\n';
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
  boundary << "stiffness_scale,spring_constant_N_m,w_max_rad_s,predicted_dt_s\n";
  for (size_t i = 0; i < map.scales.size(); ++i) {
    const double w = map.maxAngularFrequency[i];
    boundary << map.scales[i] << ',' << map.scales[i] * map.springConstant << ',' << w << ','
             << (map.stabilityConstant > 0.0 && w > 0.0 ? map.stabilityConstant / w : 0.0) << '\n';
  }
  if (!cells || !boundary) throw std::runtime_error(cellsPath + ": writing the CSV files failed");
}

}  // namespace springlab::studies
