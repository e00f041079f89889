// The fabric's implicit solve by preconditioner and tolerance, and the 5 s drape of every net
// method on the fabric (issue 16, helper cloth-solver).
//   NetFabricSolve/r/preconditioner/tolerance_exp: scenes/net_hanging.json without its sphere
//     (0.2 kg/m^2, k = 400/40/2 N/m, dt = 1/120 s), one thread, the whole 5 s run from the
//     scene's start (600 steps) per iteration. preconditioner 0 block Jacobi, 1 smoothed
//     aggregation; CG stops at a residual of 10^-tolerance_exp relative to |b|. Counters:
//     ms_per_step (CPU time / 600), cg_per_step, drape_m (the lowest point after 5 s).
//   NetFabricMethodDrape/r/method: the same run with each method's scene defaults; method 0
//     implicit_euler (smoothed aggregation, 1e-6), 1 implicit_euler_blocks (one sweep),
//     2 implicit_euler_blocks (sweeps to 1e-4, at most 400 per step; r = 32 only, as
//     tests/studies/cloth_blocks_error_test.cpp), 3 xpbd, 4 projective_dynamics.
#include <cmath>
#include <ctime>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench_support.hpp"

namespace springlab::bench {
namespace {

// Run the fabric 5 s with `integrator` and the scene's "solver" section set to `solver`; CPU
// time, CG iterations and drape in counters.
void fabricRun(benchmark::State& bench, int r, const std::string& integrator, const nlohmann::json& solver) {
  useThreads(1);
  double drape = 0.0, cpu = 0.0;
  long iterations = 0;
  constexpr int kSteps = 600;
  for (auto _ : bench) {
    bench.PauseTiming();
    SceneDocument document = SceneDocument::read(std::string(SPRINGLAB_SCENES_DIR) + "/net_hanging.json");
    document.set("net.colliders.spheres=[]");
    document.set("net.resolution=" + std::to_string(r));
    for (const auto& [key, value] : solver.items()) document.json["solver"][key] = value;
    LoadedScene scene = registry().loadScene(document);
    scene.sim->setIntegrator(registry().makeIntegrator(integrator));
    const std::clock_t start = std::clock();
    bench.ResumeTiming();
    for (int n = 0; n < kSteps; ++n) scene.sim->operate(scene.settings.dt);
    bench.PauseTiming();
    cpu += static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
    iterations += scene.sim->stats.solverIterations;
    for (const Observable& o : scene.sim->observables()) {
      if (o.name == "drape_height") drape = o.value;
    }
    bench.ResumeTiming();
  }
  const double runs = static_cast<double>(bench.iterations());
  bench.counters["ms_per_step"] = 1e3 * cpu / (runs * kSteps);
  bench.counters["cg_per_step"] = static_cast<double>(iterations) / (runs * kSteps);
  bench.counters["drape_m"] = drape;
}

void NetFabricSolve(benchmark::State& bench) {
  const int r = static_cast<int>(bench.range(0));
  const std::string preconditioner = bench.range(1) == 0 ? "block_jacobi" : "smoothed_aggregation";
  const double tolerance = std::pow(10.0, -static_cast<double>(bench.range(2)));
  fabricRun(bench, r, "implicit_euler", {{"preconditioner", preconditioner}, {"tolerance", tolerance}});
}
BENCHMARK(NetFabricSolve)
    ->ArgNames({"r", "preconditioner", "tolerance_exp"})
    ->ArgsProduct({{32, 64}, {0, 1}, {6}})
    ->ArgsProduct({{64}, {1}, {2, 3, 4, 8}})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

void NetFabricMethodDrape(benchmark::State& bench) {
  const int r = static_cast<int>(bench.range(0));
  switch (bench.range(1)) {
    case 0: fabricRun(bench, r, "implicit_euler", {{"preconditioner", "smoothed_aggregation"}}); break;
    case 1: fabricRun(bench, r, "implicit_euler_blocks", nlohmann::json::object()); break;
    case 2:
      fabricRun(bench, r, "implicit_euler_blocks", {{"block_sweeps", 400}, {"block_tolerance", 1e-4}});
      break;
    case 3: fabricRun(bench, r, "xpbd", nlohmann::json::object()); break;
    default: fabricRun(bench, r, "projective_dynamics", nlohmann::json::object()); break;
  }
}
BENCHMARK(NetFabricMethodDrape)
    ->ArgNames({"r", "method"})
    ->ArgsProduct({{32}, {0, 1, 2, 3, 4}})
    ->ArgsProduct({{64}, {0, 1, 3, 4}})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace springlab::bench
