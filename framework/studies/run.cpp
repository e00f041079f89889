#include "springlab/studies/run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <stdexcept>
#include <utility>

#include "springlab/frequency_estimate.hpp"
#include "springlab/step_stability.hpp"

namespace springlab::studies {

void scaleSprings(Simulation& sim, double factor) {
  if (factor == 1.0) return;
  sim.editModel([factor](Simulation& model) {
    for (Spring& s : model.editSprings()) s.springConstant *= factor;
  });
}

namespace {

void sample(const Simulation& sim, bool keepPositions, RunResult& out) {
  out.times.push_back(sim.state.time);
  if (keepPositions) out.positions.push_back(sim.state.pos);
  std::vector<double> values;
  for (const Observable& o : sim.observables()) values.push_back(o.value);
  out.observables.push_back(std::move(values));
}

}  // namespace

StableSwing measureStableSwing(const Registry& registry, const SceneDocument& scene, const std::string& integrator,
                               double stiffnessScale, double dt, double duration) {
  LoadedScene loaded = registry.loadScene(scene);
  Simulation& sim = *loaded.sim;
  sim.setIntegrator(registry.makeIntegrator(integrator));
  scaleSprings(sim, stiffnessScale);
  sim.setBlowUpCheck(false);
  sim.trackCorrectionWork(true);  // as the check counts it
  const long steps = std::clamp(std::lround(std::ceil(duration / dt)), 1L, kMaxSwingSteps);
  // The swing is the largest rise above the run's lowest energy so far, not above its start:
  // a scene whose dampers take energy out faster than the step swings it up early on hides the
  // step's own rise below its start (the flag under explicit Euler at half the limit never
  // rises above its start, then rises 1.3e-4 J from its low when the stretch limit engages;
  // held to its rise above the start, a run at 0.8 times the limit was stopped by passivity
  // for 4.7e-4 J it gave back at once).
  double ownLow = sim.energyBalance(), totalLow = ownLow + sim.correctionWork();
  StableSwing swing;
  swing.total = swing.own = swing.reversal = 0.0;
  swing.profile.binTime = StepReversal::kWindow * dt;
  swing.profile.held.reserve(static_cast<std::size_t>(steps / StepReversal::kWindow + 1));
  swing.profile.kinetic.reserve(swing.profile.held.capacity());
  StepReversal reversal;
  for (long k = 0; k < steps; ++k) {
    sim.operate(dt);
    const double e = sim.energyBalance();
    if (!std::isfinite(e)) return StableSwing{};
    const double total = e + sim.correctionWork();
    ownLow = std::min(ownLow, e);
    totalLow = std::min(totalLow, total);
    swing.own = std::max(swing.own, e - ownLow);
    swing.total = std::max(swing.total, total - totalLow);
    swing.reversal = std::max(swing.reversal, reversal.record(sim.state.vel));
    // The profile's bins start at t = 0, as the runs held to it do.
    const std::size_t bin = static_cast<std::size_t>(std::max(sim.state.time, 0.0) / swing.profile.binTime);
    if (swing.profile.held.size() <= bin) swing.profile.held.resize(bin + 1, 0.0);
    swing.profile.held[bin] = std::max(swing.profile.held[bin], reversal.smallestInWindow());
    if (swing.profile.kinetic.size() <= bin) swing.profile.kinetic.resize(bin + 1, 0.0);
    double kinetic = 0.0;
    for (int i = 0; i < sim.numOfMasses(); ++i) kinetic += 0.5 * sim.masses[i].m * sim.state.vel[i].squaredNorm();
    swing.profile.kinetic[bin] = std::max(swing.profile.kinetic[bin], kinetic);
  }
  // Too short a run to fill the reversal's window measured nothing (detector 5 then holds its
  // floor alone, past the step's limit).
  if (steps < StepReversal::kWindow + 2) {
    swing.reversal = -1.0;
    swing.profile = ReversalProfile{};
  }
  return swing;
}

void holdToSwing(Simulation& sim, const StableSwing& swing) {
  sim.setEnergySwing(swing.total, swing.own);
  sim.setReversalSwing(swing.reversal);
  sim.setReversalProfile(swing.profile);
}

RunResult runScene(const Registry& registry, const RunSpec& spec) {
  LoadedScene loaded = registry.loadScene(spec.scene);
  Simulation& sim = *loaded.sim;
  sim.setIntegrator(registry.makeIntegrator(spec.integrator));
  scaleSprings(sim, spec.stiffnessScale);
  sim.setBlowUpCheck(true);
  sim.setBlowUpExplanation(spec.explainBlowUp);
  if (spec.knownStepLimit) sim.setKnownStepLimit(*spec.knownStepLimit);
  std::shared_ptr<const StableSwing> swing = spec.swing;
  if (!swing && spec.swingDt > 0.0) {
    const double duration = spec.restTime + spec.dt * static_cast<double>(spec.stepsPerSample) * spec.samples;
    swing = std::make_shared<const StableSwing>(
        measureStableSwing(registry, spec.scene, spec.integrator, spec.stiffnessScale, spec.swingDt, duration));
  }
  if (swing) holdToSwing(sim, *swing);
  if (!spec.watchReversal) sim.setReversalSwing(std::numeric_limits<double>::infinity());

  RunResult out;
  out.masses = sim.numOfMasses();
  for (const Observable& o : sim.observables()) out.observableNames.push_back(o.name);
  sample(sim, spec.keepPositions, out);

  // Step, sampling every stepsPerSample steps; a blow-up ends the run and is recorded.
  const auto start = std::chrono::steady_clock::now();
  try {
    if (spec.restTime > 0.0 && spec.restDt > 0.0) {
      while (sim.state.time < spec.restTime - 0.5 * spec.restDt) sim.operate(spec.restDt);
    }
    for (int k = 0; k < spec.samples; ++k) {
      for (long j = 0; j < spec.stepsPerSample; ++j) sim.operate(spec.dt);
      sample(sim, spec.keepPositions, out);
    }
  } catch (const BlowUp& e) {
    out.stable = false;
    out.failure = e.what();
    out.stoppedAt = sim.state.time;
  }
  out.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.steps = sim.stats.steps;
  out.forceEvaluations = sim.stats.forceEvaluations;
  out.solverIterations = sim.stats.solverIterations;
  return out;
}

std::vector<std::string> studyIntegrators(const Registry& registry, const SceneDocument& scene,
                                          const std::vector<std::string>& requested) {
  if (!requested.empty()) return requested;
  std::vector<std::string> usable;
  for (const std::string& name : registry.integratorNames()) {
    // One step at the scene's own dt tells whether the method accepts the scene.
    LoadedScene loaded = registry.loadScene(scene);
    loaded.sim->setIntegrator(registry.makeIntegrator(name));
    loaded.sim->setBlowUpCheck(false);
    try {
      loaded.sim->operate(loaded.settings.dt);
      usable.push_back(name);
    } catch (const std::invalid_argument& e) {
      std::cerr << "springlab: leaving out " << name << ": " << e.what() << "\n";
    } catch (const NotImplemented&) {
      // A missing exercise (a Lab 1 integrator in Lab 3): the study skips the method and
      // names the exercise (its `skipped` list), and charts the others.
      usable.push_back(name);
    }
  }
  return usable;
}

std::vector<double> positionErrors(const RunResult& run, const RunResult& reference) {
  std::vector<double> errors;
  const size_t count = std::min(run.positions.size(), reference.positions.size());
  for (size_t k = 0; k < count; ++k) {
    const auto& a = run.positions[k];
    const auto& b = reference.positions[k];
    if (a.size() != b.size()) return {};
    double worst = 0.0;
    for (size_t i = 0; i < a.size(); ++i) {
      const double d = (a[i] - b[i]).norm();
      worst = std::isfinite(d) ? std::max(worst, d) : INFINITY;
    }
    errors.push_back(worst);
  }
  return errors;
}

std::vector<double> observableSeries(const RunResult& run, const std::string& name) {
  const auto it = std::find(run.observableNames.begin(), run.observableNames.end(), name);
  if (it == run.observableNames.end()) {
    std::string known;
    for (const std::string& n : run.observableNames) known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("the scene has no observable \"" + name + "\"; it has: " +
                                (known.empty() ? "none" : known));
  }
  const size_t index = static_cast<size_t>(it - run.observableNames.begin());
  std::vector<double> series;
  for (const auto& values : run.observables) series.push_back(values.at(index));
  return series;
}

double sceneLanczosEstimate(const Registry& registry, const SceneDocument& scene, double stiffnessScale) {
  LoadedScene loaded = registry.loadScene(scene);
  scaleSprings(*loaded.sim, stiffnessScale);
  return lanczosEstimate(*loaded.sim, loaded.sim->state).maxAngularFrequency;
}

double sceneStepStableDt(const Registry& registry, const SceneDocument& scene, const std::string& integrator,
                         double stiffnessScale) {
  LoadedScene loaded = registry.loadScene(scene);
  loaded.sim->setIntegrator(registry.makeIntegrator(integrator));
  scaleSprings(*loaded.sim, stiffnessScale);
  return stepStableDt(*loaded.sim);
}

double stabilityConstant(const Registry& registry, const std::string& integrator) {
  return registry.makeIntegrator(integrator)->stabilityConstant();
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace springlab::studies
