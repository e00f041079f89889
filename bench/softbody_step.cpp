// One step of Lab 3's pressure ball (scenes/softbody_ball.json: symplectic Euler,
// dt = 0.5 ms, floor contact, gas) at three mesh subdivisions: 162, 642 and 2562 masses.
#include "bench_support.hpp"

namespace springlab::bench {
namespace {

void BallStep(benchmark::State& bench) {
  timeScene(bench, "softbody_ball.json", {"softbody.mesh.subdivisions=" + std::to_string(bench.range(0))}, 100);
}
BENCHMARK(BallStep)->ArgNames({"subdivisions"})->DenseRange(2, 4)->UseRealTime()->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace springlab::bench
