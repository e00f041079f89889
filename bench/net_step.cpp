// One step of the cloth with each integrator, and the cloth thesis' frame broken down into
// its phases (forces, integration, collisions, stretch limit, normals), on the reference.
//   NetStep<Integrator>/r/material/threads: the bare cloth (bench_support.hpp), the
//     integrator's own work only. Symplectic Euler at a dt it survives (1/60 s on the thesis
//     material, 0.1 ms on the fabric); the implicit ones at the thesis' frame, 1/60 s.
//   NetFrame/r/threads: the thesis' scene with implicit Euler (per-particle blocks), one step
//     of 1/60 s per frame; its counters give the table's columns.
#include <ctime>

#include "bench_support.hpp"

namespace springlab::bench {
namespace {

void stepCloth(benchmark::State& bench, const std::string& integrator) {
  const int r = static_cast<int>(bench.range(0));
  const int material = static_cast<int>(bench.range(1));
  useThreads(static_cast<int>(bench.range(2)));
  net::Net sim(3, cloth(r, material));
  sim.setIntegrator(registry().makeIntegrator(integrator));
  const double dt = integrator == "symplectic_euler" && material == 1 ? 1e-4 : 1.0 / 60.0;
  timeSteps(bench, sim, dt, 30);
  useThreads(1);
}

void NetStepSymplecticEuler(benchmark::State& s) { stepCloth(s, "symplectic_euler"); }
void NetStepImplicitEuler(benchmark::State& s) { stepCloth(s, "implicit_euler"); }
void NetStepImplicitEulerBlocks(benchmark::State& s) { stepCloth(s, "implicit_euler_blocks"); }

// The thesis' sizes and two larger ones on the thesis material, one thread; r = 256 and
// 1024... on two threads too; the fabric at r = 64 shows what conditioning does to CG.
void sizes(benchmark::internal::Benchmark* b) {
  b->ArgNames({"r", "material", "threads"});
  for (int r : {8, 16, 32, 48, 64, 128, 256}) b->Args({r, 0, 1});
  b->Args({256, 0, 2});
  b->Args({64, 1, 1});
  b->UseRealTime()->Unit(benchmark::kMillisecond);
}
BENCHMARK(NetStepSymplecticEuler)->Apply(sizes);
BENCHMARK(NetStepImplicitEuler)->Apply(sizes);
BENCHMARK(NetStepImplicitEulerBlocks)->Apply(sizes);

void NetFrame(benchmark::State& bench) {
  const int r = static_cast<int>(bench.range(0));
  useThreads(static_cast<int>(bench.range(1)));
  net::Net sim(3, thesisFrame(r));
  sim.setIntegrator(registry().makeIntegrator("implicit_euler_blocks"));
  timeSteps(bench, sim, 1.0 / 60.0, 30);
  useThreads(1);
}
BENCHMARK(NetFrame)
    ->ArgNames({"r", "threads"})
    ->ArgsProduct({{8, 16, 32, 48, 64, 128, 256}, {1}})
    ->Args({256, 2})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// ---- The fabric's 5 s drape per method (XPBD and projective dynamics beside the others) -----
// scenes/net_hanging.json without its sphere (0.2 kg/m^2, k = 400/40/2 N/m, 10 % stretch
// limit, dt = 1/120 s, 2 steps per 1/60 s frame), one thread: one iteration is the whole 5 s
// run from the scene's start. Counters: ms_per_frame (CPU time / 300 frames) and drape_m (the
// lowest point after 5 s), to compare with the full implicit solve's drape.
//   NetFabricDrape/r/method/iterations/substeps/warm: method 0 implicit_euler, 1 xpbd,
//     2 projective_dynamics, 3 implicit_euler_blocks (iterations, substeps and XPBD's warm
//     start: the scene's integrator_options).
const char* const kDrapeMethods[] = {"implicit_euler", "xpbd", "projective_dynamics", "implicit_euler_blocks"};

void NetFabricDrape(benchmark::State& bench) {
  const int r = static_cast<int>(bench.range(0));
  const std::string method = kDrapeMethods[bench.range(1)];
  const std::string iterations = std::to_string(bench.range(2)), substeps = std::to_string(bench.range(3));
  const int warmStart = static_cast<int>(bench.range(4));
  useThreads(1);
  double drape = 0.0, cpu = 0.0;
  constexpr int kSteps = 600, kFrames = 300;
  for (auto _ : bench) {
    bench.PauseTiming();
    LoadedScene scene = loadScene("net_hanging.json", {"net.colliders.spheres=[]", "net.resolution=" + std::to_string(r),
                                                       "integrator_options.xpbd.iterations=" + iterations,
                                                       "integrator_options.xpbd.substeps=" + substeps,
                                                       "integrator_options.projective_dynamics.iterations=" + iterations});
    scene.sim->integratorOptions["xpbd"]["warm_start"] = warmStart;
    scene.sim->setIntegrator(registry().makeIntegrator(method));
    const std::clock_t start = std::clock();
    bench.ResumeTiming();
    for (int n = 0; n < kSteps; ++n) scene.sim->operate(scene.settings.dt);
    bench.PauseTiming();
    cpu += static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
    for (const Observable& o : scene.sim->observables()) {
      if (o.name == "drape_height") drape = o.value;
    }
    bench.ResumeTiming();
  }
  bench.counters["ms_per_frame"] = 1e3 * cpu / (static_cast<double>(bench.iterations()) * kFrames);
  bench.counters["drape_m"] = drape;
}
BENCHMARK(NetFabricDrape)
    ->ArgNames({"r", "method", "iterations", "substeps", "warm"})
    ->Args({32, 0, 1, 1, 0})
    ->Args({32, 3, 1, 1, 0})
    ->Args({32, 1, 10, 1, 0})
    ->Args({32, 1, 1, 16, 0})
    ->Args({32, 1, 1, 8, 1})
    ->Args({32, 1, 1, 16, 1})
    ->Args({32, 2, 1, 1, 0})
    ->Args({32, 2, 2, 1, 0})
    ->Args({64, 0, 1, 1, 0})
    ->Args({64, 3, 1, 1, 0})
    ->Args({64, 1, 10, 1, 0})
    ->Args({64, 1, 1, 32, 0})
    ->Args({64, 1, 1, 64, 0})
    ->Args({64, 1, 1, 16, 1})
    ->Args({64, 2, 1, 1, 0})
    ->Args({64, 2, 2, 1, 0})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace springlab::bench

// ---- The fabric's implicit step by preconditioner (issue 16) ----------------------------
namespace springlab::bench {
namespace {

//   NetImplicitFabric/r/preconditioner: implicit Euler on the fabric at dt = 1/120 s, CG to
//   1e-6 with block Jacobi (0) or smoothed aggregation (1).
void NetImplicitFabric(benchmark::State& bench) {
  const int r = static_cast<int>(bench.range(0));
  useThreads(1);
  net::Net sim(3, cloth(r, 1));
  sim.solver.preconditioner = bench.range(1) == 0 ? "block_jacobi" : "smoothed_aggregation";
  sim.setIntegrator(registry().makeIntegrator("implicit_euler"));
  timeSteps(bench, sim, 1.0 / 120.0, 30);
}
BENCHMARK(NetImplicitFabric)
    ->ArgNames({"r", "preconditioner"})
    ->ArgsProduct({{32, 64, 128}, {0, 1}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace springlab::bench
