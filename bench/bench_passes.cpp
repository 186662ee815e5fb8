// Pass-cost benchmarks: one Google Benchmark per (technique, pass, workload), named
// pass/<technique>/<pass>/<W>x<H>. Workloads are the distinct target resolutions of the console
// profiles (data/console-profiles.json, or GIB_DATA_DIR). Each iteration runs one
// frame of the technique and reports that pass's GPU time (timestamps; host clock per pass on
// a CPU device, see Executor::run_frame) through UseManualTime, after warm-up frames.
// Environment: GIB_BENCH_SCALE (fraction of the workload's resolution actually rendered;
// default 1 on a GPU, 1/8 on a CPU device), GIB_BENCH_FRAMES (iterations, default 10),
// GIB_BENCH_WARMUP (default 1 on a CPU device, 5 on a GPU), GIB_BENCH_CASE (scene under
// cases/scenes/, the working folder's first, else the source tree's; default cornell),
// GIB_DEVICE. Use --benchmark_repetitions for perf-diff.
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <cstdlib>
#include <memory>

#include "perf/perf.h"
#include "perf/profiles.h"
#include "perf/project_files.h"
#include "bench/bench_common.h"
#include "renderer/graph/executor.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/techniques/technique.h"

namespace gib {
namespace {


uint32_t env_u32(const char* name, uint32_t fallback) {
  const char* v = std::getenv(name);
  if (!v || !*v) return fallback;
  char* end = nullptr;
  unsigned long x = std::strtoul(v, &end, 10);
  return end && *end == 0 && x > 0 ? uint32_t(x) : fallback;
}

std::string scene_path() {
  const char* c = std::getenv("GIB_BENCH_CASE");
  const std::string name = c && *c ? c : "cornell";
  return perf::find_project_file("cases/scenes/" + name + ".json", "GIB_BENCH_CASE '" + name + "'");
}

double run_scale() {
  if (const char* s = std::getenv("GIB_BENCH_SCALE"); s && *s) return perf::parse_scale(s);
  return bench_gpu().info().is_software() ? 0.125 : 1.0;
}

Settings settings_for(const Technique& t, uint32_t w, uint32_t h) {
  Settings s;
  s = apply_preset(t, "medium", s);  // the reference: 1 sample per pixel per frame (its default)
  s.width = w;
  s.height = h;
  return s;
}

// One live executor at a time: the benchmarks of one (technique, workload) are registered
// consecutively and share it; the next workload replaces it (frees its resources).
struct Live {
  std::string key;
  std::unique_ptr<Scene> scene;
  std::unique_ptr<Executor> ex;
};
Live& live(const Technique& t, uint32_t w, uint32_t h) {
  static Live l;
  std::string key = fmt::format("{}/{}x{}", t.name, w, h);
  if (l.key != key) {
    l.ex.reset();
    l.scene = std::make_unique<Scene>(load_scene(scene_path()));
    // Every contract AOV the scene supports, as `gibench bench` plans (perf::bench_outputs), so
    // passes feeding only an AOV such as `reflection` are benchmarked too.
    l.ex = std::make_unique<Executor>(bench_gpu(), *l.scene, settings_for(t, w, h), make_passes(t),
                                      perf::bench_outputs(t, l.scene->features()).resources);
    uint32_t warm = env_u32("GIB_BENCH_WARMUP", bench_gpu().info().is_software() ? 1 : 5);
    for (uint32_t i = 0; i < warm; ++i) l.ex->run_frame();
    l.key = key;
  }
  return l;
}

void bm_pass(benchmark::State& state, const Technique& t, const std::string& pass, uint32_t w, uint32_t h) {
  const double scale = run_scale();
  const uint32_t rw = std::max(8u, uint32_t(std::lround(w * scale))), rh = std::max(8u, uint32_t(std::lround(h * scale)));
  Live& l = live(t, rw, rh);
  const Plan& plan = l.ex->plan();
  const PlannedPass* pp = nullptr;
  for (auto* p : plan.running())
    if (p->name == pass) pp = p;
  if (!pp) {
    state.SkipWithError(fmt::format("{} does not run at {}x{}", pass, rw, rh).c_str());
    return;
  }
  for (auto _ : state) {
    FrameResult fr = l.ex->run_frame();
    double ms = 0;
    for (auto& p : fr.passes)
      if (p.name == pass) ms = p.ms;
    state.SetIterationTime(ms * 1e-3);
  }
  perf::PassBytes b = perf::pass_bytes(plan, *pp);
  state.counters["pixels"] = double(rw) * rh;
  state.counters["bytes_read"] = double(b.read);
  state.counters["bytes_written"] = double(b.written);
  state.counters["bytes_moved"] = double(b.total());
  state.counters["GB/s"] = benchmark::Counter(double(b.total()) * state.iterations() * 1e-9, benchmark::Counter::kIsRate);
  for (const WorkCounter& w : pp->work) state.counters[w.name] = w.per_frame;
  state.SetLabel(scale == 1 ? fmt::format("{}x{}", rw, rh)
                            : fmt::format("ran at {}x{} (scale {:g} of {}x{}; time not rescaled)", rw, rh, scale, w, h));
}

int register_passes() {
  std::vector<perf::ConsoleProfile> profiles;
  try {
    profiles = perf::load_profiles(perf::find_data_dir("") + "/console-profiles.json");
  } catch (const std::exception& e) {
    fmt::print(stderr, "bench_passes: no pass benchmarks registered: {}\n", e.what());
    return 0;
  }
  std::vector<std::pair<uint32_t, uint32_t>> sizes;
  for (auto& p : profiles)
    if (std::find(sizes.begin(), sizes.end(), std::pair{p.width, p.height}) == sizes.end()) sizes.push_back({p.width, p.height});
  std::sort(sizes.begin(), sizes.end(), [](auto& a, auto& b) { return a.first * a.second < b.first * b.second; });
  Scene scene;
  try {
    scene = load_scene(scene_path());
  } catch (const std::exception& e) {
    fmt::print(stderr, "bench_passes: no pass benchmarks registered: {}\n", e.what());
    return 0;
  }
  const uint32_t iters = env_u32("GIB_BENCH_FRAMES", 10);
  for (auto& t : techniques()) {
    for (auto [w, h] : sizes) {
      // The running passes (pure CPU: compile without a device).
      Settings s = settings_for(t, w, h);
      std::vector<PassDecl> decls;
      for (auto& p : make_passes(t)) decls.push_back(p->declare(scene, s));
      Plan plan = compile(decls, {scene.features(), perf::bench_outputs(t, scene.features()).resources, w, h});
      for (auto* pp : plan.running()) {
        const Technique* tp = &t;
        std::string pass = pp->name;
        benchmark::RegisterBenchmark(fmt::format("pass/{}/{}/{}x{}", t.name, pass, w, h).c_str(),
                                     [tp, pass, w = w, h = h](benchmark::State& st) { bm_pass(st, *tp, pass, w, h); })
            ->UseManualTime()
            ->Iterations(iters)
            ->Unit(benchmark::kMillisecond);
      }
    }
  }
  return 0;
}
const int registered = register_passes();

}  // namespace
}  // namespace gib
