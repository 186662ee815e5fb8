// Ray-tracing throughput benchmarks: BVH build (CPU), GPU traversal of primary, incoherent
// and shadow rays, and path-tracer samples per second. GPU time per iteration comes from
// timestamp queries (UseManualTime). Device: GIB_DEVICE (index or name substring), else the
// default. Size: 256x144 on a CPU device, 1920x1080 on a GPU (GIB_BENCH_SIZE=WxH overrides).
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <random>

#include "bench/trace_rays_shared.h"
#include "bench/bench_common.h"
#include "perf/project_files.h"
#include "renderer/graph/executor.h"
#include "renderer/scene/bvh.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/techniques/reference/reference.h"
#include "renderer/techniques/technique.h"

namespace gib {
namespace {


std::pair<uint32_t, uint32_t> bench_size() {
  if (const char* s = std::getenv("GIB_BENCH_SIZE")) {
    unsigned w = 0, h = 0;
    if (std::sscanf(s, "%ux%u", &w, &h) == 2 && w && h) return {w, h};
  }
  return bench_gpu().info().is_software() ? std::pair{256u, 144u} : std::pair{1920u, 1080u};
}

std::string scene_file(const std::string& name) {
  return perf::find_project_file("cases/scenes/" + name + ".json", "scene '" + name + "'");
}

struct RaySet {
  std::vector<glsl::TraceRay> rays;
};

Vec3 camera_dir(const Camera& c, float px, float py, uint32_t w, uint32_t h) {
  Vec3 f = normalize(c.target - c.position), r = normalize(cross(f, c.up)), u = cross(r, f);
  float t = std::tan(c.fov_y_deg * 3.14159265f / 360.0f), aspect = float(w) / float(h);
  return normalize(f + r * ((2.0f * px / w - 1.0f) * t * aspect) - u * ((2.0f * py / h - 1.0f) * t));
}

glsl::TraceRay make_ray(Vec3 o, Vec3 d, float tmax = 3.0e38f) { return {{o.x, o.y, o.z, 0.0f}, {d.x, d.y, d.z, tmax}}; }

// kind 0: primary; 1: incoherent (cosine directions from primary hits); 2: shadow rays from
// primary hits towards a fixed point above the scene centre (any hit).
RaySet make_rays(const Scene& scene, const FlatScene& flat, const Bvh& bvh, int kind, uint32_t w, uint32_t h) {
  RaySet set;
  std::mt19937 rng(1234);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  Vec3 lo{1e30f, 1e30f, 1e30f}, hi{-1e30f, -1e30f, -1e30f};
  for (auto& v : flat.vertices) { lo = vmin(lo, {v.px, v.py, v.pz}); hi = vmax(hi, {v.px, v.py, v.pz}); }
  Vec3 light = (lo + hi) * 0.5f + Vec3{0, (hi.y - lo.y) * 0.45f, 0};
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      Vec3 d = camera_dir(scene.camera, x + 0.5f, y + 0.5f, w, h);
      if (kind == 0) { set.rays.push_back(make_ray(scene.camera.position, d)); continue; }
      Hit hit = intersect_bvh(bvh, flat, {scene.camera.position, d}, 0.0f, 3.0e38f);
      if (!hit.hit) continue;
      const GpuTriangle& t = flat.triangles[hit.triangle];
      auto P = [&](uint32_t i) { auto& v = flat.vertices[i]; return Vec3{v.px, v.py, v.pz}; };
      Vec3 n = normalize(cross(P(t.i1) - P(t.i0), P(t.i2) - P(t.i0)));
      if (dot(n, d) > 0) n = -n;
      Vec3 p = scene.camera.position + d * hit.t + n * 1e-3f;
      if (kind == 1) {
        float r = std::sqrt(u01(rng)), phi = 6.2831853f * u01(rng);
        Vec3 a = std::fabs(n.x) > 0.5f ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
        Vec3 tx = normalize(cross(a, n)), ty = cross(n, tx);
        Vec3 dir = normalize(tx * (r * std::cos(phi)) + ty * (r * std::sin(phi)) + n * std::sqrt(1 - r * r));
        set.rays.push_back(make_ray(p, dir));
      } else {
        Vec3 to = light - p;
        float len = length(to);
        set.rays.push_back(make_ray(p, to / len, len));
      }
    }
  return set;
}

void bm_trace(benchmark::State& state, const std::string& scene_name, int kind) {
  Gpu& gpu = bench_gpu();
  auto [w, h] = bench_size();
  Scene scene = load_scene(scene_file(scene_name));
  FlatScene flat = flatten(scene, 0.0f);
  Bvh bvh = build_bvh(flat);
  RaySet rays = make_rays(scene, flat, bvh, kind, w, h);
  std::vector<std::shared_ptr<Buffer>> bufs;
  auto put = [&](const void* data, size_t bytes) {
    auto b = gpu.create_buffer(std::max<size_t>(bytes, 16), BufferUsage::storage, "bench");
    if (bytes) gpu.upload(*b, data, bytes);
    bufs.push_back(b);
    return b.get();
  };
  std::vector<Bind> binds;
  const void* datas[] = {flat.vertices.data(), flat.triangles.data(), flat.instances.data(), flat.materials.data(),
                         bvh.nodes.data(), bvh.tri_index.data(), flat.lights.data()};
  size_t sizes[] = {flat.vertices.size() * sizeof(GpuVertex), flat.triangles.size() * sizeof(GpuTriangle),
                    flat.instances.size() * sizeof(GpuInstance), flat.materials.size() * sizeof(GpuMaterial),
                    bvh.nodes.size() * sizeof(GpuBvhNode), bvh.tri_index.size() * 4, flat.lights.size() * sizeof(GpuLight)};
  ComputePipelineDesc desc{"trace_rays.comp", {}, sizeof(glsl::TraceRaysPush)};
  for (uint32_t i = 0; i < 7; ++i) {
    binds.push_back({glsl::kTraceRaysBindScene + i, put(datas[i], sizes[i])});
    desc.bindings.push_back({glsl::kTraceRaysBindScene + i, DescriptorKind::storage_buffer});
  }
  binds.push_back({glsl::kTraceRaysBindRays, put(rays.rays.data(), rays.rays.size() * sizeof(glsl::TraceRay))});
  auto hits = gpu.create_buffer(rays.rays.size() * 4 + 16, BufferUsage::storage, "hits");
  binds.push_back({glsl::kTraceRaysBindHits, hits.get()});
  desc.bindings.push_back({glsl::kTraceRaysBindRays, DescriptorKind::storage_buffer});
  desc.bindings.push_back({glsl::kTraceRaysBindHits, DescriptorKind::storage_buffer});
  auto pipeline = gpu.compute_pipeline(desc);
  glsl::TraceRaysPush push{uint32_t(rays.rays.size()), kind == 2 ? 1u : 0u};
  {  // warm-up: lavapipe compiles shaders lazily on first use
    auto cmd = gpu.begin(0);
    cmd->bind(*pipeline, binds, &push, sizeof(push));
    cmd->dispatch(div_up(push.ray_count, glsl::kTraceRaysGroup));
    gpu.submit(std::move(cmd));
  }
  double total_s = 0;
  for (auto _ : state) {
    auto cmd = gpu.begin(2);
    cmd->bind(*pipeline, binds, &push, sizeof(push));
    cmd->timestamp(0);
    cmd->dispatch(div_up(push.ray_count, glsl::kTraceRaysGroup));
    cmd->timestamp(1);
    // CPU device: host clock around submit-and-wait (llvmpipe timestamps misattribute its
    // lazily-run work; see Executor::run_frame). GPU: the timestamp pair.
    auto t0 = std::chrono::steady_clock::now();
    auto ns = gpu.submit(std::move(cmd));
    double s = gpu.info().is_software()
                   ? std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()
                   : (ns[1] - ns[0]) * 1e-9;
    total_s += s;
    state.SetIterationTime(s);
  }
  state.counters["rays"] = double(rays.rays.size());
  state.counters["triangles"] = double(flat.triangles.size());
  state.counters["Mrays_per_s"] = double(rays.rays.size()) * state.iterations() / total_s * 1e-6;
  state.SetLabel(fmt::format("{}x{}", w, h));
}

void bm_path_trace(benchmark::State& state, const std::string& scene_name) {
  Gpu& gpu = bench_gpu();
  auto [w, h] = bench_size();
  Scene scene = load_scene(scene_file(scene_name));
  const Technique& ref = find_technique("reference");
  Settings s = apply_options(ref, Settings{}, {});  // the reference's defaults: 1 spp per frame, 8 bounces
  s.width = w;
  s.height = h;
  Executor ex(gpu, scene, s, make_passes(ref), {"radiance"});
  ex.run_frame();  // warm-up: pipeline creation and lavapipe's lazy shader compile
  double total_s = 0;
  for (auto _ : state) {
    FrameResult fr = ex.run_frame();
    double sec = fr.passes[0].ms * 1e-3;  // path_trace
    total_s += sec;
    state.SetIterationTime(sec);
  }
  state.counters["Msamples_per_s"] = double(w) * h * state.iterations() / total_s * 1e-6;
  state.SetLabel(fmt::format("{}x{} 1spp/iter, {} bounces max", w, h, s.params<ReferenceSettings>().max_bounces));
}

void bm_bvh_build(benchmark::State& state, const std::string& scene_name) {
  Scene scene = load_scene(scene_file(scene_name));
  FlatScene flat = flatten(scene, 0.0f);
  Bvh bvh;
  for (auto _ : state) bvh = build_bvh(flat);
  state.counters["triangles"] = double(flat.triangles.size());
  state.counters["nodes"] = double(bvh.stats.nodes);
  state.counters["sah_cost"] = bvh.stats.sah_cost;
}

const char* kScenes[] = {"cornell", "features_zoo"};

int register_all() {
  for (const char* sc : kScenes) {
    std::string s = sc;
    benchmark::RegisterBenchmark(("bvh_build/" + s).c_str(), [s](benchmark::State& st) { bm_bvh_build(st, s); })
        ->Unit(benchmark::kMillisecond);
    const char* kinds[] = {"trace_primary", "trace_incoherent", "trace_shadow"};
    for (int k = 0; k < 3; ++k)
      benchmark::RegisterBenchmark((std::string(kinds[k]) + "/" + s).c_str(),
                                   [s, k](benchmark::State& st) { bm_trace(st, s, k); })
          ->UseManualTime()->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("path_trace/" + s).c_str(), [s](benchmark::State& st) { bm_path_trace(st, s); })
        ->UseManualTime()->Unit(benchmark::kMillisecond);
  }
  return 0;
}
const int registered = register_all();

}  // namespace
}  // namespace gib

BENCHMARK_MAIN();
