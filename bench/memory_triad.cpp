// The machine's memory bandwidth, measured in the same run as the kernels it judges:
// STREAM's triad a[i] = b[i] + s c[i] on arrays far larger than the caches (3 x 128 MiB per
// thread; this machine's L3 is 32 MiB). Counted as STREAM counts it, 24 bytes per element
// (read b and c, write a); `./springlab bench` divides each kernel's bytes by this rate.
// With ->Threads(2) each thread streams its own arrays and the rates add up.
#include <benchmark/benchmark.h>

#include <cstddef>
#include <vector>

namespace {

constexpr std::size_t kElements = std::size_t{1} << 24;  // 128 MiB of doubles per array

void MemoryTriad(benchmark::State& bench) {
  std::vector<double> a(kElements, 0.0), b(kElements, 1.0), c(kElements, 2.0);
  const double s = 3.0;
  for (auto _ : bench) {
    double* __restrict pa = a.data();
    const double* __restrict pb = b.data();
    const double* __restrict pc = c.data();
    for (std::size_t i = 0; i < kElements; ++i) pa[i] = pb[i] + s * pc[i];
    benchmark::DoNotOptimize(pa);
    benchmark::ClobberMemory();
  }
  bench.SetBytesProcessed(static_cast<std::int64_t>(bench.iterations()) * static_cast<std::int64_t>(3 * sizeof(double) * kElements));
}
BENCHMARK(MemoryTriad)->Threads(1)->Threads(2)->UseRealTime()->Unit(benchmark::kMillisecond)->MinTime(0.5);

}  // namespace
