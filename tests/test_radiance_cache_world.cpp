// The radiance-cache world passes (probe_trace, radiance_cache_update, radiance_cache_shade,
// irradiance_volume_update) on lavapipe at small sizes: cache counters against the table and
// the hit records, drops under a tiny table, the insertion's table and counters against a CPU
// mirror of the all-rounds design, convergence of an open-sky probe to the sky
// radiance, and a CPU mirror of the cell key. A test-only pass (rc_world_test.comp) exposes the
// hit positions/keys exactly as the update computes them and decodes the RGB9E5 atlas.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <set>

#include "renderer/codecs/octahedral.h"
#include "renderer/codecs/packed_float.h"
#include "renderer/graph/executor.h"
#include "renderer/techniques/radiance_cache/irradiance_volume_update/irradiance_volume_update.h"
#include "renderer/techniques/radiance_cache/light_grid/light_grid.h"
#include "renderer/techniques/radiance_cache/probe_trace/probe_trace.h"
#include "renderer/techniques/radiance_cache/radiance_cache_shade/radiance_cache_shade.h"
#include "renderer/techniques/radiance_cache/radiance_cache_update/radiance_cache_update.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/techniques/radiance_cache/radiance_cache_params.h"
#include "tests/gpu_fixture.h"
#include "tests/rc_world_test_shared.h"
#include "tests/technique_settings.h"

namespace gib {
namespace {

using test::GpuTest;
constexpr uint32_t kProbes = 16 * 16 * 16;

// Reads the world passes' results back: keys of this frame's hits and the decoded atlas.
class RcWorldProbePass final : public Pass {
 public:
  PassDecl declare(const Scene&, const Settings& s) const override {
    PassDecl d;
    d.name = "rc_world_test";
    ResourceDesc keys{Format::buffer, SizeRule::buffer};
    keys.bytes = uint64_t(kProbes) * rc(s).rays_per_probe * sizeof(glsl::RcTestKey);
    ResourceDesc decoded{Format::rgba32_float, SizeRule::fixed, glsl::kProbeAtlasWidth,
                         glsl::kProbeAtlasRowsPerCascade * rc(s).cascades};
    d.slots = {{"probe_hits", Access::read},
               {"probe_irradiance", Access::read},
               {"probe_visibility", Access::read},
               {"rc_test_keys", Access::write, keys},
               {"rc_test_atlas", Access::write, decoded}};
    return d;
  }
  void record(RecordContext& ctx) override {
    using namespace glsl;
    RcParams push = make_rc_params(ctx.settings, ctx.frame);
    for (uint32_t mode = 0; mode < 2; ++mode) {
      uint32_t threads = mode == 0 ? kProbes * rc(ctx.settings).rays_per_probe
                                   : ctx.width("rc_test_atlas") * ctx.height("rc_test_atlas");
      if (mode) ctx.cmd.barrier(kStageCompute, kStageCompute);
      record_compute(ctx, {.shader = "rc_world_test.comp",
                           .images = {{kRcTestBindIrradiance, "probe_irradiance"},
                                      {kRcTestBindVisibility, "probe_visibility"},
                                      {kRcTestBindDecoded, "rc_test_atlas"}},
                           .groups_x = div_up(threads, kRcTestGroup),
                           .push = &push,
                           .push_bytes = sizeof(push),
                           .spec_constants = {{kRcTestSpecMode, mode}},
                           .buffers = {{kRcTestBindHits, "probe_hits"}, {kRcTestBindKeys, "rc_test_keys"}}});
    }
  }
};

std::vector<std::unique_ptr<Pass>> world_passes() {
  std::vector<std::unique_ptr<Pass>> p;
  p.push_back(make_probe_trace_pass());
  p.push_back(make_radiance_cache_update_pass());
  p.push_back(make_radiance_cache_shade_pass());
  p.push_back(make_irradiance_volume_update_pass());
  p.push_back(std::make_unique<RcWorldProbePass>());
  return p;
}

Settings small_settings() {
  Settings s = defaults_of("radiance-cache");
  s.width = 32;
  s.height = 18;
  rc(s).cascades = 1;
  rc(s).rays_per_probe = 16;
  return s;
}

template <class T>
std::vector<T> as(const std::vector<uint8_t>& bytes) {
  std::vector<T> out(bytes.size() / sizeof(T));
  std::memcpy(out.data(), bytes.data(), out.size() * sizeof(T));
  return out;
}

// ---- CPU mirror of rc_cell_key (radiance_cache.glsl).
uint32_t pcg(uint32_t v) {
  uint32_t state = v * 747796405u + 2891336453u;
  uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}
struct CpuKey {
  uint32_t key = 0;
  bool near_boundary = false;  // within float noise of a cell or LOD boundary: skip comparing
};
CpuKey cpu_cell_key(const float p[3], Vec3 camera, float cell_size, float lod_distance, uint32_t side) {
  double dx = p[0] - camera.x, dy = p[1] - camera.y, dz = p[2] - camera.z;
  double l = std::log2(1.0 + std::sqrt(dx * dx + dy * dy + dz * dz) / lod_distance);
  CpuKey k;
  k.near_boundary = std::abs(l - std::round(l)) < 1e-4;
  double lod = std::exp2(std::floor(l));
  double size = double(cell_size) * lod;
  int32_t c[3];
  for (int i = 0; i < 3; ++i) {
    double q = p[i] / size;
    if (std::abs(q - std::round(q)) < 1e-4) k.near_boundary = true;
    c[i] = int32_t(std::floor(q));
  }
  uint32_t h = pcg(uint32_t(c[0]));
  h = pcg(uint32_t(c[1]) + h);
  h = pcg(uint32_t(c[2]) + h);
  h = pcg(side + h);
  k.key = (pcg(uint32_t(lod) + h) & ~3u) | 1u;
  return k;
}

// A 6 x 3 x 6 m room open at the top (sky light comes in from above), a box inside.
const char* kRoom = R"({
  "materials": {"white": {"albedo": [0.7, 0.7, 0.7]}, "red": {"albedo": [0.8, 0.2, 0.2]}},
  "objects": [
    {"primitive": {"type": "quad", "size": [6, 6], "facing": "+y"}, "material": "white"},
    {"primitive": {"type": "thin_slab", "size": [6, 3], "thickness": 0.1, "facing": "+z"},
     "transform": {"translate": [0, 1.5, -3]}, "material": "white"},
    {"primitive": {"type": "thin_slab", "size": [6, 3], "thickness": 0.1, "facing": "+z"},
     "transform": {"translate": [0, 1.5, 3]}, "material": "white"},
    {"primitive": {"type": "thin_slab", "size": [6, 3], "thickness": 0.1, "facing": "+x"},
     "transform": {"translate": [-3, 1.5, 0]}, "material": "red"},
    {"primitive": {"type": "thin_slab", "size": [6, 3], "thickness": 0.1, "facing": "+x"},
     "transform": {"translate": [3, 1.5, 0]}, "material": "white"},
    {"primitive": {"type": "box", "size": [1, 1, 1]}, "transform": {"translate": [0.7, 0.5, -0.6]}, "material": "white"}
  ],
  "sky": {"type": "constant", "radiance": [1, 1, 1]},
  "camera": {"position": [0.1, 1.4, 2.2], "target": [0, 1, 0]}
})";

