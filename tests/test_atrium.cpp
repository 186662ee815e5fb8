// The committed glTF courtyard (cases/scenes/atrium.json + atrium.glb, tools/make_atrium.cpp):
// the scene features derived from its imported content, its textures (a linear normal map on
// the bricks among sRGB base colours), and the plans they give every technique: passes that
// need what the scene lacks are culled with the reason, the rest run.
#include <gtest/gtest.h>

#include <string>

#include "renderer/graph/graph.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/techniques/technique.h"

namespace gib {
namespace {

const PlannedPass* find_pass(const Plan& p, const std::string& name) {
  for (const PlannedPass& x : p.passes)
    if (x.name == name) return &x;
  return nullptr;
}

TEST(Atrium, ImportedFeaturesTexturesAndCulledPlan) {
  const Scene s = load_scene(std::string(GIB_SOURCE_DIR) + "/cases/scenes/atrium.json");
  const SceneFeatures f = s.features();
  EXPECT_TRUE(f.has(Feature::sun));
  EXPECT_TRUE(f.has(Feature::sky));
  EXPECT_TRUE(f.has(Feature::textured));
  EXPECT_TRUE(f.has(Feature::alpha_tested));  // the arch and leaf cards' MASK
  EXPECT_FALSE(f.has(Feature::local_lights));
  EXPECT_FALSE(f.has(Feature::emissive));
  EXPECT_FALSE(f.has(Feature::motion));
  ASSERT_EQ(s.textures.size(), 5u);
  int normal_maps = 0;
  for (const Material& m : s.materials)
    if (m.normal_texture >= 0) {
      ++normal_maps;
      EXPECT_FALSE(s.textures[size_t(m.normal_texture)].srgb) << m.name;
      EXPECT_TRUE(s.textures[size_t(m.base_color_texture)].srgb) << m.name;
    }
  EXPECT_EQ(normal_maps, 1);  // the bricks

  for (const char* technique : {"direct", "radiance-cache", "probe-volume", "deferred"}) {
    const Technique& t = find_technique(technique);
    Settings settings = apply_preset(t, "medium", Settings{});
    settings.width = 128;
    settings.height = 72;
    std::vector<PassDecl> decls;
    for (auto& p : make_passes(t)) decls.push_back(p->declare(s, settings));
    const Plan plan = compile(decls, {f, {t.output}, 128, 72});
    size_t culled = 0;
    for (const PlannedPass& p : plan.passes) {
      if (p.runs) continue;
      ++culled;
      EXPECT_FALSE(p.reason.empty()) << technique << " " << p.name;
      // Nothing the atrium has may cull a pass: every reason names something it lacks.
      const size_t lacks = p.reason.find("scene lacks ");
      if (lacks == std::string::npos) continue;  // culled for another reason (e.g. nothing reads it)
      for (const char* has : {"sun", "sky", "textured", "alpha_tested"})
        EXPECT_EQ(p.reason.find(has, lacks), std::string::npos) << technique << " " << p.name << ": " << p.reason;
    }
    if (const PlannedPass* grid = find_pass(plan, "light_grid")) {
      EXPECT_FALSE(grid->runs) << technique;
      EXPECT_NE(grid->reason.find("local_lights"), std::string::npos) << grid->reason;
    }
    std::printf("atrium %s: %zu passes, %zu culled\n", technique, plan.passes.size(), culled);
  }
}

}  // namespace
}  // namespace gib
