// probe-volume's energy per bounce in the closed white-furnace box (cases/white-furnace-closed-box.json:
// a 4 m box, every wall albedo 0.99 and emission 0.01, 12^3 probes at 0.5 m covering it, every
// probe relit every frame). Known answers from the texel formats in use: the probe G-buffer's
// unorm8 albedo (0.99 -> 252/255), its RGB9E5 emission (0.01 -> 0.01001) and the half
// irradiance under each probe's lighting scale.
//   - One bounce: with every probe's irradiance set to U (E / pi, graph override after
//     probe_convolve) and the probes outside the box set to 0, one relight and convolution give
//     each probe inside a U + e; the probes behind the walls (they see only the walls' backs and
//     the void) must be disabled, or their darkness enters the walls' samples.
//   - Frame by frame: after n frames every probe inside holds e (1 - a^n) / (1 - a), one bounce
//     a frame, and the loop's fixed point is e / (1 - a) = 0.851 (the box's bound).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "harness/case.h"
#include "harness/case_render.h"
#include "renderer/codecs/half.h"
#include "renderer/codecs/packed_float.h"
#include "renderer/codecs/rgb9e5.h"
#include "renderer/techniques/probe_volume/include/probe_volume_shared.h"
#include "tests/case_rows.h"
#include "tests/gpu_fixture.h"