struct FrameCheck {
  RcStats stats;
  uint32_t hits = 0, occupied = 0, dropped_keys = 0, shaded_now = 0;
  uint32_t mirror_checked = 0, mirror_agree = 0, misplaced = 0;
  bool active_distinct = true, active_shaded_now = true;
  double max_radiance = 0, mean_radiance = 0;  // over cells shaded so far, all channels
};

// Everything one frame left behind, checked against the counters.
FrameCheck check_frame(Executor& ex, const Scene& scene, uint32_t frame) {
  const Settings& s = ex.settings();
  FrameCheck fc;
  fc.stats = rc_stats_from_bytes(ex.read_buffer("rc_counters").data(), sizeof(glsl::RcCounters));
  auto cells = as<glsl::RcCell>(ex.read_buffer("rc_cells"));
  auto active = as<uint32_t>(ex.read_buffer("rc_active"));
  auto keys = as<glsl::RcTestKey>(ex.read_buffer("rc_test_keys"));
  const uint32_t mask = (1u << rc(s).cache_log2_cells) - 1u;
  std::set<uint32_t> present;
  for (uint32_t i = 0; i < cells.size(); ++i) {
    const glsl::RcCell& c = cells[i];
    if (!c.key) continue;
    ++fc.occupied;
    present.insert(c.key);
    if ((((i - ((c.key >> 2) & mask)) & mask)) >= rc(s).cache_max_probe) ++fc.misplaced;
    if (c.shaded_frame == frame + 1) ++fc.shaded_now;
    if (c.shaded_frame) {
      float rgb[3];
      codecs::decode_rgb9e5(c.radiance, rgb);
      for (float v : rgb) {
        fc.max_radiance = std::max(fc.max_radiance, double(v));
        fc.mean_radiance += v / 3.0;
      }
    }
  }
  if (fc.occupied) fc.mean_radiance /= fc.occupied;
  std::set<uint32_t> seen;
  for (uint32_t i = 0; i < fc.stats.active && i < active.size(); ++i) {
    if (!seen.insert(active[i]).second) fc.active_distinct = false;
    if (cells[active[i]].shaded_frame != frame + 1) fc.active_shaded_now = false;
  }
  Vec3 cam = scene.camera_at(0).position;
  for (auto& k : keys) {
    if (!k.key.x) continue;
    ++fc.hits;
    if (!present.count(k.key.x)) ++fc.dropped_keys;
    float p[3] = {k.position.x, k.position.y, k.position.z};
    CpuKey ck = cpu_cell_key(p, cam, rc(s).cache_cell_size, rc(s).cache_lod_distance, k.key.z);
    if (ck.near_boundary) continue;
    ++fc.mirror_checked;
    fc.mirror_agree += ck.key == k.key.x;
  }
  return fc;
}

void print_timings(const char* what, const FrameResult& fr) {
  std::printf("%s frame %u:", what, fr.frame);
  for (auto& p : fr.passes) std::printf(" %s %.1f ms", p.name.c_str(), p.ms);
  std::printf("\n");
}

class RadianceCacheWorld : public GpuTest {};

