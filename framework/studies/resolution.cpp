#include "springlab/studies/resolution.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>

#include "parallel.hpp"

namespace springlab::studies {

namespace {

// The observable to study: the one asked for, or the scene's first; with its unit.
std::pair<std::string, std::string> pickObservable(const Registry& registry, const SceneDocument& scene,
                                                   const std::string& asked) {
  LoadedScene loaded = registry.loadScene(scene);
  const std::vector<Observable> all = loaded.sim->observables();
  if (all.empty()) throw std::invalid_argument(scene.file + ": the scene reports no observables to study");
  if (asked.empty()) return {all.front().name, all.front().unit};
  std::string known;
  for (const Observable& o : all) {
    if (o.name == asked) return {o.name, o.unit};
    known += (known.empty() ? "" : ", ") + o.name;
  }
  throw std::invalid_argument(scene.file + ": no observable \"" + asked + "\"; the scene has: " + known);
}

// A step that divides the sample interval exactly, no larger than dt.
long stepsPerSample(double interval, double dt) {
  return std::max(1L, static_cast<long>(std::ceil(interval / dt * (1.0 - 1e-12))));
}

// The scene's own dt, integrator and frame length (dt x substeps).
double sceneDt(const SceneDocument& scene) { return scene.json.at("dt").get<double>(); }

// A run's work for the progress lines: its steps times its masses.
double runWork(const Registry& registry, const RunSpec& spec) {
  const double masses = registry.loadScene(spec.scene).sim->numOfMasses();
  return masses * static_cast<double>(spec.stepsPerSample) * spec.samples;
}

}  // namespace

double relativeError(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size() || b.empty()) return INFINITY;
  double diff = 0.0, scale = 0.0;
  for (size_t k = 0; k < a.size(); ++k) {
    const double d = std::abs(a[k] - b[k]);
    if (!std::isfinite(d)) return INFINITY;
    diff = std::max(diff, d);
    scale = std::max(scale, std::abs(b[k]));
  }
  return scale > 0.0 ? diff / scale : diff;
}

