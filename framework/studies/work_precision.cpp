#include "springlab/studies/work_precision.hpp"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <stdexcept>

#include "parallel.hpp"

namespace springlab::studies {

WorkPrecision workPrecision(const Registry& registry, const SceneDocument& scene, const WorkPrecisionOptions& o) {
  WorkPrecision study;
  study.scene = scene.file;
  study.duration = o.duration;
  const std::vector<std::string> names = studyIntegrators(registry, scene, o.integrators);

  // The dt ladder: the sample interval over powers of two, starting at about twice the
  // largest stable dt of any method (RK4's 2.83 / w_max) unless given.
  const double interval = o.duration / o.samples;
  study.maxAngularFrequency = sceneLanczosEstimate(registry, scene);
  const double largest = o.largestDt > 0.0 ? o.largestDt
                         : study.maxAngularFrequency > 0.0 ? 2.0 * 2.83 / study.maxAngularFrequency
                                                            : interval;
  int firstLevel = 0;
  while (interval / std::ldexp(1.0, firstLevel) > largest * (1.0 + 1e-9)) ++firstLevel;
  auto stepsPerSample = [&](int level) { return 1L << level; };
  const int referenceLevel = firstLevel + o.levels - 1 + 3;
  study.referenceDt = interval / static_cast<double>(stepsPerSample(referenceLevel));

  // The reference: RK4 at 8 times the finest step of the sweep.
  RunSpec refSpec{scene, "rk4", study.referenceDt, stepsPerSample(referenceLevel), o.samples};
  const RunResult reference = runScene(registry, refSpec);
  if (!reference.stable) throw std::runtime_error("the RK4 reference run blew up: " + reference.failure);

  // Every (integrator, dt) pair is a task; a warm-up run measures the error, timed runs the cost.
  struct Task {
    std::string integrator;
    int level;
  };
  std::vector<Task> tasks;
  for (const std::string& name : names) {
    for (int l = 0; l < o.levels; ++l) tasks.push_back({name, firstLevel + l});
  }
  std::vector<WorkPrecisionPoint> points(tasks.size());
  std::vector<std::string> missing(tasks.size());
  parallelFor(static_cast<int>(tasks.size()), o.threads, [&](int t) {
    const Task& task = tasks[t];
    RunSpec spec{scene, task.integrator, interval / static_cast<double>(stepsPerSample(task.level)),
                 stepsPerSample(task.level), o.samples};
    spec.explainBlowUp = false;  // a blow-up is charted, its message is not
    WorkPrecisionPoint& p = points[t];
    p.integrator = task.integrator;
    p.dt = spec.dt;
    RunResult run;
    try {
      run = runScene(registry, spec);
    } catch (const NotImplemented& e) {
      missing[t] = e.what();
      return;
    }
    p.stable = run.stable;
    p.steps = run.steps;
    p.forceEvaluations = run.forceEvaluations;
    const std::vector<double> errors = positionErrors(run, reference);
    p.finalError = run.stable && !errors.empty() ? errors.back() : INFINITY;
    p.maxError = INFINITY;
    if (run.stable) {
      p.maxError = 0.0;
      for (double e : errors) p.maxError = std::max(p.maxError, e);
    }
    // Timing: the median of the timed runs (the first run was the warm-up).
    std::vector<double> walls;
    spec.keepPositions = false;
    for (int r = 0; r < o.repeats && run.stable; ++r) walls.push_back(runScene(registry, spec).wallSeconds);
    p.wallSeconds = walls.empty() ? run.wallSeconds : median(walls);
  }, o.progress ? "work-precision runs" : "");

  // Keep the points of integrators that ran; name the ones a missing exercise skipped.
  for (size_t t = 0; t < tasks.size(); ++t) {
    if (missing[t].empty()) {
      study.points.push_back(points[t]);
    } else if (study.skipped.empty() || study.skipped.back().rfind(tasks[t].integrator + ":", 0) != 0) {
      study.skipped.push_back(tasks[t].integrator + ": " + missing[t]);
    }
  }
  return study;
}

void writeCsv(const WorkPrecision& study, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write the CSV file");
  out << std::setprecision(10);
  out << "integrator,dt_s,stable,steps,force_evaluations,wall_s,final_error_m,max_error_m\n";
  for (const WorkPrecisionPoint& p : study.points) {
    out << p.integrator << ',' << p.dt << ',' << (p.stable ? 1 : 0) << ',' << p.steps << ',' << p.forceEvaluations
        << ',' << p.wallSeconds << ',' << p.finalError << ',' << p.maxError << '\n';
  }
  if (!out) throw std::runtime_error(path + ": writing the CSV file failed");
}

}  // namespace springlab::studies