TEST_F(RadianceCacheWorld, CountersAgreeWithTableAndHits) {
  Scene scene = parse_scene(nlohmann::json::parse(kRoom), "room");
  Settings s = small_settings();
  Executor ex(gpu(), scene, s, world_passes(), {"probe_irradiance", "rc_test_keys", "rc_test_atlas"});
  uint32_t total_insertions = 0;
  for (uint32_t f = 0; f < 5; ++f) {
    FrameResult fr = ex.run_frame();
    print_timings("room", fr);
    FrameCheck c = check_frame(ex, scene, f);
    const RcStats& st = c.stats;
    total_insertions += st.insertions;
    std::printf("room frame %u: hits %u insertions %u reused %u drops %u collisions %u active %u "
                "occupied %u shaded_now %u\n",
                f, c.hits, st.insertions, st.reused, st.drops, st.collisions, st.active, c.occupied, c.shaded_now);
    EXPECT_GT(c.hits, kProbes * rc(s).rays_per_probe / 4) << "the room should catch many probe rays";
    EXPECT_LE(st.insertions + st.reused + st.drops, c.hits);
    EXPECT_LE(st.insertions, st.active);
    EXPECT_EQ(st.active, c.shaded_now) << "every queued cell is shaded this frame, and only those";
    EXPECT_EQ(st.dispatch_x, (st.active + glsl::kRcShadeGroup - 1) / glsl::kRcShadeGroup);
    EXPECT_TRUE(c.active_distinct) << "a cell is queued at most once per frame";
    EXPECT_TRUE(c.active_shaded_now);
    EXPECT_EQ(st.drops, 0u);
    EXPECT_EQ(c.dropped_keys, 0u);
    EXPECT_EQ(c.occupied, total_insertions) << "cells are never lost or duplicated";
    EXPECT_EQ(c.misplaced, 0u) << "every key sits within cache_max_probe slots of its first slot";
    // One bounce ray per shade: L = albedo x (sky 1 or a cell's radiance), so never above the
    // largest albedo (0.8) plus RGB9E5 rounding; the open top lets sky in.
    std::printf("room frame %u: cell radiance mean %.3f max %.3f\n", f, c.mean_radiance, c.max_radiance);
    EXPECT_LE(c.max_radiance, 0.805);
    EXPECT_GT(c.mean_radiance, 0.05);
    if (f == 0) {
      EXPECT_EQ(st.reused, 0u);
      EXPECT_EQ(st.insertions, st.active);
    }
    if (f >= 1 && f < rc(s).cache_reuse_frames) {
      EXPECT_GT(st.reused, 0u) << "recently shaded cells are reused";
    }
  }
  // Something was lit: the sky comes in through the open top.
  FloatImage atlas = ex.read("rc_test_atlas");
  double sum = 0;
  for (uint32_t y = 0; y < atlas.height; ++y)
    for (uint32_t x = 0; x < atlas.width; ++x) sum += atlas.at(x, y, 1);
  EXPECT_GT(sum / atlas.pixel_count(), 0.05);
}

TEST_F(RadianceCacheWorld, TinyCacheCountsEveryDrop) {
  Scene scene = parse_scene(nlohmann::json::parse(kRoom), "room");
  Settings s = small_settings();
  rc(s).cache_log2_cells = 6;  // 64 cells for thousands of distinct cells
  rc(s).cache_max_probe = 4;
  Executor ex(gpu(), scene, s, world_passes(), {"probe_irradiance", "rc_test_keys", "rc_test_atlas"});
  uint32_t total_insertions = 0;
  for (uint32_t f = 0; f < 2; ++f) {
    ex.run_frame();
    FrameCheck c = check_frame(ex, scene, f);
    const RcStats& st = c.stats;
    total_insertions += st.insertions;
    std::printf("tiny frame %u: hits %u insertions %u reused %u drops %u collisions %u active %u occupied %u "
                "hits whose key is absent %u\n",
                f, c.hits, st.insertions, st.reused, st.drops, st.collisions, st.active, c.occupied, c.dropped_keys);
    EXPECT_GT(st.drops, 0u);
    // A hit is dropped exactly when its key is not in the table afterwards (slots only fill, so a
    // key absent at the end was absent from every slot the hit probed).
    EXPECT_EQ(st.drops, c.dropped_keys);
    EXPECT_LE(st.insertions + st.reused + st.drops, c.hits);
    EXPECT_LE(c.occupied, 64u);
    EXPECT_EQ(c.occupied, total_insertions);
    EXPECT_EQ(c.misplaced, 0u);
    EXPECT_EQ(st.active, c.shaded_now);
    EXPECT_GE(st.collisions, st.drops * rc(s).cache_max_probe) << "a drop probed every slot";
  }
}

// ---- CPU mirror of the insertion as it was first designed (radiance_cache.glsl, "Insertion"):
// rounds 0 .. max_probe, each over every hit. Within a round the outcome does not depend on the
// order of the hits (a bid is an atomicMax, a commit a compare-and-swap that one of the key's hits
// wins), so running the hits one after another gives what the GPU's round gives. The GPU pass now
// searches once and runs the later rounds over the pending hits only; it must leave the same
// table and counters.
struct MirrorInsertion {
  std::vector<uint32_t> keys;  // the table's keys afterwards
  uint32_t insertions = 0, collisions = 0, drops = 0, reused = 0, active = 0;
};
MirrorInsertion mirror_insertion(const std::vector<glsl::RcCell>& before, const std::vector<uint32_t>& hit_keys,
                                 const Settings& s, uint32_t frame) {
  MirrorInsertion m;
  for (auto& c : before) m.keys.push_back(c.key);
  std::vector<uint32_t> shaded;
  for (auto& c : before) shaded.push_back(c.shaded_frame);
  const uint32_t mask = (1u << rc(s).cache_log2_cells) - 1u, n = rc(s).cache_max_probe, now = frame + 1;
  for (uint32_t round = 0; round <= n; ++round)
    for (uint32_t key : hit_keys) {
      if (!key) continue;
      const uint32_t first = (key >> 2) & mask, hash = key & ~3u;
      const uint32_t bid = hash | (2u + (round & 1u)), last_bid = hash | (2u + ((round + 1u) & 1u));
      int64_t placed = -1;
      for (uint32_t st = 0; st < round && placed < 0; ++st) {
        const uint32_t i = (first + st) & mask, v = m.keys[i];
        if (v == key) {
          placed = i;
        } else if (v == last_bid && st + 1 == round) {
          m.keys[i] = key;
          ++m.insertions;
          placed = i;
        } else if (st + 1 == round) {
          ++m.collisions;
        }
      }
      if (placed < 0) {
        if (round == n) {
          ++m.drops;
          continue;
        }
        const uint32_t i = (first + round) & mask, v = m.keys[i];
        if (v == key)
          placed = i;
        else if (v == 0 || (v & 3u) == (bid & 3u))
          m.keys[i] = std::max(v, bid);
      }
      if (round == n && placed >= 0) {
        uint32_t& sf = shaded[size_t(placed)];
        if (sf == now) continue;
        if (sf != 0 && now - sf < rc(s).cache_reuse_frames) {
          ++m.reused;
          continue;
        }
        sf = now;
        ++m.active;
      }
    }
  return m;
}

