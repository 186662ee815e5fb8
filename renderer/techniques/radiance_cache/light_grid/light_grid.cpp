#include "renderer/techniques/radiance_cache/light_grid/light_grid.h"
#include "renderer/techniques/radiance_cache/radiance_cache.h"

#include <algorithm>
#include <cmath>

namespace gib {
namespace {

using namespace glsl;

constexpr uint32_t kGroupThreads = kLightGridGroup * kLightGridGroup * kLightGridGroup;
static_assert(kLightGridBitWords * 32 == kLightGridSceneLights);
static_assert(kLightGridCellWords == kLightGridMaxLights + 1);
static_assert(kLightGridDim % kLightGridGroup == 0);
static_assert(kGroupThreads == 64);
static_assert(sizeof(LightGridPush) == 32 && sizeof(LightGridStats) == 16);

class LightGridPass final : public Pass {
 public:
  explicit LightGridPass(LightGridOptions options) : options_(options) {}

  PassDecl declare(const Scene& scene, const Settings& settings) const override {
    PassDecl d;
    d.name = "light_grid";
    d.needs = Feature::local_lights;
    glsl::LightGridParams p = make_light_grid_params(settings, static_cast<uint32_t>(scene.lights.size()));
    ResourceDesc grid{Format::buffer, SizeRule::buffer, 0, 0, uint64_t(light_grid_words(p)) * 4};
    ResourceDesc stats{Format::buffer, SizeRule::buffer, 0, 0, sizeof(LightGridStats)};
    d.slots = {{"light_grid", Access::write, grid}, {"light_grid_stats", Access::write, stats}};
    return d;
  }

  void record(RecordContext& ctx) override {
    LightGridPush push{};
    push.lg = make_light_grid_params(ctx.settings, ctx.scene_gpu.light_count);
    push.flags = options_.cone_cull ? kLightGridFlagConeCull : 0u;
    const Buffer& grid = ctx.buffer("light_grid");
    const Buffer& stats = ctx.buffer("light_grid_stats");
    ctx.cmd.fill(stats, 0);
    ctx.cmd.barrier(kStageTransfer, kStageCompute);
    ComputePipelineDesc desc;
    desc.shader = "light_grid.comp";
    desc.bindings = scene_bindings();
    desc.bindings.push_back({kLightGridBindGrid, DescriptorKind::storage_buffer});
    desc.bindings.push_back({kLightGridBindStats, DescriptorKind::storage_buffer});
    desc.push_constant_bytes = sizeof(push);
    std::vector<Bind> binds = ctx.scene_gpu.binds();
    binds.push_back({kLightGridBindGrid, &grid, nullptr});
    binds.push_back({kLightGridBindStats, &stats, nullptr});
    auto pipeline = ctx.gpu.compute_pipeline(desc);
    ctx.cmd.bind(*pipeline, binds, &push, sizeof(push));
    const uint32_t blocks = kLightGridDim / kLightGridGroup;
    ctx.cmd.dispatch(blocks, blocks, blocks * light_grid_cascades(push.lg));
  }

