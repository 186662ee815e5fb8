// probe-volume's per-pixel path and probe lookups against the path tracer, one light path class at
// a time, in the sunlit thin-wall room (cases/thin-wall-leak-005.json at 64x36) with the sky off:
// the room is lit only by the sun the window lets in (the patch on the floor and the west wall)
// and by the sunlit ground outside. Each ratio is the room ROI's mean indirect_diffuse over the
// reference's (256 spp, max_bounces capping the path).
//   - One interreflection (max_bounces 2: pixel -> hit -> sun): every probe's irradiance and
//     radiance overridden to 0, so the technique's indirect is the per-pixel hits' traced sun
//     alone (screen_trace, world_trace, hit_lighting, pixel_denoise, pixel_upscale).
//   - Two (max_bounces 3: pixel -> hit -> hit -> sun): multi_bounce 0, so the probes hold the sun
//     at their texels only, and the per-pixel hits add albedo x the probes' irradiance there.
// Rays reach far enough that no path ends in a radiance-probe lookup (pixel_range 10; trace_range
// 20 spacings, 10 m, or 100, 50 m, where the probes must see the whole 60 m ground: beyond 10 m
// it still gives the probes 0.035 of their irradiance here). At the default pixel_range 2 the
// per-pixel hits carry 0.20 of the one-interreflection light in this room, the rest arrives
// through the radiance probes at the rays' ends.
//   - The probes' own irradiance against the path tracer at their positions.
//   - The probe lookups' share of the second interreflection.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "harness/case.h"
#include "harness/case_render.h"
#include "metrics/image_metrics.h"
#include "renderer/codecs/octahedral.h"
#include "renderer/codecs/packed_float.h"
#include "renderer/techniques/probe_volume/include/probe_volume_shared.h"
#include "tests/case_rows.h"
#include "tests/gpu_fixture.h"