// The pass's table and counters against the mirror, frame by frame, in the room and with a
// table so small that most keys collide and many are dropped.
// Both layouts of rounds 1 .. max_probe (insertion_rounds 0: one workgroup walks every round;
// 1: one indirect dispatch per round), both counter layouts (update_counters) and both places of
// round 0 (insertion_find 0: in probe_trace; 1: a dispatch of radiance_cache_update) are checked.
TEST_F(RadianceCacheWorld, InsertionMatchesCpuMirrorOfAllRounds) {
  Scene scene = parse_scene(nlohmann::json::parse(kRoom), "room");
  for (int run = 0; run < 8; ++run) {
    const int tiny = run % 2, layout = run / 2;
    Settings s = small_settings();
    rc(s).insertion_rounds = uint32_t(layout == 1);
    rc(s).update_counters = layout == 2 ? 1u : 0u;  // lavapipe's default is per subgroup: also the GPUs' layout
    rc(s).insertion_find = uint32_t(layout == 3);
    SCOPED_TRACE(layout == 1   ? "one dispatch per round"
                 : layout == 2 ? "counters per workgroup"
                 : layout == 3 ? "find in a dispatch of its own"
                               : "rounds in one workgroup");
    if (tiny) {
      rc(s).cache_log2_cells = 6;
      rc(s).cache_max_probe = 4;
    }
    Executor ex(gpu(), scene, s, world_passes(), {"probe_irradiance", "rc_test_keys", "rc_test_atlas"});
    std::vector<glsl::RcCell> before(size_t(1) << rc(s).cache_log2_cells, glsl::RcCell{});
    for (uint32_t f = 0; f < 4; ++f) {
      ex.run_frame();
      auto cells = as<glsl::RcCell>(ex.read_buffer("rc_cells"));
      RcStats st = rc_stats_from_bytes(ex.read_buffer("rc_counters").data(), sizeof(glsl::RcCounters));
      std::vector<uint32_t> hit_keys;
      uint32_t stored_differ = 0;
      for (auto& k : as<glsl::RcTestKey>(ex.read_buffer("rc_test_keys"))) {
        hit_keys.push_back(k.key.x);
        stored_differ += k.key.w != k.key.x;
      }
      EXPECT_EQ(stored_differ, 0u) << "probe_trace's stored keys differ from the keys recomputed from the hits";
      MirrorInsertion m = mirror_insertion(before, hit_keys, s, f);
      std::printf("%s frame %u: gpu insertions %u collisions %u drops %u reused %u active %u; mirror %u %u %u %u %u\n",
                  tiny ? "tiny" : "room", f, st.insertions, st.collisions, st.drops, st.reused, st.active,
                  m.insertions, m.collisions, m.drops, m.reused, m.active);
      ASSERT_EQ(cells.size(), m.keys.size());
      uint32_t differ = 0, hit_index_left = 0;
      for (size_t i = 0; i < cells.size(); ++i) {
        differ += cells[i].key != m.keys[i];
        hit_index_left += cells[i].hit_index != 0;
      }
      EXPECT_EQ(differ, 0u) << "table keys differ from the mirror's";
      EXPECT_EQ(hit_index_left, 0u) << "radiance_cache_shade resets every queued cell's hit_index";
      EXPECT_EQ(st.insertions, m.insertions);
      EXPECT_EQ(st.collisions, m.collisions);
      EXPECT_EQ(st.drops, m.drops);
      EXPECT_EQ(st.reused, m.reused);
      EXPECT_EQ(st.active, m.active);
      if (tiny) {
        EXPECT_GT(m.drops, 0u);
      }
      before = cells;
    }
  }
}