ResolutionStudy resolutionStudy(const Registry& registry, const SceneDocument& scene, const ResolutionOptions& o) {
  ResolutionStudy study;
  study.scene = scene.file;
  study.tolerance = o.tolerance;
  std::tie(study.observable, study.unit) = pickObservable(registry, scene, o.observable);
  study.integrator = o.integrator.empty() ? scene.json.at("integrator").get<std::string>() : o.integrator;

  // Resolutions: given, or the scene's own over 2^-3 .. 2^o.finerSteps (advise stops at the
  // scene's own: the author's model is the fine one it simplifies).
  std::set<int> values(o.resolutions.begin(), o.resolutions.end());
  if (values.empty()) {
    const int base = registry.resolution(scene);
    for (int k = -3; k <= o.finerSteps; ++k) {
      values.insert(std::max(2, static_cast<int>(std::lround(base * std::ldexp(1.0, k)))));
    }
  }

  // Each resolution keeps the scene's w_max dt (its author's safety margin), rounded down to
  // divide the sample interval.
  const double interval = o.duration / o.samples;
  const double w0 = sceneLanczosEstimate(registry, scene);
  std::vector<RunSpec> specs;
  std::vector<double> work;  // steps x masses of each run, for the progress lines
  for (int r : values) {
    SceneDocument doc = registry.atResolution(scene, r);
    const double w = sceneLanczosEstimate(registry, doc);
    const double dt = sceneDt(scene) * (w > w0 && w > 0.0 ? w0 / w : 1.0);
    const long per = stepsPerSample(interval, dt);
    RunSpec spec{doc, study.integrator, interval / static_cast<double>(per), per, o.samples};
    spec.keepPositions = false;
    spec.explainBlowUp = false;  // a blow-up is charted, its message is not
    if (o.runProgress) work.push_back(runWork(registry, spec));
    specs.push_back(spec);
    study.rows.push_back({});
    study.rows.back().resolution = r;
    study.rows.back().dt = spec.dt;
  }
  std::vector<RunResult> runs(specs.size());
  std::vector<double> walls(specs.size());
  if (o.runProgress) {
    double total = 0.0;
    for (double w : work) total += w;
    o.runProgress->plan(static_cast<int>(specs.size()), total);
  }
  const std::string key = o.runProgress ? registry.resolutionRule(scene.json.at("lab").get<std::string>()).key : "";
  parallelFor(static_cast<int>(specs.size()), o.threads, [&](int i) {
    // The first run gives the observable and warms up; the timed runs give the wall time.
    runs[i] = runScene(registry, specs[i]);
    if (o.runProgress) {
      std::ostringstream what;
      what << key << " = " << study.rows[i].resolution << ", " << study.integrator << " at dt = " << specs[i].dt << " s";
      o.runProgress->finished(what.str(), work[i]);
    }
    std::vector<double> timed;
    for (int r = 0; r < o.repeats; ++r) timed.push_back(runScene(registry, specs[i]).wallSeconds);
    walls[i] = timed.empty() ? runs[i].wallSeconds : median(timed);
  }, o.progress ? "resolution runs" : "");

  // Errors against the finest; the chosen row is the coarsest from which every finer one fits.
  study.times = runs.back().times;
  const std::vector<double> finest = observableSeries(runs.back(), study.observable);
  for (size_t i = 0; i < runs.size(); ++i) {
    ResolutionRow& row = study.rows[i];
    row.masses = runs[i].masses;
    row.stable = runs[i].stable;
    row.forceEvaluations = runs[i].forceEvaluations + runs[i].solverIterations;
    row.cost = static_cast<double>(row.forceEvaluations) * row.masses;
    row.wallSeconds = walls[i];
    row.series = observableSeries(runs[i], study.observable);
    row.error = row.stable ? relativeError(row.series, finest) : INFINITY;
  }
  study.chosen = static_cast<int>(study.rows.size()) - 1;
  for (int i = study.chosen - 1; i >= 0 && study.rows[i].error <= o.tolerance; --i) study.chosen = i;
  return study;
}