namespace gib {
namespace {

struct Room {
  Case c;
  TechniqueRun pv;
  Roi roi;
};

// with_ground false: the ground quad outside removed (the room stands on its floor slab).
Room sunlit_room(uint32_t frames, bool with_ground, double trace_range = 20) {
  Room r;
  r.c = load_case(std::string(GIB_SOURCE_DIR) + "/cases/thin-wall-leak-005.json");
  r.c.width = 64;
  r.c.height = 36;
  r.c.frames = frames;
  r.c.scene.sky.kind = SkyKind::none;
  if (!with_ground) {
    auto& inst = r.c.scene.instances;
    for (size_t i = 0; i < inst.size(); ++i)
      if (inst[i].name == "ground") inst.erase(inst.begin() + std::ptrdiff_t(i--));
  }
  for (const TechniqueRun& t : r.c.techniques)
    if (t.technique == "probe-volume" && t.label.empty()) r.pv = t;
  r.pv.frames = frames;
  r.pv.options["pixel_range"] = 10;
  r.pv.options["trace_range"] = trace_range;
  for (const Roi& roi : r.c.rois)
    if (roi.name == "room") r.roi = roi;
  return r;
}

double room_mean(const Room& r, const FloatImage& img) {
  return metrics::roi_mean_luminance(img, r.roi.x0, r.roi.y0, r.roi.x1, r.roi.y1);
}

double reference_room(Gpu& gpu, const Room& r, uint32_t max_bounces) {
  TechniqueRun ref;
  ref.technique = "reference";
  ref.compare_aov = "indirect_diffuse";
  ref.options = {{"max_bounces", double(max_bounces)}};
  ref.spp = 256;
  return room_mean(r, render_case(gpu, r.c, ref, "ultra").image);
}

class ProbeVolumePixelEnergy : public test::GpuTest {};
class SlowProbeVolumePixelEnergy : public test::GpuTest {};  // over 120 s on two cores

// Luminance ratio of a over b in blocks of `block` pixels, printed as a map (rows top first).
void print_ratio_map(const FloatImage& a, const FloatImage& b, uint32_t block) {
  for (uint32_t by = 0; by + block <= a.height; by += block) {
    for (uint32_t bx = 0; bx + block <= a.width; bx += block) {
      double sa = 0, sb = 0;
      for (uint32_t y = by; y < by + block; ++y)
        for (uint32_t x = bx; x < bx + block; ++x) {
          sa += 0.2126 * a.at(x, y, 0) + 0.7152 * a.at(x, y, 1) + 0.0722 * a.at(x, y, 2);
          sb += 0.2126 * b.at(x, y, 0) + 0.7152 * b.at(x, y, 1) + 0.0722 * b.at(x, y, 2);
        }
      std::printf(sb > 1e-6 ? " %5.2f" : "     -", sa / sb);
    }
    std::printf("\n");
  }
}

// Measured (lavapipe): 0.1192 against 0.1158, ratio 1.029.
TEST_F(ProbeVolumePixelEnergy, SunAtPerPixelHitsMatchesOneInterreflection) {
  const Room room = sunlit_room(32, true);
  RunHooks sizes;
  sizes.read = {"probe_irradiance", "probe_radiance"};
  const CaseRender r1 = render_case_hooked(gpu(), sunlit_room(1, true).c, room.pv, "medium", 0, sizes);
  RunHooks dark;
  for (const char* probes : {"probe_irradiance", "probe_radiance"})
    dark.overrides.push_back({"probe_convolve", probes, std::vector<uint8_t>(r1.read.at(probes).size(), 0)});
  const double got = room_mean(room, render_case_hooked(gpu(), room.c, room.pv, "medium", 0, dark).image);
  const double ref = reference_room(gpu(), room, 2);
  std::printf("one interreflection: probe-volume %.5f reference %.5f ratio %.4f\n", got, ref, got / ref);
  EXPECT_NEAR(got / ref, 1.0, 0.05);
}

// Every probe relit every frame (budget 4096), 48 frames. Measured (lavapipe): 0.1508 against
// 0.1458, ratio 1.034 (0.997 while a lookup at a +-x or +-y normal read the irradiance texel 14
// degrees towards +z: the probe lookups carried 0.87 of the second interreflection, the per-pixel
// sun's 1.03 hid it; ProbeLookupsCarryTheSecondInterreflection below splits the two).
TEST_F(ProbeVolumePixelEnergy, ProbesCarryTheSecondInterreflectionIndoors) {
  Room room = sunlit_room(48, false);
  room.pv.options["multi_bounce"] = 0;
  room.pv.options["probe_budget"] = 4096;
  const double got = room_mean(room, render_case_hooked(gpu(), room.c, room.pv, "medium", 0, RunHooks{}).image);
  const double ref = reference_room(gpu(), room, 3);
  std::printf("two interreflections, no ground outside: probe-volume %.5f reference %.5f ratio %.4f\n", got, ref, got / ref);
  EXPECT_NEAR(got / ref, 1.0, 0.05);
}

// The second interreflection's share that comes through the probe lookups: the technique's room
// with the converged probes (multi_bounce 0, read after 8 frames and overridden every frame)
// minus the same run with the probes of a class at 0 (same seeds: the per-pixel sun's noise
// cancels), against the reference's max_bounces 3 minus 2; probe rays reach 50 m (trace_range
// 100) so that the probes see the whole ground. Measured (lavapipe): with the ground outside
// 0.0792 of 0.0800 (0.990; outdoor probes 0.0014), without it 0.0586 of 0.0603 (0.972; 0.0005).
// With the irradiance tile's plain mirrored border (a lookup at a +-x or +-y normal read the
// texel 14 degrees towards +z) and 10 m probe rays: 0.80 / 0.87; the border alone 0.937 / 0.971.
TEST_F(SlowProbeVolumePixelEnergy, ProbeLookupsCarryTheSecondInterreflection) {
  for (bool ground : {true, false}) {
    Room room = sunlit_room(8, ground, 100);
    room.pv.options["multi_bounce"] = 0;
    room.pv.options["probe_budget"] = 4096;
    RunHooks hooks;
    hooks.read = {"probe_state", "probe_irradiance", "probe_radiance"};
    const CaseRender r = render_case_hooked(gpu(), room.c, room.pv, "medium", 0, hooks);
    const std::vector<glsl::PvProbe> probes = test::probes_of(r.read.at("probe_state"));
    Room full = sunlit_room(48, ground, 100);
    full.pv.options = room.pv.options;
    full.pv.frames = 48;
    double room_with[3];  // probes as converged, outdoor ones at 0, indoor ones at 0
    for (int zero = -1; zero <= 1; ++zero) {  // -1 none, 0 outdoor zeroed, 1 indoor zeroed
      RunHooks o;
      for (const char* name : {"probe_irradiance", "probe_radiance"}) {
        std::vector<uint8_t> data = r.read.at(name);
        const size_t per = data.size() / probes.size();
        for (size_t i = 0; i < probes.size(); ++i) {
          const bool indoor = (uint32_t(probes[i].coord.w) & glsl::kPvProbeIndoor) != 0;
          if (zero >= 0 && indoor == (zero == 1)) std::memset(data.data() + i * per, 0, per);
        }
        o.overrides.push_back({"probe_convolve", name, data});
      }
      room_with[zero + 1] = room_mean(full, render_case_hooked(gpu(), full.c, full.pv, "medium", 0, o).image);
    }
    const double outdoor = room_with[0] - room_with[1], lookups = room_with[0] - room_with[2] + outdoor;
    const double second = reference_room(gpu(), full, 3) - reference_room(gpu(), full, 2);
    std::printf("ground %d: probe lookups %.5f (outdoor probes %.5f), reference second interreflection %.5f, ratio %.4f\n",
                ground, lookups, outdoor, second, lookups / second);
    EXPECT_NEAR(lookups / second, 1.0, 0.05) << "ground " << ground;
  }
}

// The probes' own irradiance against the path tracer at their positions: with multi_bounce 0 a
// probe's texels hold the sun on the surfaces they see, so its E / pi for a normal n is the
// cosine-weighted mean of the one-bounce radiance around it (the reference's max_bounces 1
// radiance), here from six 90-degree renders per probe, for the 64 indoor probes 0.75 m above
// the floor and the six axis normals (read back and looked up as pv_irradiance_at does).
// Measured (lavapipe, trace_range 100): 0.9987 summed, axes 1.041 / 0.992 / 1.069 / 0.989 /
// 0.978 / 1.011 (+x, -x, +y, -y, +z, -z; +x and +y are dim here). With the irradiance tile's
// middle border texels copied (the plain mirrored border) the same reads 0.959 (+-x and +-y
// 0.88-0.92: a lookup at an equator vertex read the texel 14 degrees towards +z, away from the
// window); with 10 m probe rays 0.966 (the ground beyond 10 m missing).
TEST_F(ProbeVolumePixelEnergy, ProbesHoldTheIrradianceAroundThem) {
  Room room = sunlit_room(24, true, 100);
  room.pv.options["multi_bounce"] = 0;
  room.pv.options["probe_budget"] = 4096;
  RunHooks hooks;
  hooks.read = {"probe_state", "probe_irradiance"};
  const CaseRender r = render_case_hooked(gpu(), room.c, room.pv, "medium", 0, hooks);
  const std::vector<glsl::PvProbe> probes = test::probes_of(r.read.at("probe_state"));
  const auto& irr = r.read.at("probe_irradiance");
  const int interior = int(glsl::kPvIrradianceInterior), side = int(glsl::kPvIrradianceSide);
  // Bilinear lookup in probe i's bordered tile, as pv_irradiance_at: luminance of E / pi.
  auto probe_lookup = [&](size_t i, Vec3 n) {
    const Vec2 tc = codecs::oct_tile_coord(n, interior);
    const float fx = tc.x - 0.5f, fy = tc.y - 0.5f;
    const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
    auto fetch = [&](int x, int y) {
      uint16_t h[4];
      std::memcpy(h, irr.data() + (i * size_t(side * side) + size_t(y * side + x)) * 8, 8);
      return 0.2126 * codecs::half_to_float(h[0]) + 0.7152 * codecs::half_to_float(h[1]) +
             0.0722 * codecs::half_to_float(h[2]);
    };
    const double ax = fx - float(x0), ay = fy - float(y0);
    const double v = (fetch(x0, y0) * (1 - ax) + fetch(x0 + 1, y0) * ax) * (1 - ay) +
                     (fetch(x0, y0 + 1) * (1 - ax) + fetch(x0 + 1, y0 + 1) * ax) * ay;
    return v / probes[i].offset.w;
  };
  TechniqueRun ref;
  ref.technique = "reference";
  ref.compare_aov = "radiance";
  ref.options = {{"max_bounces", 1.0}};
  ref.spp = 64;
  const Vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  const float spacing = 0.5f;  // the case's probe_spacing
  const int layer = 1;         // cells y = 1: 0.75 m
  double probe_sum[6] = {}, ref_sum[6] = {};
  for (int cz = -4; cz <= 3; ++cz)
    for (int cx = -4; cx <= 3; ++cx) {
      size_t found = probes.size();
      for (size_t i = 0; i < probes.size() / 2; ++i)  // cascade 0
        if (probes[i].coord.x == cx && probes[i].coord.y == layer && probes[i].coord.z == cz) found = i;
      ASSERT_LT(found, probes.size()) << cx << " " << cz;
      const glsl::PvProbe& p = probes[found];
      ASSERT_NE(uint32_t(p.coord.w) & glsl::kPvProbeIndoor, 0u);
      const Vec3 at{(float(cx) + 0.5f) * spacing + p.offset.x, (float(layer) + 0.5f) * spacing + p.offset.y,
                    (float(cz) + 0.5f) * spacing + p.offset.z};
      for (const Vec3& f : axes) {
        Case c = room.c;
        c.width = c.height = 16;
        c.frames = 1;
        c.scene.camera.position = at;
        c.scene.camera.target = at + f;
        c.scene.camera.up = std::fabs(f.y) > 0.5f ? Vec3{0, 0, 1} : Vec3{0, 1, 0};
        c.scene.camera.fov_y_deg = 90.0f;
        c.scene.camera.near_plane = 0.001f;
        c.scene.camera.animation.clear();
        const FloatImage img = render_case(gpu(), c, ref, "ultra").image;
        const Vec3 right = normalize(cross(f, c.scene.camera.up)), up = cross(right, f);
        for (uint32_t y = 0; y < img.height; ++y)
          for (uint32_t x = 0; x < img.width; ++x) {
            const float u = 2.0f * (float(x) + 0.5f) / float(img.width) - 1.0f;
            const float v = 1.0f - 2.0f * (float(y) + 0.5f) / float(img.height);
            const Vec3 d = f + right * u + up * v;
            const double len = std::sqrt(double(dot(d, d)));
            const double solid = (2.0 / img.width) * (2.0 / img.height) / (len * len * len);
            const double lum = 0.2126 * img.at(x, y, 0) + 0.7152 * img.at(x, y, 1) + 0.0722 * img.at(x, y, 2);
            for (int k = 0; k < 6; ++k) ref_sum[k] += std::max(0.0, dot(axes[k], d) / len) * solid * lum / 3.14159265358979;
          }
      }
      for (int k = 0; k < 6; ++k) probe_sum[k] += probe_lookup(found, axes[k]);
    }
  double got = 0, want = 0;
  for (int k = 0; k < 6; ++k) {
    std::printf("normal %d: probes %.4f reference %.4f ratio %.4f\n", k, probe_sum[k], ref_sum[k], probe_sum[k] / ref_sum[k]);
    got += probe_sum[k];
    want += ref_sum[k];
  }
  std::printf("probes' E / pi over the path tracer's, summed: %.4f / %.4f = %.4f\n", got, want, got / want);
  EXPECT_NEAR(got / want, 1.0, 0.03);
}

// The probe lookups at the surfaces the camera sees: lookup_view replaces each ray pixel's light
// by the probes' irradiance at its own surface; with multi_bounce 0 the probes hold the sun at
// their texels, so the image is the probes' estimate of the one-interreflection image
// (max_bounces 2), which the per-pixel rays deliver in the technique. A diagnostic of where the
// lookups gain or lose (the ratio map printed in blocks of 4x4 pixels), not a bound of the
// technique: measured (lavapipe, trace_range 100) 1.105 with the ground outside and 1.050
// without (0.791 / 0.934 at trace_range 20 with the plain mirrored border). The excess sits on
// surfaces whose nearest probes are closer than they are to the sunlit patch (the ceiling
// above it, the floor next to it), so disabled.
TEST_F(ProbeVolumePixelEnergy, DISABLED_ProbeLookupsAtVisibleSurfacesMatchOneInterreflection) {
  for (bool ground : {true, false}) {
    Room room = sunlit_room(24, ground, 100);
    room.pv.options["multi_bounce"] = 0;
    room.pv.options["probe_budget"] = 4096;
    room.pv.options["lookup_view"] = 1;
    const FloatImage got = render_case_hooked(gpu(), room.c, room.pv, "medium", 0, RunHooks{}).image;
    TechniqueRun ref;
    ref.technique = "reference";
    ref.compare_aov = "indirect_diffuse";
    ref.options = {{"max_bounces", 2.0}};
    ref.spp = 256;
    const FloatImage want = render_case(gpu(), room.c, ref, "ultra").image;
    const double g = room_mean(room, got), w = room_mean(room, want);
    std::printf("ground %d: probe lookups at the visible surfaces %.5f, reference one interreflection %.5f, ratio %.4f\n",
                ground, g, w, g / w);
    print_ratio_map(got, want, 4);
    EXPECT_NEAR(g / w, 1.0, 0.05) << "ground " << ground;
  }
}

}  // namespace
}  // namespace gib
