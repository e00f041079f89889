// Time per step of a cloth of r x r masses with each integrator, on the reference solution.
// The cloth: 1 m x 1 m, 0.2 kg/m^2, k = 400 / 150 / 15 N/m, hanging from two corners under
// gravity; no wind, colliders or corrections, no blow-up check, so a step is the
// integrator's work only (forces, Jacobians, solve). Each run first lets the cloth fall for
// 30 steps, so the solver sees a moving, stretched cloth.
//   build/bench/net_bench                                  all sizes and integrators
//   build/bench/net_bench --benchmark_filter='/64$'        the r = 64 cloth only
// Counters: cg_iterations (per step, implicit_euler), force_evals (per step).
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "net.hpp"

namespace {

using namespace springlab;

net::NetParameters benchCloth(int r) {
  net::NetParameters p;
  p.width = 1.0;
  p.height = 1.0;
  p.resolution = r;
  p.origin = Vec3(-0.5, 0.0, 0.0);
  p.uAxis = Vec3::UnitX();
  p.vAxis = Vec3::UnitZ();
  p.massModel = net::MassModel::Density;
  p.arealDensity = 0.2;
  p.springs[kStructural] = {true, 400.0, 0.3};
  p.springs[kShear] = {true, 150.0, 0.3};
  p.springs[kBend] = {true, 15.0, 0.05};
  p.pins = {net::Pin::Corner00, net::Pin::Corner10};
  p.gravitation = Vec3(0.0, -9.81, 0.0);
  p.wind.strength = 0.0;
  p.wind.drag = 0.0;
  p.stretchLimiting = false;
  p.selfCollision = false;
  return p;
}

// One step of `integrator` at dt on an r x r cloth (state.range(0) = r).
void stepCloth(benchmark::State& bench, const std::string& integrator, double dt) {
  Registry registry;
  registerFramework(registry);
  net::registerLab(registry);
  const int r = static_cast<int>(bench.range(0));
  net::Net cloth(3, benchCloth(r));
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
  bench.SetLabel(integrator + ", dt = " + std::to_string(dt) + " s");
}

// Symplectic Euler at a dt it survives at every size (2 / w_max is about 0.2 ms at r = 64).
void SymplecticEuler(benchmark::State& s) { stepCloth(s, "symplectic_euler", 1e-4); }
// The implicit methods at the frame step of the cloth thesis, 1/60 s.
void ImplicitEuler(benchmark::State& s) { stepCloth(s, "implicit_euler", 1.0 / 60.0); }
void ImplicitEulerBlocks(benchmark::State& s) { stepCloth(s, "implicit_euler_blocks", 1.0 / 60.0); }

BENCHMARK(SymplecticEuler)->Arg(8)->Arg(16)->Arg(32)->Arg(64)->Unit(benchmark::kMillisecond);
BENCHMARK(ImplicitEuler)->Arg(8)->Arg(16)->Arg(32)->Arg(64)->Unit(benchmark::kMillisecond);
BENCHMARK(ImplicitEulerBlocks)->Arg(8)->Arg(16)->Arg(32)->Arg(64)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