Advice advise(const Registry& registry, const SceneDocument& scene, const AdviseOptions& o) {
  Advice advice;
  const double half = 0.5 * o.tolerance;
  RunProgress progress("advise", o.progress);

  // 1. The coarsest resolution within half the tolerance (the scene's own when the lab has
  //    no resolution rule).
  SceneDocument model = scene;
  const std::string lab = scene.json.at("lab").get<std::string>();
  bool hasRule = true;
  try {
    registry.resolutionRule(lab);
  } catch (const std::invalid_argument&) {
    hasRule = false;
  }
  if (hasRule) {
    ResolutionOptions ro;
    ro.observable = o.observable;
    ro.tolerance = half;
    ro.duration = o.duration;
    ro.samples = o.samples;
    ro.resolutions = o.resolutions;
    ro.repeats = 0;  // the advisor counts costs; it does not time them
    ro.threads = o.threads;
    ro.progress = false;
    ro.runProgress = &progress;
    ro.finerSteps = 0;
    advice.resolution = resolutionStudy(registry, scene, ro);
    advice.chosenResolution = advice.resolution.rows[advice.resolution.chosen].resolution;
    model = registry.atResolution(scene, advice.chosenResolution);
  }
  const std::string observable = pickObservable(registry, model, o.observable).first;

  // 2. At that resolution: a dt ladder from about RK4's limit down, and an RK4 reference
  //    converged on the observable: RK4 at 2 and then 4, 8, ... times below its limit, until
  //    two successive halvings agree within a fiftieth of the tolerance's half (RK4's error
  //    falls 16-fold per halving, so the finer one is then far more accurate than any rung it
  //    judges), at most 2^(levels + 1) below. (A fixed reference 2^levels below the limit
  //    took most of an hour on the cloth, and was never needed.)
  const double interval = o.duration / o.samples;
  const double w = sceneLanczosEstimate(registry, model);
  const double top = w > 0.0 ? 2.83 / w : interval;
  int first = 0;
  while (interval / std::ldexp(1.0, first) > top * (1.0 + 1e-9)) ++first;
  auto per = [](int level) { return 1L << level; };
  // (A run that blows up gives no series: damping can put RK4's real limit well below
  //  2.83 / w_max, as on the cloth; the next halving is tried.)
  auto referenceAt = [&](int level) -> std::optional<std::vector<double>> {
    RunSpec spec{model, "rk4", interval / static_cast<double>(per(level)), per(level), o.samples};
    spec.keepPositions = false;
    spec.explainBlowUp = false;  // a reference that blows up is replaced by the next halving
    progress.plan(1, runWork(registry, spec));
    const RunResult run = runScene(registry, spec);
    std::ostringstream what;
    what << "the reference, rk4 at dt = " << spec.dt << " s" << (run.stable ? "" : ": blew up");
    progress.finished(what.str(), runWork(registry, spec));
    if (!run.stable) return std::nullopt;
    return observableSeries(run, observable);
  };
  const int lastReference = first + std::max(o.levels + 1, 2);
  int refLevel = first;
  std::optional<std::vector<double>> refSeries;
  while (refLevel < lastReference) {
    std::optional<std::vector<double>> finer = referenceAt(++refLevel);
    const bool converged = refSeries && finer && relativeError(*refSeries, *finer) <= half / 50.0;
    refSeries = std::move(finer);
    if (converged) break;
  }
  if (!refSeries) throw std::runtime_error("the RK4 reference blew up at every dt down to 2^-" +
                                           std::to_string(lastReference - first) + " times its limit");
  advice.referenceDt = interval / static_cast<double>(per(refLevel));

  // 3. Each integrator: the largest dt on the ladder that is stable and within half the
  //    tolerance (integrators in parallel, each walking down its ladder). A method stable at
  //    any dt (implicit Euler, XPBD, projective dynamics) starts higher, at the scene's frame
  //    length (the largest step the viewer can take), since RK4's limit says nothing about
  //    it: on a stiff scene its own step can be many times that limit. The others start at
  //    the first rung within their own exact limit (stepStableDt).
  const double frame = sceneDt(scene) * scene.json.at("substeps").get<double>();
  int frameLevel = 0;
  while (frameLevel < first && interval / std::ldexp(1.0, frameLevel) > frame * (1.0 + 1e-9)) ++frameLevel;
  const std::vector<std::string> names = studyIntegrators(registry, model, o.integrators);
  advice.candidates.resize(names.size());
  // Every rung of every ladder is planned; the rungs below a ladder's answer are dropped.
  const double modelMasses = registry.loadScene(model).sim->numOfMasses();
  auto rungWork = [&](int level) { return modelMasses * static_cast<double>(per(level)) * o.samples; };
  // Each ladder starts at the first rung at or below the method's own stability limit
  // (sceneStepStableDt); a method stable at every dt at the frame length.
  std::vector<int> startLevel(names.size(), first);
  std::vector<std::string> limitNote(names.size());
  for (std::size_t i = 0; i < names.size(); ++i) {
    double limit = 0.0;
    try {
      limit = sceneStepStableDt(registry, model, names[i]);
    } catch (const NotImplemented& e) {
      limitNote[i] = e.what();
      continue;
    }
    int start = std::isinf(limit) ? frameLevel : 0;
    while (std::isfinite(limit) && start < first + o.levels - 1 && interval / std::ldexp(1.0, start) > limit * (1.0 + 1e-9)) ++start;
    startLevel[i] = start;
  }
  for (std::size_t i = 0; i < names.size(); ++i) {
    for (int l = startLevel[i]; l < first + o.levels; ++l) progress.plan(1, rungWork(l));
  }
  parallelFor(static_cast<int>(names.size()), o.threads, [&](int i) {
    Candidate& c = advice.candidates[i];
    c.integrator = names[i];
    const int start = startLevel[i];
    auto dropFrom = [&](int level) {
      for (int l = level; l < first + o.levels; ++l) progress.dropped(1, rungWork(l));
    };
    if (!limitNote[i].empty()) {
      c.note = limitNote[i];
      dropFrom(start);
      return;
    }
    for (int l = start; l < first + o.levels; ++l) {
      RunSpec spec{model, names[i], interval / static_cast<double>(per(l)), per(l), o.samples};
      spec.keepPositions = false;
      spec.explainBlowUp = false;  // a blow-up is charted, its message is not
      RunResult run;
      try {
        run = runScene(registry, spec);
      } catch (const NotImplemented& e) {
        c.note = e.what();
        dropFrom(l);
        return;
      }
      const double error = run.stable ? relativeError(observableSeries(run, observable), *refSeries) : INFINITY;
      std::ostringstream what;
      what << names[i] << " at dt = " << spec.dt << " s: "
           << (run.stable ? (error <= half ? "within" : "outside") + std::string(" the tolerance") : "blew up");
      progress.finished(what.str(), rungWork(l));
      c.error = error;  // kept when no rung meets the tolerance: the finest rung's error
      if (error <= half) {
        c.dt = spec.dt;
        c.error = error;
        c.evaluationsPerSecond = static_cast<double>(run.forceEvaluations + run.solverIterations) / o.duration;
        dropFrom(l + 1);
        return;
      }
    }
    std::ostringstream note;
    note << "no dt down to " << interval / static_cast<double>(per(first + o.levels - 1)) << " s met the tolerance (error "
         << c.error << " there)";
    c.note = note.str();
  });

  // 4. The cheapest in force evaluations per simulated second (ties: the smaller error).
  for (int i = 0; i < static_cast<int>(advice.candidates.size()); ++i) {
    const Candidate& c = advice.candidates[i];
    if (c.dt <= 0.0) continue;
    if (advice.best < 0) { advice.best = i; continue; }
    const Candidate& b = advice.candidates[advice.best];
    if (c.evaluationsPerSecond < b.evaluationsPerSecond ||
        (c.evaluationsPerSecond == b.evaluationsPerSecond && c.error < b.error)) {
      advice.best = i;
    }
  }

  // 5. The snippet: integrator, dt, substeps for the scene's frame length, the lab's section.
  if (advice.best >= 0) {
    const Candidate& b = advice.candidates[advice.best];
    advice.snippet["integrator"] = b.integrator;
    advice.snippet["dt"] = b.dt;
    advice.snippet["substeps"] = std::max(1L, std::lround(frame / b.dt));
    if (hasRule) advice.snippet[lab] = model.json.at(lab);
  }
  return advice;
}

