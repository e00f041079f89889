// The cloth's 5 s drape by method, on the two materials of the Bullet comparison
// (bench/bullet_cloth.cpp, built with SPRINGLAB_BULLET_BENCH): README's table. One iteration
// is a whole 5 s run from the flat start, one thread; counters: ms_per_frame (CPU time / 300
// frames of 1/60 s) and drape_m (the lowest point after 5 s, m; the pins are at 0).
//   ClothDrape/r/material/method: method 0 implicit_euler_blocks, 1 implicit_euler, 2 xpbd,
//     3 projective_dynamics.
// material 0 "thesis": 1 kg per mass, k = 75/22/8 N/m, one step of 1/60 s per frame;
// material 1 "fabric": scenes/net_hanging.json without its sphere (0.2 kg/m^2, k = 400/40/2,
// two steps of 1/120 s per frame). Both: 1 m x 1 m, held at two corners, 10 % stretch limit.
#include <ctime>
#include <memory>

#include "bench_support.hpp"

namespace springlab::bench {
namespace {

constexpr int kFrames = 300;  // 5 s of 1/60 s frames

// Steps per frame and the step of each material.
int stepsPerFrame(int material) { return material == 0 ? 1 : 2; }
double stepOf(int material) { return 1.0 / 60.0 / stepsPerFrame(material); }

const char* const kMethods[] = {"implicit_euler_blocks", "implicit_euler", "xpbd", "projective_dynamics"};

void ClothDrape(benchmark::State& bench) {
  const int r = static_cast<int>(bench.range(0)), material = static_cast<int>(bench.range(1));
  const std::string method = kMethods[bench.range(2)];
  useThreads(1);
  double drape = 0.0, cpu = 0.0;
  for (auto _ : bench) {
    bench.PauseTiming();
    std::unique_ptr<Simulation> sim;
    if (material == 0) {
      net::NetParameters p = cloth(r, 0);
      p.stretchLimiting = true;
      p.maxStretch = 0.1;
      sim = std::make_unique<net::Net>(3, p);
    } else {
      LoadedScene scene = loadScene("net_hanging.json", {"net.colliders.spheres=[]", "net.resolution=" + std::to_string(r)});
      sim = std::move(scene.sim);
    }
    sim->setIntegrator(registry().makeIntegrator(method));
    const std::clock_t start = std::clock();
    bench.ResumeTiming();
    for (int n = 0; n < kFrames * stepsPerFrame(material); ++n) sim->operate(stepOf(material));
    bench.PauseTiming();
    cpu += static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
    for (const Observable& o : sim->observables()) {
      if (o.name == "drape_height") drape = o.value;
    }
    bench.ResumeTiming();
  }
  bench.counters["ms_per_frame"] = 1e3 * cpu / (static_cast<double>(bench.iterations()) * kFrames);
  bench.counters["drape_m"] = drape;
}
BENCHMARK(ClothDrape)
    ->ArgNames({"r", "material", "method"})
    ->ArgsProduct({{32, 64}, {0, 1}, {0, 1, 2, 3}})
    ->Args({128, 0, 0})
    ->Args({128, 1, 2})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace springlab::bench