// irradiance_volume_update's layouts: the per-probe kernel GPUs run (volume_kernel 1: carry,
// then one group per probe with its rays in group-shared memory; the cache fallback in a second
// dispatch over the probes that need it, volume_fallback 0, or inline, 1) and the CPU split (2:
// carry, rays, convolve) leave bit-identical atlases and moments, frame after frame, with three
// cascades so every frame carries two of them, in a table where every hit finds its cell and in
// one where many do not. (The per-probe layout keeps its rays in shared memory and zeroes
// probe_ray_radiance, so the ray buffers are not compared.)
TEST_F(RadianceCacheWorld, VolumeKernelsAgreeBitForBit) {
  Scene scene = parse_scene(nlohmann::json::parse(kRoom), "room");
  // The default table, and one of 64 cells, where many hits find no cell: their probes take the
  // cache fallback (the per-probe kernel's second dispatch with volume_fallback 0).
  for (uint32_t log2_cells : {RadianceCacheSettings{}.cache_log2_cells, 6u}) {
    SCOPED_TRACE("2^" + std::to_string(log2_cells) + " cells");
    uint32_t listed = 0;  // probes the first per-probe dispatch left to the fallback dispatch
    auto run = [&](uint32_t kernel, uint32_t fallback) {
      Settings s = small_settings();
      rc(s).cascades = 3;
      rc(s).cache_log2_cells = log2_cells;
      rc(s).volume_kernel = kernel;
      rc(s).volume_fallback = fallback;
      Executor ex(gpu(), scene, s, world_passes(), {"probe_irradiance", "rc_test_keys", "rc_test_atlas"});
      std::vector<std::vector<uint32_t>> frames;  // bit patterns: decoded atlas, both moments
      for (uint32_t f = 0; f < 4; ++f) {
        ex.run_frame();
        std::vector<uint32_t> bits;
        for (float v : ex.read("rc_test_atlas").pixels) bits.push_back(std::bit_cast<uint32_t>(v));
        for (float v : ex.read("probe_visibility").pixels) bits.push_back(std::bit_cast<uint32_t>(v));
        frames.push_back(std::move(bits));
        if (kernel == 1 && fallback == 0) listed += as<uint32_t>(ex.read_buffer("iv_fallback")).at(0);
      }
      return frames;
    };
    auto split = run(2, 0);
    for (uint32_t fallback : {0u, 1u}) {
      SCOPED_TRACE(fallback == 0 ? "per-probe, fallback dispatch" : "per-probe, fallback inline");
      auto per_probe = run(1, fallback);
      ASSERT_EQ(per_probe.size(), split.size());
      for (size_t f = 0; f < split.size(); ++f) {
        ASSERT_EQ(per_probe[f].size(), split[f].size());
        size_t differ = 0;
        for (size_t i = 0; i < split[f].size(); ++i) differ += per_probe[f][i] != split[f][i];
        EXPECT_EQ(differ, 0u) << "frame " << f << ": values of the atlas / moments that differ";
      }
    }
    std::printf("2^%u cells: %u probes left to the fallback dispatch over 4 frames\n", log2_cells, listed);
    if (log2_cells == 6u) {
      EXPECT_GT(listed, 0u) << "the tiny table must send probes to the fallback";
    }
  }
}

// The carry's contract: each frame's atlas equals last frame's outside the cascade this frame
// updated (the carry copies only the cascade last frame updated, into a copy two frames old).
// Four cascades on the interleaved schedule, so the updated and carried cascades both change;
// both kernel layouts (the per-probe kernel carries inside its dispatch, the split pair in a
// carry dispatch).
TEST_F(RadianceCacheWorld, AtlasChangesOnlyInTheUpdatedCascade) {
  for (uint32_t kernel : {1u, 2u}) {
  SCOPED_TRACE(kernel == 1 ? "per-probe kernel" : "split pair");
  Scene scene = parse_scene(nlohmann::json::parse(kRoom), "room");
  Settings s = small_settings();
  rc(s).cascades = 4;
  rc(s).probe_schedule = 1;
  rc(s).volume_kernel = kernel;
  Executor ex(gpu(), scene, s, world_passes(), {"probe_irradiance", "rc_test_keys", "rc_test_atlas"});
  std::vector<uint32_t> last;
  uint32_t width = 0, changed_elsewhere = 0, changed_inside = 0;
  for (uint32_t f = 0; f < 8; ++f) {
    ex.run_frame();
    const FloatImage atlas = ex.read("rc_test_atlas"), moments = ex.read("probe_visibility");
    ASSERT_EQ(atlas.height, moments.height);
    std::vector<uint32_t> bits;  // per texel: the decoded irradiance's channels, then the moments'
    for (uint32_t y = 0; y < atlas.height; ++y)
      for (uint32_t x = 0; x < atlas.width; ++x) {
        for (uint32_t c = 0; c < atlas.channels; ++c) bits.push_back(std::bit_cast<uint32_t>(atlas.at(x, y, c)));
        for (uint32_t c = 0; c < moments.channels; ++c) bits.push_back(std::bit_cast<uint32_t>(moments.at(x, y, c)));
      }
    width = atlas.width * (atlas.channels + moments.channels);
    if (f > 0) {
      const uint32_t updated = rc_updated_cascade(rc(s).probe_schedule, rc(s).cascades, f);
      for (size_t i = 0; i < bits.size(); ++i) {
        const uint32_t row = uint32_t(i / width), cascade = row / glsl::kProbeAtlasRowsPerCascade;
        if (bits[i] == last[i]) continue;
        (cascade == updated ? changed_inside : changed_elsewhere) += 1;
      }
    }
    last = std::move(bits);
  }
  EXPECT_EQ(changed_elsewhere, 0u) << "texels outside the updated cascade changed between frames";
  EXPECT_GT(changed_inside, 0u) << "the updated cascades never changed: the test sees nothing";
  }
}

