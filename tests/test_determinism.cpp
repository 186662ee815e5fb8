// Every technique is deterministic on a given device: the same settings,
// scene and frame count give bit-identical images, run after run, in fresh executors. On
// lavapipe several threads run each dispatch, so any result that depends on which invocation
// wins a race (a hash slot, an atomic accumulation order) shows up here as a differing bit.
// radiance-cache runs with a small hash table too, so that insertions collide and some are
// dropped: which keys win a slot and which are dropped must depend on the keys only.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "gpu_fixture.h"
#include "renderer/graph/executor.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/techniques/technique.h"

namespace gib {
namespace {

struct Config {
  std::string technique, preset;
  std::vector<std::pair<std::string, double>> options;
};

// Renders `frames` frames in a fresh executor and returns every contract AOV's resource.
// `batched`: the frames in one submission with GPU timestamps (a GPU's way), not one
// submission a pass (lavapipe's default).
std::vector<FloatImage> render(Gpu& gpu, const Scene& scene, const Config& cfg, uint32_t frames,
                               bool batched = false) {
  const Technique& t = find_technique(cfg.technique);
  Settings s;
  s.width = 48;
  s.height = 27;
  s = apply_preset(t, cfg.preset, s);
  std::map<std::string, double> opts(cfg.options.begin(), cfg.options.end());
  s = apply_options(t, s, opts);
  std::vector<std::string> res;
  for (auto& a : contract_aov_names(t, scene.features())) res.push_back(contract_resource(t, a));
  Executor ex(gpu, scene, s, make_passes(t), res);
  if (batched) {
    ex.time_passes_on_host(false);
    ex.run_frames(frames);
  } else {
    for (uint32_t f = 0; f < frames; ++f) ex.run_frame();
  }
  std::vector<FloatImage> out;
  for (auto& r : res) out.push_back(ex.read(r));
  return out;
}

size_t differing_floats(const FloatImage& a, const FloatImage& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) n += std::memcmp(&a.pixels[i], &b.pixels[i], sizeof(float)) != 0;
  return n;
}

class Determinism : public test::GpuTest {};

TEST_F(Determinism, EveryTechniqueIsBitIdenticalRunToRun) {
  std::vector<Config> configs;
  for (const Technique& t : techniques()) configs.push_back({t.name, "medium", {}});
  // 2^6 cells for thousands of probe hits per frame: most insertions collide, many drop.
  configs.push_back({"radiance-cache", "low", {{"cache_log2_cells", 6}}});
  for (const char* file : {"cornell.json", "thin_wall_005.json"}) {
    Scene scene = load_scene(std::string(GIB_SOURCE_DIR) + "/cases/scenes/" + file);
    for (const Config& cfg : configs) {
      SCOPED_TRACE(std::string(file) + " " + cfg.technique + " " + cfg.preset +
                   (cfg.options.empty() ? "" : " cache_log2_cells 6"));
      // Six frames: radiance-cache inserts, reuses and re-shades cells across frames.
      std::vector<FloatImage> a = render(gpu(), scene, cfg, 6), b = render(gpu(), scene, cfg, 6);
      ASSERT_EQ(a.size(), b.size());
      for (size_t i = 0; i < a.size(); ++i) {
        ASSERT_EQ(a[i].pixels.size(), b[i].pixels.size());
        double sum = 0;
        for (float v : a[i].pixels) sum += v;
        EXPECT_GT(sum, 0.0) << "output " << i << " is black: a black image proves nothing";
        EXPECT_EQ(differing_floats(a[i], b[i]), 0u) << "output " << i << " of " << a[i].pixels.size() << " floats";
      }
    }
  }
}

// Frames recorded into one submission (Executor::run_frames on a GPU) are the same commands
// in the same order as a submission per pass: every technique's output is the same bit for bit.
TEST_F(Determinism, FramesInOneSubmissionAreTheFramesSubmittedOneByOne) {
  Scene scene = load_scene(std::string(GIB_SOURCE_DIR) + "/cases/scenes/cornell.json");
  for (const Technique& t : techniques()) {
    const Config cfg{t.name, "medium", {}};
    SCOPED_TRACE(t.name);
    std::vector<FloatImage> a = render(gpu(), scene, cfg, 5), b = render(gpu(), scene, cfg, 5, true);
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) {
      ASSERT_EQ(a[i].pixels.size(), b[i].pixels.size());
      EXPECT_EQ(differing_floats(a[i], b[i]), 0u) << "output " << i << " of " << a[i].pixels.size() << " floats";
    }
  }
}

// voxel-clipmap with geometry_light (on by default) in a thin-wall room: scene_voxel_light's lit
// voxels, the out-of-view cells and the wall test of the cube lookups, both kinds: the voxel walk
// (wall_test 1: its DDA reads the triangles the fill kept while the feed writes the voxels) and
// the flood mask (wall_test 2: the relight's flood in shared memory, the air voxel's geometry flag).
TEST_F(Determinism, VoxelClipmapGeometryLightIsBitIdenticalRunToRun) {
  Scene scene = load_scene(std::string(GIB_SOURCE_DIR) + "/cases/scenes/thin_wall_005.json");
  for (double wall_test : {1.0, 2.0}) {
    SCOPED_TRACE(wall_test == 1.0 ? "wall_test 1" : "wall_test 2");
    const Config cfg{"voxel-clipmap", "medium", {{"geometry_light", 1}, {"wall_test", wall_test}}};
    std::vector<FloatImage> a = render(gpu(), scene, cfg, 6), b = render(gpu(), scene, cfg, 6);
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) {
      ASSERT_EQ(a[i].pixels.size(), b[i].pixels.size());
      EXPECT_EQ(differing_floats(a[i], b[i]), 0u) << "output " << i << " of " << a[i].pixels.size() << " floats";
    }
  }
}

// A glossy floor: the reference's reflection AOV and gow-ragnarok's reflection passes (the cube
// map's capture accumulates, the resolve reads history) in both reflection modes.
TEST_F(Determinism, GlossyReflectionsAreBitIdenticalRunToRun) {
  Scene scene = load_scene(std::string(GIB_SOURCE_DIR) + "/cases/scenes/glossy_hall.json");
  for (const Config& cfg : {Config{"reference", "medium", {}}, Config{"gow-ragnarok", "medium", {}},
                            Config{"gow-ragnarok", "medium", {{"reflection_mode", 0}}}}) {
    SCOPED_TRACE(cfg.technique + (cfg.options.empty() ? "" : " reflection_mode 0"));
    std::vector<FloatImage> a = render(gpu(), scene, cfg, 4), b = render(gpu(), scene, cfg, 4);
    ASSERT_EQ(a.size(), 4u) << "radiance, direct, indirect_diffuse (gow-ragnarok: ssgi's), reflection";
    for (size_t i = 0; i < a.size(); ++i) {
      double sum = 0;
      for (float v : a[i].pixels) sum += v;
      EXPECT_GT(sum, 0.0) << "output " << i << " is black: a black image proves nothing";
      EXPECT_EQ(differing_floats(a[i], b[i]), 0u) << "output " << i << " of " << a[i].pixels.size() << " floats";
    }
  }
}

}  // namespace
}  // namespace gib
