// One step of Lab 1's rope of 80 masses (scenes/rope.json: symplectic Euler, dt = 2 ms,
// ground contact), on the reference.
#include "bench_support.hpp"

namespace springlab::bench {
namespace {

void RopeStep(benchmark::State& bench) {
  timeScene(bench, "rope.json", {"rope.masses=" + std::to_string(bench.range(0))}, 100);
}
BENCHMARK(RopeStep)->ArgNames({"masses"})->Arg(80)->UseRealTime()->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace springlab::bench