TEST_F(RadianceCacheWorld, OpenSkyProbeConvergesToSkyRadiance) {
  // No geometry near the probes (the loader wants one object: a 1 m quad 9 km below).
  const char* kOpenSky = R"({
    "materials": {"grey": {"albedo": [0.5, 0.5, 0.5]}},
    "objects": [{"primitive": {"type": "quad", "size": [1, 1]}, "transform": {"translate": [0, -9000, 0]}, "material": "grey"}],
    "sky": {"type": "constant", "radiance": [2.0, 1.0, 0.5]},
    "camera": {"position": [0, 1, 0], "target": [0, 1, -1]}
  })";
  Scene scene = parse_scene(nlohmann::json::parse(kOpenSky), "open_sky");
  Settings s = small_settings();
  Executor ex(gpu(), scene, s, world_passes(), {"probe_irradiance", "rc_test_keys", "rc_test_atlas"});
  const float sky[3] = {2.0f, 1.0f, 0.5f};
  for (uint32_t f = 0; f < 4; ++f) {
    ex.run_frame();
    FloatImage atlas = ex.read("rc_test_atlas");
    double worst = 0, mean_distance = 0;
    uint32_t zero = 0;
    for (uint32_t y = 0; y < atlas.height; ++y)
      for (uint32_t x = 0; x < atlas.width; ++x) {
        for (uint32_t c = 0; c < 3; ++c) worst = std::max(worst, std::abs(atlas.at(x, y, c) / sky[c] - 1.0));
        zero += atlas.at(x, y, 3) == 0.0f;
        mean_distance += atlas.at(x, y, 3);
      }
    mean_distance /= atlas.pixel_count();
    std::printf("open sky frame %u: max |E/pi / L - 1| over %zu texels (borders included) = %.4f, mean moment %.3f m\n",
                f, atlas.pixel_count(), worst, mean_distance);
    EXPECT_LT(worst, 0.02);
    EXPECT_EQ(zero, 0u) << "every texel of every probe is written";
    // Misses clamp the distance moment to 4 probe spacings.
    EXPECT_NEAR(mean_distance, 4.0 * rc(s).probe_spacing, 0.01);
  }
  FrameCheck c = check_frame(ex, scene, 3);
  EXPECT_EQ(c.hits, 0u);
  EXPECT_EQ(c.stats.active, 0u);
}

TEST_F(RadianceCacheWorld, CpuMirrorOfCellKeyAgrees) {
  Scene scene = parse_scene(nlohmann::json::parse(kRoom), "room");
  Settings s = small_settings();
  rc(s).cache_lod_distance = 2.0f;  // LODs 1, 2 and 4 inside the room
  Executor ex(gpu(), scene, s, world_passes(), {"probe_irradiance", "rc_test_keys", "rc_test_atlas"});
  ex.run_frame();
  FrameCheck c = check_frame(ex, scene, 0);
  auto keys = as<glsl::RcTestKey>(ex.read_buffer("rc_test_keys"));
  std::set<float> lods;
  for (auto& k : keys)
    if (k.key.x) lods.insert(k.position.w);
  std::printf("key mirror: %u of %u hit positions compared (rest within 1e-4 of a cell/LOD boundary), %u agree, %zu LODs\n",
              c.mirror_checked, c.hits, c.mirror_agree, lods.size());
  // Floor and walls sit on cell planes (y = 0, x = +-3, ...), so many hits are skipped.
  EXPECT_GT(c.mirror_checked, c.hits / 2);
  EXPECT_EQ(c.mirror_agree, c.mirror_checked);
  EXPECT_GE(lods.size(), 3u);
}

TEST_F(RadianceCacheWorld, GradientSkyProbeConvergesToCosineIrradiance) {
  // Sky radiance 2 above the horizon, ground 0.5 below: irradiance / pi for a normal with
  // n.y = c is 2 (1 + c) / 2 + 0.5 (1 - c) / 2 = 1.25 + 0.75 c. 16 rays a frame, blended.
  const char* kGradient = R"({
    "materials": {"grey": {"albedo": [0.5, 0.5, 0.5]}},
    "objects": [{"primitive": {"type": "quad", "size": [1, 1]}, "transform": {"translate": [0, -9000, 0]}, "material": "grey"}],
    "sky": {"type": "gradient", "radiance": [2, 2, 2], "horizon": [2, 2, 2], "ground": [0.5, 0.5, 0.5]},
    "camera": {"position": [0, 1, 0], "target": [0, 1, -1]}
  })";
  Scene scene = parse_scene(nlohmann::json::parse(kGradient), "gradient_sky");
  Settings s = small_settings();
  Executor ex(gpu(), scene, s, world_passes(), {"probe_irradiance", "rc_test_keys", "rc_test_atlas"});
  double mean_err = 0, max_err = 0;
  for (uint32_t f = 0; f < 24; ++f) {
    ex.run_frame();
    if (f % 4 != 3 && f != 0) continue;
    FloatImage atlas = ex.read("rc_test_atlas");
    mean_err = 0;
    max_err = 0;
    for (uint32_t y = 0; y < atlas.height; ++y)
      for (uint32_t x = 0; x < atlas.width; ++x) {
        codecs::Texel t = codecs::oct_border_source({int(x % 10), int(y % 10)}, 8);
        Vec3 n = codecs::oct_texel_direction(t, 8);
        double expect = 1.25 + 0.75 * n.y;
        double err = std::abs(atlas.at(x, y, 1) / expect - 1.0);
        mean_err += err;
        max_err = std::max(max_err, err);
      }
    mean_err /= atlas.pixel_count();
    std::printf("gradient sky frame %u: |E/pi / expected - 1| mean %.4f max %.4f\n", f, mean_err, max_err);
  }
  EXPECT_LT(mean_err, 0.03);
  EXPECT_LT(max_err, 0.10);
}

