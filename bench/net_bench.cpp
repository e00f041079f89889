// Time per step of a cloth of r x r masses with each integrator, on the reference solution.
// The cloth: 1 m x 1 m, held at two corners of one edge, lying flat at the start, under
// gravity; no wind, colliders or corrections, no blow-up check, so a step is the
// integrator's work only (forces, Jacobians, solve). Each run first lets the cloth fall for
// 30 steps, so the solver sees a moving, stretched cloth. Two materials (second argument):
//   0 "fabric": 0.2 kg/m^2, k = 400 / 150 / 15 N/m; light masses on stiff springs, so the
//     implicit system is badly conditioned at r = 64 (dt^2 k / m ~ 2e4 at dt = 1/60 s);
//   1 "thesis": 1 kg per mass, k = 75 / 22 / 8 N/m, kd = 0.25 N s/m (the cloth thesis).
//   build/bench/net_bench                                  all sizes, materials, integrators
//   build/bench/net_bench --benchmark_filter='/64/'        the r = 64 cloth only
// Counters: cg_iterations (per step, implicit_euler), force_evals (per step).
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "net.hpp"

namespace {

using namespace springlab;

net::NetParameters benchCloth(int r, bool thesis) {
  net::NetParameters p;
  p.width = 1.0;
  p.height = 1.0;
  p.resolution = r;
  p.origin = Vec3(-0.5, 0.0, 0.0);
  p.uAxis = Vec3::UnitX();
  p.vAxis = Vec3::UnitZ();
  if (thesis) {
    p.massModel = net::MassModel::Constant;
    p.particleMass = 1.0;
    p.springs[kStructural] = {true, 75.0, 0.25};
    p.springs[kShear] = {true, 22.0, 0.25};
    p.springs[kBend] = {true, 8.0, 0.25};
  } else {
    p.massModel = net::MassModel::Density;
    p.arealDensity = 0.2;
    p.springs[kStructural] = {true, 400.0, 0.3};
    p.springs[kShear] = {true, 150.0, 0.3};
    p.springs[kBend] = {true, 15.0, 0.05};
  }
  p.pins = {net::Pin::Corner00, net::Pin::Corner10};
  p.gravitation = Vec3(0.0, -9.81, 0.0);
  p.wind.strength = 0.0;
  p.wind.drag = 0.0;
  p.stretchLimiting = false;
  p.selfCollision = false;
  return p;
}

// One step of `integrator` at dt on an r x r cloth (range(0) = r, range(1) = material).
void stepCloth(benchmark::State& bench, const std::string& integrator, double dt) {
  Registry registry;
  registerFramework(registry);
  net::registerLab(registry);
  const int r = static_cast<int>(bench.range(0));
  const bool thesis = bench.range(1) == 1;
  net::Net cloth(3, benchCloth(r, thesis));
  cloth.setIntegrator(registry.makeIntegrator(integrator));
  cloth.setBlowUpCheck(false);
  for (int n = 0; n < 30; ++n) cloth.operate(dt);

  const Stats before = cloth.stats;
  for (auto _ : bench) cloth.operate(dt);
  const double steps = static_cast<double>(cloth.stats.steps - before.steps);
  bench.counters["cg_iterations"] = static_cast<double>(cloth.stats.solverIterations - before.solverIterations) / steps;
  bench.counters["force_evals"] = static_cast<double>(cloth.stats.forceEvaluations - before.forceEvaluations) / steps;
  bench.counters["masses"] = r * r;
  bench.counters["springs"] = static_cast<double>(cloth.springs.size());
  bench.SetLabel(std::string(thesis ? "thesis" : "fabric") + ", dt = " + std::to_string(dt) + " s");
}

// Symplectic Euler at a dt it survives: on the fabric 2 / w_max is about 0.2 ms at r = 64, so
// 0.1 ms; the thesis' material allows 1/60 s (2 / w_max = 69 ms).
void SymplecticEuler(benchmark::State& s) { stepCloth(s, "symplectic_euler", s.range(1) == 1 ? 1.0 / 60.0 : 1e-4); }
// The implicit methods at the frame step of the cloth thesis, 1/60 s.
void ImplicitEuler(benchmark::State& s) { stepCloth(s, "implicit_euler", 1.0 / 60.0); }
void ImplicitEulerBlocks(benchmark::State& s) { stepCloth(s, "implicit_euler_blocks", 1.0 / 60.0); }

// r = 8 ... 64, both materials.
void sizes(benchmark::internal::Benchmark* b) {
  for (int material : {0, 1}) {
    for (int r : {8, 16, 32, 64}) b->Args({r, material});
  }
  b->Unit(benchmark::kMillisecond);
}
BENCHMARK(SymplecticEuler)->Apply(sizes);
BENCHMARK(ImplicitEuler)->Apply(sizes);
BENCHMARK(ImplicitEulerBlocks)->Apply(sizes);

}  // namespace

BENCHMARK_MAIN();
