// FLIP metric throughput (CPU): LDR-FLIP and HDR-FLIP (ACES, automatic exposures) on a
// 1920x1080 pair generated in code (smooth colour gradient, test = reference + noise).
// GIB_BENCH_SIZE=WxH overrides the size. Registered with the other benchmarks in
// gibench-bench; BENCHMARK_MAIN lives in bench_trace.cpp.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <thread>

#if defined(__linux__)
#include <sched.h>
#endif

#include "metrics/flip.h"

namespace gib {
namespace {

std::pair<uint32_t, uint32_t> flip_bench_size() {
  if (const char* s = std::getenv("GIB_BENCH_SIZE")) {
    unsigned w = 0, h = 0;
    if (std::sscanf(s, "%ux%u", &w, &h) == 2 && w && h) return {w, h};
  }
  return {1920u, 1080u};
}

// The CPUs flip() spreads its rows over (it follows the affinity mask too).
int usable_cpu_count() {
#if defined(__linux__)
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof(set), &set) == 0) return CPU_COUNT(&set);
#endif
  return int(std::thread::hardware_concurrency());
}

// Smooth gradient in [0, 1] (LDR) or spanning ~1e-3..1e2 (HDR), plus a noisy copy.
std::pair<FloatImage, FloatImage> make_pair(uint32_t w, uint32_t h, bool hdr) {
  FloatImage ref(w, h, 3), test(w, h, 3);
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const float fx = float(x) / float(w - 1), fy = float(y) / float(h - 1);
      float c[3] = {fx, fy, 0.5f * (1.0f - fx) + 0.25f * std::sin(6.0f * fy)};
      for (uint32_t k = 0; k < 3; ++k) {
        float v = std::fabs(c[k]);
        if (hdr) v = 1e-3f * std::pow(1e5f, 0.5f * (fx + fy)) * (0.5f + v);
        ref.at(x, y, k) = v;
        float t = hdr ? v * (1.0f + 0.2f * u(rng)) : v + 0.05f * u(rng);
        test.at(x, y, k) = hdr ? t : std::fmin(std::fmax(t, 0.0f), 1.0f);
      }
    }
  return {std::move(ref), std::move(test)};
}

void bm_flip(benchmark::State& state, bool hdr) {
  auto [w, h] = flip_bench_size();
  auto [ref, test] = make_pair(w, h, hdr);
  FlipOptions opt;
  opt.mode = hdr ? FlipOptions::Mode::hdr : FlipOptions::Mode::ldr;
  FlipResult r;
  for (auto _ : state) {
    r = flip(ref, test, opt);
    benchmark::DoNotOptimize(r.mean);
  }
  state.counters["mean"] = r.mean;
  state.counters["exposures"] = r.num_exposures;
  state.counters["cpus"] = double(usable_cpu_count());
  state.counters["Mpix/s"] = benchmark::Counter(double(w) * h * double(state.iterations()) / 1e6,
                                                benchmark::Counter::kIsRate);
  state.SetLabel(std::to_string(w) + "x" + std::to_string(h));
}

int register_flip() {
  benchmark::RegisterBenchmark("flip/ldr", [](benchmark::State& st) { bm_flip(st, false); })
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  benchmark::RegisterBenchmark("flip/hdr_aces_auto", [](benchmark::State& st) { bm_flip(st, true); })
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  return 0;
}
const int registered_flip = register_flip();

}  // namespace
}  // namespace gib