TEST_F(RadianceCacheWorld, LocalLightReachesCellsThroughLightGrid) {
  // A closed box (no sky, no sun) lit only by a point light: every cell's light comes through
  // the light grid (and bounces of it).
  const char* kLitBox = R"({
    "materials": {"white": {"albedo": [0.5, 0.5, 0.5]}},
    "objects": [{"primitive": {"type": "box", "size": [4, 3, 4]}, "material": "white"}],
    "lights": [{"type": "point", "position": [0.3, 0.2, 0.1], "intensity": [2, 2, 2], "range": 20}],
    "camera": {"position": [0, 0, 0.4], "target": [0, 0, 0]}
  })";
  Scene scene = parse_scene(nlohmann::json::parse(kLitBox), "lit_box");
  ASSERT_TRUE(scene.features().has(Feature::local_lights));
  Settings s = small_settings();
  auto passes = world_passes();
  passes.insert(passes.begin(), make_light_grid_pass());
  Executor ex(gpu(), scene, s, std::move(passes), {"probe_irradiance", "rc_test_keys", "rc_test_atlas"});
  for (uint32_t f = 0; f < 2; ++f) {
    FrameResult fr = ex.run_frame();
    print_timings("lit box", fr);
  }
  FrameCheck c = check_frame(ex, scene, 1);
  std::printf("lit box: occupied %u, cell radiance mean %.4f max %.4f\n", c.occupied, c.mean_radiance, c.max_radiance);
  EXPECT_GT(c.occupied, 100u);
  EXPECT_GT(c.mean_radiance, 0.005);
  // Brightest point: a wall 1.7 m from the light, 0.5/pi * 2/1.7^2 = 0.11 direct, plus bounce.
  EXPECT_LT(c.max_radiance, 0.5);
}

// Which cascade a frame updates (the presets' probe_schedule): schedule 0 each in turn; schedule 1 the
// finest on every even frame and the others in turn on odd frames.
TEST(RadianceCacheSchedule, UpdatedCascadeByScheduleKnownAnswers) {
  std::vector<uint32_t> in_turn, finest_first, two;
  for (uint32_t f = 0; f < 12; ++f) {
    in_turn.push_back(rc_updated_cascade(0, 4, f));
    finest_first.push_back(rc_updated_cascade(1, 4, f));
    two.push_back(rc_updated_cascade(1, 2, f));
    EXPECT_EQ(rc_updated_cascade(1, 1, f), 0u);
    EXPECT_EQ(rc_updated_cascade(0, 1, f), 0u);
  }
  EXPECT_EQ(in_turn, (std::vector<uint32_t>{0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3}));
  EXPECT_EQ(finest_first, (std::vector<uint32_t>{0, 1, 0, 2, 0, 3, 0, 1, 0, 2, 0, 3}));
  EXPECT_EQ(two, (std::vector<uint32_t>{0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1}));
  // Every cascade of 6 is updated within 2 x 5 frames under schedule 1.
  std::set<uint32_t> seen;
  for (uint32_t f = 100; f < 110; ++f) seen.insert(rc_updated_cascade(1, 6, f));
  EXPECT_EQ(seen.size(), 6u);
}

// high and ultra keep medium's probe noise: rays x (1 + h) / (1 - h) ray samples per texel.
TEST(RadianceCacheSchedule, PresetsKeepMediumProbeSamples) {
  const Technique& t = find_technique("radiance-cache");
  auto samples = [](const RadianceCacheSettings& r) {
    return float(r.rays_per_probe) * (1.0f + r.probe_hysteresis) / (1.0f - r.probe_hysteresis);
  };
  const Settings medium = apply_preset(t, "medium", Settings{});
  EXPECT_NEAR(samples(rc(medium)), 394.67f, 0.01f);
  EXPECT_EQ(rc(medium).probe_schedule, 0u);
  // Every preset stores the probe atlas, the GI history and the cells dithered (closed box).
  EXPECT_TRUE(rc(medium).dither_stores);
  EXPECT_TRUE(rc(apply_preset(t, "low", Settings{})).dither_stores);
  EXPECT_EQ(rc(apply_preset(t, "low", Settings{})).probe_schedule, 0u);
  EXPECT_FLOAT_EQ(rc(apply_preset(t, "low", Settings{})).probe_hysteresis, 0.85f);
  for (const char* p : {"high", "ultra"}) {
    const Settings s = apply_preset(t, p, Settings{});
    EXPECT_EQ(rc(s).probe_schedule, 1u) << p;
    EXPECT_TRUE(rc(s).dither_stores) << p;
    EXPECT_NEAR(samples(rc(s)), samples(rc(medium)), 0.05f) << p;
    EXPECT_NEAR(rc(s).probe_hysteresis, 0.7211f, 1e-3f) << p;
  }
  // A case's option still overrides the preset.
  const Settings o = apply_options(t, apply_preset(t, "high", Settings{}), {{"probe_hysteresis", 0.5}});
  EXPECT_FLOAT_EQ(rc(o).probe_hysteresis, 0.5f);
}

// Probe `pr` of cascade 0 (spacing sp) around the camera: its world position and the top-left
// texel of its tile in the decoded atlas (probe_volume.glsl's layout).
struct ProbeAt {
  double p[3];
  uint32_t tile_x, tile_y;
};
ProbeAt probe_at(uint32_t pr, Vec3 cam, double sp) {
  const int ijk[3] = {int(pr & 15), int((pr >> 4) & 15), int(pr >> 8)};
  const double cv[3] = {cam.x, cam.y, cam.z};
  ProbeAt out{};
  uint32_t slot[3];
  for (int a = 0; a < 3; ++a) {
    const int cell = int(std::floor(cv[a] / sp)) - 8 + ijk[a];
    out.p[a] = (cell + 0.5) * sp;
    slot[a] = uint32_t(cell) & 15u;
  }
  out.tile_x = (slot[2] * 16 + slot[0]) * 10;
  out.tile_y = slot[1] * 10;
  return out;
}

