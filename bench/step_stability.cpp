// The stability limit of the step that runs (springlab/step_stability.hpp) on the hanging
// cloth, as the stability chart and the blow-up message compute it: settling, the stiffest
// and most damped modes (Lanczos), and a bisection on dt of finite-difference runs.
//   StepStableDt/r/method: scenes/net_hanging.json (its sphere and stretch limit as shipped),
//     r x r masses; method 0 symplectic_euler, 1 rk4, 2 implicit_euler (the scene's own),
//     3 explicit_euler, 4 midpoint, 5 velocity_verlet, 6 position_verlet (the promise,
//     a prediction under a second on the 64 x 64 cloth, is for every explicit method).
//     Counters: the limit found (ms), and CPU time per prediction (s), beside wall time.
//   SimLimitCheck/scene/full: what `sim` computes before it runs, at the scene's own dt and
//     method: full 0 the step's spectral radius at dt (enough when it is within 1), 1 the limit
//     (the bisection it took before). scene 0 rope.json (480 coordinates, the dense Jacobian),
//     1 net_hanging.json as shipped (implicit Euler). Counter: the radius or the limit (ms).
#include <ctime>

#include <springlab/step_stability.hpp>

#include "bench_support.hpp"

namespace springlab::bench {
namespace {

const char* const kStabilityMethods[] = {"symplectic_euler", "rk4",      "implicit_euler", "explicit_euler",
                                         "midpoint",         "velocity_verlet", "position_verlet"};

void StepStableDt(benchmark::State& bench) {
  const int r = static_cast<int>(bench.range(0));
  const std::string method = kStabilityMethods[bench.range(1)];
  useThreads(1);
  double limit = 0.0, cpu = 0.0;
  for (auto _ : bench) {
    bench.PauseTiming();
    LoadedScene scene = loadScene("net_hanging.json", {"net.resolution=" + std::to_string(r)});
    scene.sim->setIntegrator(registry().makeIntegrator(method));
    const std::clock_t start = std::clock();
    bench.ResumeTiming();
    limit = stepStableDt(*scene.sim);
    bench.PauseTiming();
    cpu += static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
    bench.ResumeTiming();
  }
  bench.SetLabel(method);  // the report names the method from here
  bench.counters["limit_ms"] = 1e3 * limit;
  bench.counters["cpu_s"] = cpu / static_cast<double>(bench.iterations());
}
BENCHMARK(StepStableDt)
    ->ArgNames({"r", "method"})
    ->ArgsProduct({{16, 32, 64}, {0, 1, 2, 3, 4, 5, 6}})
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

const char* const kSimScenes[] = {"rope.json", "net_hanging.json"};

void SimLimitCheck(benchmark::State& bench) {
  const bool full = bench.range(1) != 0;
  useThreads(1);
  double value = 0.0, cpu = 0.0;
  for (auto _ : bench) {
    bench.PauseTiming();
    LoadedScene scene = loadScene(kSimScenes[bench.range(0)]);
    const double dt = scene.settings.dt;
    const std::clock_t start = std::clock();
    bench.ResumeTiming();
    value = full ? 1e3 * stepStableDt(*scene.sim) : stepSpectralRadius(*scene.sim, dt).radius;
    bench.PauseTiming();
    cpu += static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
    bench.ResumeTiming();
  }
  bench.SetLabel(std::string(kSimScenes[bench.range(0)]) + (full ? " limit" : " radius at dt"));
  bench.counters[full ? "limit_ms" : "radius"] = value;
  bench.counters["cpu_s"] = cpu / static_cast<double>(bench.iterations());
}
BENCHMARK(SimLimitCheck)
    ->ArgNames({"scene", "full"})
    ->ArgsProduct({{0, 1}, {0, 1}})
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace springlab::bench