namespace gib {
namespace {

using glsl::PvCascade;
using glsl::PvProbe;

struct BoxRun {
  Case c;
  TechniqueRun run;
  double spacing = 0;
};

BoxRun closed_box(uint32_t frames) {
  BoxRun b;
  b.c = load_case(std::string(GIB_SOURCE_DIR) + "/cases/white-furnace-closed-box.json");
  b.c.width = 16;
  b.c.height = 9;
  b.c.frames = frames;
  b.run = test::plain_row(b.c, "probe-volume");
  b.run.frames = frames;
  b.spacing = b.run.options.at("probe_spacing");
  return b;
}

// The probe's position: its cell's centre (cascade 0) plus its relocation offset.
bool in_box(const PvProbe& p, double s) {
  const double x = (p.coord.x + 0.5) * s + p.offset.x, y = (p.coord.y + 0.5) * s + p.offset.y,
               z = (p.coord.z + 0.5) * s + p.offset.z;
  return std::abs(x) < 2 && std::abs(z) < 2 && y > 0 && y < 4;
}
bool usable(const PvProbe& p) {
  const uint32_t f = uint32_t(p.coord.w);
  return (f & glsl::kPvProbeValid) && !(f & glsl::kPvProbeDisabled);
}

// Mean of a probe's interior irradiance texels, red channel, at true scale (E / pi).
double irradiance_of(const std::vector<uint8_t>& bytes, size_t probe, const PvProbe& p) {
  const uint16_t* h = reinterpret_cast<const uint16_t*>(bytes.data());
  double sum = 0;
  for (uint32_t y = 1; y <= glsl::kPvIrradianceInterior; ++y)
    for (uint32_t x = 1; x <= glsl::kPvIrradianceInterior; ++x)
      sum += codecs::half_to_float(h[(probe * glsl::kPvIrradianceTexels + y * glsl::kPvIrradianceSide + x) * 4]);
  return sum / (glsl::kPvIrradianceInterior * glsl::kPvIrradianceInterior) / p.offset.w;
}

// The albedo and emission the probe G-buffer stores for the walls (unorm8, RGB9E5).
double stored_albedo() { return std::floor(0.99 * 255.0 + 0.5) / 255.0; }
double stored_emission() {
  float rgb[3];
  codecs::decode_rgb9e5(codecs::encode_rgb9e5(0.01f, 0.01f, 0.01f), rgb);
  return rgb[0];
}

// probe_irradiance with every probe inside the box at E / pi = inside and the others at
// outside, each stored under the lighting scale it has in `probes`.
std::vector<uint8_t> set_irradiance(const std::vector<PvProbe>& probes, size_t bytes, double s, float inside, float outside) {
  std::vector<uint8_t> out(bytes, 0);
  uint16_t* h = reinterpret_cast<uint16_t*>(out.data());
  for (size_t i = 0; i < probes.size(); ++i) {
    const uint16_t v = codecs::float_to_half((in_box(probes[i], s) ? inside : outside) * probes[i].offset.w);
    for (uint32_t t = 0; t < glsl::kPvIrradianceTexels; ++t)
      for (int ch = 0; ch < 3; ++ch) h[(i * glsl::kPvIrradianceTexels + t) * 4 + ch] = v;
  }
  return out;
}

class ProbeVolumeEnergy : public test::GpuTest {};

// Frame 1 lights the probes from the walls' emission only (no probe is valid yet); the override
// after frame 1's convolution makes frame 2's relight read U inside, 0 outside. probe_convolve's
// mean luminance of everything arriving (PvProbe::meta.w, float) is then a U + e in a uniform
// field; the override also rewrites frame 2's irradiance, so meta.w is what is read back.
TEST_F(ProbeVolumeEnergy, OneBounceGivesAlbedoTimesIrradiancePlusEmission) {
  const BoxRun one = closed_box(1);
  RunHooks first;
  first.read = {"probe_state", "probe_irradiance"};
  const CaseRender r1 = render_case_hooked(gpu(), one.c, one.run, "low", 0, first);
  const auto probes1 = test::probes_of(r1.read.at("probe_state"));
  const double a = stored_albedo(), e = stored_emission();
  for (int k = 0; k < int(probes1.size()); ++k) {
    if (in_box(probes1[k], one.spacing)) continue;
    // Behind a wall: the walls' backs and the void only; samplers must skip it.
    const double c[3] = {(probes1[k].coord.x + 0.5) * one.spacing, (probes1[k].coord.y + 0.5) * one.spacing - 2,
                         (probes1[k].coord.z + 0.5) * one.spacing};
    if (std::max({std::abs(c[0]), std::abs(c[1]), std::abs(c[2])}) < 2.5) {
      EXPECT_FALSE(usable(probes1[k])) << "probe " << k << " just outside the box is usable";
    }
  }
  const BoxRun two = closed_box(2);
  for (const float u : {0.0f, 1.0f}) {
    RunHooks hooks;
    hooks.read = {"probe_state"};
    hooks.overrides.push_back(
        {"probe_convolve", "probe_irradiance", set_irradiance(probes1, r1.read.at("probe_irradiance").size(), two.spacing, u, 0.0f)});
    const CaseRender r = render_case_hooked(gpu(), two.c, two.run, "low", 0, hooks);
    const auto probes = test::probes_of(r.read.at("probe_state"));
    int inside = 0;
    for (size_t i = 0; i < probes.size(); ++i) {
      if (!in_box(probes[i], two.spacing)) continue;
      ++inside;
      ASSERT_TRUE(usable(probes[i])) << i;
      // Half rounding of U x scale: 2^-11 relative.
      EXPECT_NEAR(probes[i].meta.w, a * u + e, 1e-3 * (a * u + e)) << "U " << u << " probe " << i;
    }
    EXPECT_EQ(inside, 512);
  }
}

// One bounce a frame, every probe inside relit every frame (probe_select's round robin must
// not leave any behind when the budget covers them all).
TEST_F(ProbeVolumeEnergy, EveryFrameAddsOneBounce) {
  constexpr uint32_t kFrames = 12;
  const BoxRun b = closed_box(kFrames);
  RunHooks hooks;
  hooks.read = {"probe_state", "probe_irradiance"};
  const CaseRender r = render_case_hooked(gpu(), b.c, b.run, "low", 0, hooks);
  const auto probes = test::probes_of(r.read.at("probe_state"));
  const double a = stored_albedo(), e = stored_emission();
  double expected = 0;
  for (uint32_t k = 0; k < kFrames; ++k) expected = expected * a + e;
  int inside = 0;
  for (size_t i = 0; i < probes.size(); ++i) {
    if (!in_box(probes[i], b.spacing)) continue;
    ++inside;
    ASSERT_TRUE(usable(probes[i])) << i;
    EXPECT_EQ(probes[i].stamp.x, kFrames) << "probe " << i << " not relit in the last frame";
    EXPECT_NEAR(irradiance_of(r.read.at("probe_irradiance"), i, probes[i]), expected, 1e-3 * expected) << "probe " << i;
  }
  EXPECT_EQ(inside, 512);
  // The fixed point the formats imply (the case's bound for probe-volume).
  EXPECT_NEAR(e / (1.0 - a), 0.851, 0.001);
}

}  // namespace
}  // namespace gib
