// The spring force pass of the cloth, alone: Simulation::evaluateForces on an r x r cloth
// (zero the forces, one spring-damper force per spring, gravity on each mass), for r = 64,
// 256 and 1024 on 1 and 2 threads. Reported per spring; `./springlab bench` compares it with
// the memory-traffic floor: the bytes the pass must move (below) at the triad's bandwidth.
#include "bench_support.hpp"

namespace springlab::bench {
namespace {

// Bytes one pass moves at least, streaming once through every array it touches: each
// spring's k, L0 and kd (the pass reads its copies of them; a run's ends are implied by its
// first mass), and per mass its position, velocity and force (zeroed, then added to).
double trafficBytes(const Simulation& sim) {
  const double n = sim.numOfMasses();
  return static_cast<double>(sim.springs().size() * 3 * sizeof(double)) + n * 4.0 * sizeof(Vec3);
}

void SpringForcePass(benchmark::State& bench) {
  const int r = static_cast<int>(bench.range(0));
  useThreads(static_cast<int>(bench.range(1)));
  net::Net sim(3, cloth(r, 0));
  // A stretched, moving state: let it fall a little first.
  for (int n = 0; n < 5; ++n) sim.operate(1.0 / 60.0);
  for (auto _ : bench) {
    sim.evaluateForces(sim.state, sim.force);
    benchmark::ClobberMemory();
  }
  const double springs = static_cast<double>(sim.springs().size());
  bench.counters["springs"] = springs;
  bench.counters["masses"] = sim.numOfMasses();
  bench.counters["bytes_per_spring"] = trafficBytes(sim) / springs;
  bench.counters["ns_per_spring"] = benchmark::Counter(springs * 1e-9, benchmark::Counter::kIsIterationInvariantRate |
                                                                           benchmark::Counter::kInvert);
  useThreads(1);
}
BENCHMARK(SpringForcePass)
    ->ArgNames({"r", "threads"})
    ->ArgsProduct({{64, 256, 1024}, {1, 2}})
    ->UseRealTime()
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace springlab::bench
