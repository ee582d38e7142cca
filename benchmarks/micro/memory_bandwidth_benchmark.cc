// The machine's memory bandwidth, the bound of a pass over contacts that do not fit in cache: a
// triad a = b + s·c over arrays of 3 × 64 MB on all threads (24 bytes moved per element, the
// write-allocate of a not counted). Reported as bytes per second.
#include <benchmark/benchmark.h>

#include <vector>

namespace {

void BM_MemoryTriad(benchmark::State& state) {
  const long n = 8L << 20;  // 8 Mi doubles per array
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  const double s = 0.5;
  for (auto _ : state) {
#pragma omp parallel for schedule(static)
    for (long i = 0; i < n; ++i) a[i] = b[i] + s * c[i];
    benchmark::DoNotOptimize(a.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(state.iterations() * n * 3 * static_cast<long>(sizeof(double)));
}
BENCHMARK(BM_MemoryTriad)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
