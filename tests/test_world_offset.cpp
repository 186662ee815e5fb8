// The far-from-origin stress (docs/architecture.md "Determinism and numerical stability", the degenerate-geometry case):
// Settings::world_offset moves every world-space position; the technique options that set it;
// `gibench render --option NAME=VALUE`. The GPU side (the camera moves too, the image does not
// change) is in test_render.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "harness/render.h"
#include "renderer/scene/scene.h"
#include "renderer/techniques/technique.h"

namespace gib {
namespace {

Scene one_box_scene() {
  Scene s;
  s.materials.push_back(Material{});
  Mesh box;
  box.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  box.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  box.indices = {0, 1, 2};
  s.meshes.push_back(box);
  Instance inst;
  inst.transform = Mat4::trs({1, 2, 3}, {0, 30, 0}, {2, 2, 2});
  s.instances.push_back(inst);
  LocalLight l;
  l.position = {0.5f, 4, -1};
  s.lights.push_back(l);
  return s;
}

TEST(WorldOffset, FlattenTranslatesVerticesAndLightsOnly) {
  Scene s = one_box_scene();
  const Vec3 offset{10000, -3, 10000};
  FlatScene a = flatten(s, 0.0f), b = flatten(s, 0.0f, offset);
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  for (size_t i = 0; i < a.vertices.size(); ++i) {
    const GpuVertex &u = a.vertices[i], &v = b.vertices[i];
    // p + offset, rounded once (float spacing at 10 km is ~1 mm).
    EXPECT_EQ(v.px, u.px + offset.x);
    EXPECT_EQ(v.py, u.py + offset.y);
    EXPECT_EQ(v.pz, u.pz + offset.z);
    EXPECT_EQ(v.nx, u.nx);  // directions and UVs do not move
    EXPECT_EQ(v.ny, u.ny);
    EXPECT_EQ(v.nz, u.nz);
    EXPECT_EQ(v.u, u.u);
  }
  ASSERT_EQ(b.lights.size(), 1u);
  EXPECT_EQ(b.lights[0].position[0], 0.5f + 10000.0f);
  EXPECT_EQ(b.lights[0].position[1], 1.0f);
  EXPECT_EQ(b.lights[0].position[2], -1.0f + 10000.0f);
  EXPECT_EQ(b.lights[0].direction[1], a.lights[0].direction[1]);
  EXPECT_EQ(b.triangles.size(), a.triangles.size());
}

TEST(WorldOffset, SharedOptionsOfEveryTechnique) {
  for (const Technique& t : techniques()) {
    for (const char* name : {"world_offset_x", "world_offset_y", "world_offset_z"}) {
      EXPECT_EQ(check_option(t, name, 10000), "") << t.name << " " << name;
      EXPECT_EQ(check_option(t, name, -1e6), "") << t.name << " " << name;
      EXPECT_EQ(check_option(t, name, 0.25), "") << t.name << " " << name;  // any finite value, not only integers
      EXPECT_NE(check_option(t, name, 1.5e6).find("expected a number in [-1000000, 1000000], got 1500000"),
                std::string::npos)
          << check_option(t, name, 1.5e6);
      EXPECT_NE(check_option(t, name, std::nan("")).find("got NaN"), std::string::npos);
    }
    Settings s = apply_options(t, Settings{}, {{"world_offset_x", 10000}, {"world_offset_z", -2.5}});
    EXPECT_EQ(s.world_offset, (Vec3{10000, 0, -2.5f})) << t.name;
  }
  EXPECT_EQ(Settings{}.world_offset, (Vec3{0, 0, 0}));
}

// The alpha strategy and translucency switches are shared by every technique (every ray
// traversal and every material read honours them) and land in Settings.
TEST(SharedOptions, AlphaStrategyAndTranslucencyOfEveryTechnique) {
  for (const Technique& t : techniques()) {
    Settings s = apply_options(t, Settings{}, {{"alpha_strategy", 2}, {"alpha_any_hit_limit", 4}, {"translucency", 0}});
    EXPECT_EQ(s.alpha.strategy, AlphaStrategy::opaque_approx) << t.name;
    EXPECT_EQ(s.alpha.any_hit_limit, 4u) << t.name;
    EXPECT_FALSE(s.translucency) << t.name;
    EXPECT_NE(check_option(t, "alpha_strategy", 4).find("expected an integer in [0, 3], got 4"), std::string::npos)
        << check_option(t, "alpha_strategy", 4);
    EXPECT_NE(check_option(t, "alpha_any_hit_limit", 2.5).find("expected an integer"), std::string::npos);
    EXPECT_NE(check_option(t, "translucency", 2).find("expected an integer in [0, 1], got 2"), std::string::npos);
  }
  const Settings d;
  EXPECT_EQ(d.alpha.strategy, AlphaStrategy::test);
  EXPECT_EQ(d.alpha.any_hit_limit, 0u);
  EXPECT_TRUE(d.translucency);
}

TEST(RenderOptions, ParsesNameEqualsValueAndValidates) {
  const Technique& direct = find_technique("direct");
  auto opts = parse_render_options(direct, {"world_offset_x=10000", "nan_guards=0", "sky_rays=16"});
  EXPECT_EQ(opts.size(), 3u);
  EXPECT_EQ(opts["world_offset_x"], 10000.0);
  EXPECT_EQ(opts["nan_guards"], 0.0);
  auto error = [&](std::vector<std::string> o) -> std::string {
    try {
      parse_render_options(direct, o);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_EQ(error({"world_offset_x"}), "--option: expected NAME=VALUE, got 'world_offset_x'");
  EXPECT_EQ(error({"=3"}), "--option: expected NAME=VALUE, got '=3'");
  EXPECT_EQ(error({"sky_rays=many"}), "--option sky_rays: expected a number, got 'many'");
  EXPECT_EQ(error({"sky_rays="}), "--option sky_rays: expected a number, got ''");
  EXPECT_EQ(error({"sky_rays=4x"}), "--option sky_rays: expected a number, got '4x'");
  EXPECT_NE(error({"sky_rayz=4"}).find("--option sky_rayz: expected one of the options of direct ("), std::string::npos)
      << error({"sky_rayz=4"});
  EXPECT_NE(error({"world_offset_y=2e6"}).find("--option world_offset_y: expected a number in"), std::string::npos);
  EXPECT_NE(error({"sky_rays=nan"}).find("got NaN"), std::string::npos);
  EXPECT_EQ(error({"sky_rays=1", "sky_rays=2"}), "--option sky_rays: expected each option once, got it twice");
}

}  // namespace
}  // namespace gib