// The decoded atlas after one frame of the world passes (one cascade of 0.5 m probes, every
// probe updated) on `scene`, whose camera the probes follow.
FloatImage atlas_after_one_update(Gpu& gpu, const Scene& scene) {
  Settings s = small_settings();
  rc(s).probe_spacing = 0.5f;
  Executor ex(gpu, scene, s, world_passes(), {"probe_irradiance", "rc_test_keys", "rc_test_atlas"});
  ex.run_frame();
  return ex.read("rc_test_atlas");
}

// Probes inside a solid (Instance::solid): most of their rays meet the back of its faces, so
// irradiance_volume_update marks them inside (moments 0, as never updated: samplers skip them) and they
// carry none of the light their rays reach through it. A 1.2 m slab under an open sky holds the
// probes of two layers (y = -0.25 and -0.75); every other probe is in the open or under it and
// must stay an ordinary probe. The same slab declared not solid (negative control) marks none.
TEST_F(RadianceCacheWorld, ProbesInsideSolidsAreMarkedAndSkipped) {
  for (bool solid : {true, false}) {
    nlohmann::json doc = nlohmann::json::parse(R"({
      "materials": {"white": {"albedo": [0.5, 0.5, 0.5]}},
      "objects": [{"primitive": {"type": "thin_slab", "size": [6, 6], "thickness": 1.2, "facing": "+y"},
                   "transform": {"translate": [0, -0.6, 0]}, "material": "white"}],
      "sky": {"type": "constant", "radiance": [1, 1, 1]},
      "camera": {"position": [0.1, 1.4, 0.3], "target": [0, 0, 0]}
    })");
    doc["objects"][0]["solid"] = solid;
    Scene scene = parse_scene(doc, "slab");
    FloatImage atlas = atlas_after_one_update(gpu(), scene);
    Vec3 cam = scene.camera_at(0).position;
    uint32_t in_slab = 0, in_marked = 0, out = 0, out_marked = 0;
    for (uint32_t pr = 0; pr < kProbes; ++pr) {
      const ProbeAt q = probe_at(pr, cam, 0.5);
      const bool inside = std::abs(q.p[0]) < 3 && std::abs(q.p[2]) < 3 && q.p[1] < 0 && q.p[1] > -1.2;
      uint32_t marked = 0;
      for (uint32_t y = 0; y < 10; ++y)
        for (uint32_t x = 0; x < 10; ++x)
          marked += atlas.at(q.tile_x + x, q.tile_y + y, 3) == 0.0f;  // every probe was updated in frame 0
      if (inside) {
        ++in_slab;
        in_marked += marked == 100;
      } else {
        ++out;
        out_marked += marked != 0;
      }
    }
    std::printf("slab solid=%d: probes inside %u (marked %u), outside %u (marked %u)\n", solid, in_slab, in_marked, out,
                out_marked);
    EXPECT_EQ(in_slab, 2u * 12u * 12u) << "two layers of 12 x 12 probes lie in the slab";
    EXPECT_EQ(out_marked, 0u) << "a probe in the open or under the slab sees front faces only";
    EXPECT_EQ(in_marked, solid ? in_slab : 0u);
  }
}

// A probe on a surface (a lattice falling on a wall plane) is inside too: an open quad 0.1 mm
// above a layer of probes (y = 0.25) is nearer than kRcOnSurface (1e-3 spacings, 0.5 mm) along
// 40% of the sphere of directions, so that layer is marked; 1 cm above (control) it is not.
TEST_F(RadianceCacheWorld, ProbesOnASurfaceAreMarked) {
  for (double gap : {1e-4, 1e-2}) {
    nlohmann::json doc = nlohmann::json::parse(R"({
      "materials": {"white": {"albedo": [0.5, 0.5, 0.5]}},
      "objects": [{"primitive": {"type": "quad", "size": [6, 6], "facing": "-y"}, "material": "white"}],
      "sky": {"type": "constant", "radiance": [1, 1, 1]},
      "camera": {"position": [0.1, 1.4, 0.3], "target": [0, 0, 0]}
    })");
    doc["objects"][0]["transform"] = {{"translate", {0.0, 0.25 + gap, 0.0}}};
    Scene scene = parse_scene(doc, "ceiling");
    FloatImage atlas = atlas_after_one_update(gpu(), scene);
    Vec3 cam = scene.camera_at(0).position;
    uint32_t layer = 0, layer_marked = 0, other_marked = 0;
    for (uint32_t pr = 0; pr < kProbes; ++pr) {
      const ProbeAt q = probe_at(pr, cam, 0.5);
      const bool on = std::abs(q.p[0]) < 2.9 && std::abs(q.p[2]) < 2.9 && q.p[1] == 0.25;
      const bool marked = atlas.at(q.tile_x + 5, q.tile_y + 5, 3) == 0.0f;
      layer += on;
      layer_marked += on && marked;
      other_marked += !on && marked;
    }
    std::printf("quad %.4f m above the probes: layer %u marked %u, others marked %u\n", gap, layer, layer_marked,
                other_marked);
    EXPECT_EQ(layer, 12u * 12u);
    EXPECT_EQ(layer_marked, gap < 1e-3 ? layer : 0u);
    EXPECT_EQ(other_marked, 0u);
  }
}

}  // namespace
}  // namespace gib