 private:
  LightGridOptions options_;
};

// Mirrors of the shader helpers, operation for operation in float.
int32_t cell_coord(float p, float cell) {
  return static_cast<int32_t>(std::clamp(std::floor(p / cell), -1e9f, 1e9f));
}

float dot3(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

bool sphere_overlaps_box(Vec3 c, float r, Vec3 bmin, Vec3 bmax) {
  Vec3 q{std::clamp(c.x, bmin.x, bmax.x), std::clamp(c.y, bmin.y, bmax.y), std::clamp(c.z, bmin.z, bmax.z)};
  Vec3 d = c - q;
  return dot3(d, d) <= r * r;
}

bool cone_may_touch_box(const GpuLight& l, Vec3 bmin, Vec3 bmax) {
  Vec3 c = (bmin + bmax) * 0.5f;
  Vec3 e = bmax - bmin;
  float rb = 0.5f * std::sqrt(dot3(e, e)) * 1.001f + 1e-4f;
  Vec3 v = c - Vec3{l.position[0], l.position[1], l.position[2]};
  float a = dot3(v, Vec3{l.direction[0], l.direction[1], l.direction[2]});
  if (a < -rb) return false;
  float h = std::sqrt(std::max(dot3(v, v) - a * a, 0.0f));
  float cos_o = std::clamp(l.cos_outer, 0.0f, 1.0f);
  float sin_o = std::sqrt(std::max(1.0f - cos_o * cos_o, 0.0f));
  return cos_o * h - a * sin_o <= rb;
}

}  // namespace

std::unique_ptr<Pass> make_light_grid_pass(LightGridOptions options) {
  return std::make_unique<LightGridPass>(options);
}

glsl::LightGridParams make_light_grid_params(const Settings& settings, uint32_t light_count) {
  glsl::LightGridParams p{};
  const RadianceCacheSettings& r = settings.params<RadianceCacheSettings>();
  p.extent = {r.light_grid_extent, float(r.light_grid_cascades), float(light_count), 0.0f};
  return p;
}

uint32_t light_grid_cascades(const glsl::LightGridParams& params) {
  return std::min(static_cast<uint32_t>(params.extent.y), kMaxCascades);
}

uint32_t light_grid_words(const glsl::LightGridParams& params) {
  return std::max(light_grid_cascades(params), 1u) * kLightGridDim * kLightGridDim * kLightGridDim * kLightGridCellWords;
}

float light_grid_cell_size(const glsl::LightGridParams& params, uint32_t cascade) {
  return params.extent.x * float(1u << cascade) / float(kLightGridDim);
}

void light_grid_base_cell(const glsl::LightGridParams& params, uint32_t cascade, Vec3 camera, int32_t out[3]) {
  float cell = light_grid_cell_size(params, cascade);
  for (int a = 0; a < 3; ++a) out[a] = cell_coord(camera[a], cell) - int32_t(kLightGridDim / 2);
}

void light_grid_cell_bounds(const glsl::LightGridParams& params, uint32_t cascade, const uint32_t local[3],
                            Vec3 camera, Vec3& bmin, Vec3& bmax) {
  float cell = light_grid_cell_size(params, cascade);
  int32_t base[3];
  light_grid_base_cell(params, cascade, camera, base);
  for (int a = 0; a < 3; ++a) {
    int32_t w = base[a] + int32_t(local[a]);
    bmin[a] = float(w) * cell;
    bmax[a] = float(w + 1) * cell;
  }
}

uint32_t light_grid_cell_word(uint32_t cascade, const uint32_t local[3]) {
  return (((cascade * kLightGridDim + local[2]) * kLightGridDim + local[1]) * kLightGridDim + local[0]) *
         kLightGridCellWords;
}

uint32_t light_grid_cell_of(const glsl::LightGridParams& params, Vec3 camera, Vec3 p) {
  for (uint32_t c = 0; c < light_grid_cascades(params); ++c) {
    float cell = light_grid_cell_size(params, c);
    int32_t base[3];
    light_grid_base_cell(params, c, camera, base);
    uint32_t local[3];
    bool inside = true;
    for (int a = 0; a < 3; ++a) {
      int32_t q = cell_coord(p[a], cell) - base[a];
      inside = inside && q >= 0 && q < int32_t(kLightGridDim);
      local[a] = static_cast<uint32_t>(q);
    }
    if (inside) return light_grid_cell_word(c, local);
  }
  return kLightGridInvalid;
}

std::vector<uint32_t> lights_for_cell(const std::vector<GpuLight>& lights, const glsl::LightGridParams& params,
                                      uint32_t cascade, const uint32_t local[3], Vec3 camera, bool cone_cull) {
  Vec3 bmin, bmax;
  light_grid_cell_bounds(params, cascade, local, camera, bmin, bmax);
  std::vector<uint32_t> out;
  uint32_t n = std::min<uint32_t>(static_cast<uint32_t>(lights.size()), kLightGridSceneLights);
  for (uint32_t i = 0; i < n; ++i) {
    const GpuLight& l = lights[i];
    if (!sphere_overlaps_box(Vec3{l.position[0], l.position[1], l.position[2]}, l.range, bmin, bmax)) continue;
    if (cone_cull && l.kind == static_cast<uint32_t>(LightKind::spot) && !cone_may_touch_box(l, bmin, bmax)) continue;
    out.push_back(i);
  }
  return out;
}

}  // namespace gib
