#include "bench_support.hpp"

#include <springlab/scene_document.hpp>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <springlab/rope/rope.hpp>
#include <springlab/softbody/softbody.hpp>

namespace springlab::bench {

const Registry& registry() {
  static const Registry instance = [] {
    Registry r;
    registerFramework(r);
    rope::registerLab(r);
    net::registerLab(r);
    softbody::registerLab(r);
    return r;
  }();
  return instance;
}

net::NetParameters cloth(int r, int material) {
  net::NetParameters p;
  p.width = 1.0;
  p.height = 1.0;
  p.resolution = r;
  p.origin = Vec3(-0.5, 0.0, 0.0);
  p.uAxis = Vec3::UnitX();
  p.vAxis = Vec3::UnitZ();
  if (material == 0) {
    p.massModel = net::MassModel::Constant;
    p.particleMass = 1.0;
    p.springs[SpringKind::Structural] = {true, 75.0, 0.25};
    p.springs[SpringKind::Shear] = {true, 22.0, 0.25};
    p.springs[SpringKind::Bend] = {true, 8.0, 0.25};
  } else {
    p.massModel = net::MassModel::Density;
    p.arealDensity = 0.2;
    p.springs[SpringKind::Structural] = {true, 400.0, 0.3};
    p.springs[SpringKind::Shear] = {true, 150.0, 0.3};
    p.springs[SpringKind::Bend] = {true, 15.0, 0.05};
  }
  p.pins = {net::Pin::Corner00, net::Pin::Corner10};
  p.gravitation = Vec3(0.0, -9.81, 0.0);
  p.wind.strength = 0.0;
  p.wind.drag = 0.0;
  p.stretchLimiting = false;
  p.selfCollision = false;
  return p;
}

net::NetParameters thesisFrame(int r) {
  net::NetParameters p = cloth(r, 0);
  p.spheres.push_back({Vec3(0.0, -0.6, 0.5), 0.3, false, Vec3::Zero()});
  p.planes.push_back({Vec3(0.0, -1.2, 0.0), Vec3::UnitY()});
  p.stretchLimiting = true;
  p.maxStretch = 0.1;
  p.wind.model = net::WindModel::Thesis;
  p.wind.direction = Vec3(0.0, 0.0, -1.0);
  p.wind.strength = 4.0;
  return p;
}

LoadedScene loadScene(const std::string& file, const std::vector<std::string>& sets) {
  SceneDocument document = SceneDocument::read(std::string(SPRINGLAB_SCENES_DIR) + "/" + file);
  for (const std::string& s : sets) document.set(s);
  return registry().loadScene(document);
}

void useThreads(int threads) {
#ifdef _OPENMP
  omp_set_num_threads(threads);
#else
  (void)threads;
#endif
}

void timeSteps(benchmark::State& bench, Simulation& sim, double dt, int warmup) {
  sim.setBlowUpCheck(false);
  for (int n = 0; n < warmup; ++n) sim.operate(dt);

  const Stats before = sim.stats;
  sim.profile.clear();
  sim.profile.setEnabled(true);
  for (auto _ : bench) sim.operate(dt);
  sim.profile.setEnabled(false);

  const double steps = static_cast<double>(sim.stats.steps - before.steps);
  for (int p = 0; p < PhaseProfile::kPhases; ++p) {
    const Phase phase = static_cast<Phase>(p);
    std::string name(phaseName(phase));
    for (char& c : name) c = c == ' ' ? '_' : c;
    bench.counters["ms_" + name] = 1e3 * sim.profile.seconds(phase) / steps;
  }
  bench.counters["cg_iterations"] = static_cast<double>(sim.stats.solverIterations - before.solverIterations) / steps;
  bench.counters["force_evals"] = static_cast<double>(sim.stats.forceEvaluations - before.forceEvaluations) / steps;
  bench.counters["masses"] = sim.numOfMasses();
  bench.counters["springs"] = static_cast<double>(sim.springs().size());
}

void timeScene(benchmark::State& bench, const std::string& file, const std::vector<std::string>& sets, int warmup) {
  LoadedScene scene = loadScene(file, sets);
  timeSteps(bench, *scene.sim, scene.settings.dt, warmup);
}

}  // namespace springlab::bench