void writeCsv(const ResolutionStudy& study, const std::string& summaryPath, const std::string& seriesPath) {
  std::ofstream out(summaryPath);
  if (!out) throw std::runtime_error(summaryPath + ": cannot write the CSV file");
  out << std::setprecision(10);
  out << "resolution,masses,dt_s,stable,force_evaluations,cost_mass_evaluations,wall_s,relative_error,chosen\n";
  for (size_t i = 0; i < study.rows.size(); ++i) {
    const ResolutionRow& r = study.rows[i];
    out << r.resolution << ',' << r.masses << ',' << r.dt << ',' << (r.stable ? 1 : 0) << ',' << r.forceEvaluations
        << ',' << r.cost << ',' << r.wallSeconds << ',' << r.error << ',' << (static_cast<int>(i) == study.chosen ? 1 : 0)
        << '\n';
  }
  std::ofstream series(seriesPath);
  if (!series) throw std::runtime_error(seriesPath + ": cannot write the CSV file");
  series << std::setprecision(10);
  series << "resolution,time_s," << study.observable << "_" << study.unit << "\n";
  for (const ResolutionRow& r : study.rows) {
    for (size_t k = 0; k < r.series.size() && k < study.times.size(); ++k) {
      series << r.resolution << ',' << study.times[k] << ',' << r.series[k] << '\n';
    }
  }
  if (!out || !series) throw std::runtime_error(summaryPath + ": writing the CSV files failed");
}

}  // namespace springlab::studies
