// probe-volume in a closed building under a bright sun (cases/extreme-range.json: 0.3 m walls,
// floor and roof, a 1e5 W/m^2 sun and a 3000-6000 sky outside) with its one interior light
// removed. Known answer: no light reaches the interior, so everything the camera sees inside
// reads exactly 0, and so does every probe classed indoor and every probe lookup on the inner
// faces. Any light there came through a wall (at 1e5 W/m^2 outside, a single leaking ray pixel
// shows).
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "harness/case.h"
#include "harness/case_render.h"
#include "metrics/image_metrics.h"
#include "renderer/techniques/probe_volume/include/probe_volume_shared.h"
#include "tests/case_rows.h"
#include "tests/gpu_fixture.h"

namespace gib {
namespace {

using glsl::PvCascade;
using glsl::PvProbe;

struct DarkBuilding {
  Case c;
  TechniqueRun pv;
  Roi interior;
};

DarkBuilding dark_building(uint32_t frames) {
  DarkBuilding b;
  b.c = load_case(std::string(GIB_SOURCE_DIR) + "/cases/extreme-range.json");
  b.c.width = 48;
  b.c.height = 27;
  b.c.frames = frames;
  b.c.scene.lights.clear();
  b.pv = test::plain_row(b.c, "probe-volume");
  b.pv.frames = frames;
  for (const Roi& roi : b.c.rois)
    if (roi.name == "interior") b.interior = roi;
  return b;
}

double interior_mean(const DarkBuilding& b, const FloatImage& img) {
  return metrics::roi_mean_luminance(img, b.interior.x0, b.interior.y0, b.interior.x1, b.interior.y1);
}

class ProbeVolumeLeak : public test::GpuTest {};

// The per-pixel path (screen_trace, world_trace, hit_lighting) and the probes classed indoor.
// Before screen_trace kept its results within the ray's indoor / outdoor class, the interior
// read 0.947 here (points on a floor's plane past its edge, inside the wall, were lit by the
// outdoor probes; ends of screen misses past a wall took the outdoor radiance probes), while
// every indoor probe already read 0.
TEST_F(ProbeVolumeLeak, ClosedBuildingStaysDarkInside) {
  const DarkBuilding b = dark_building(32);
  RunHooks hooks;
  hooks.read = {"probe_state"};
  const CaseRender r = render_case_hooked(gpu(), b.c, b.pv, "medium", 0, hooks);
  EXPECT_EQ(interior_mean(b, r.image), 0.0);
  int indoor = 0;
  for (const PvProbe& p : test::probes_of(r.read.at("probe_state"))) {
    const uint32_t f = uint32_t(p.coord.w);
    if (!(f & glsl::kPvProbeIndoor) || !(f & glsl::kPvProbeValid) || (f & glsl::kPvProbeDisabled)) continue;
    ++indoor;
    EXPECT_EQ(p.meta.w, 0.0f) << "indoor probe at cell " << p.coord.x << " " << p.coord.y << " " << p.coord.z;
  }
  EXPECT_GT(indoor, 500);
}

// The probe lookups on the surfaces the camera sees (lookup_view: each ray pixel carries the
// probes' irradiance at its own surface), the walls' inner faces and the floor among them: the
// 0.3 m walls between the outdoor probes and the indoor ones, 0.5 m apart, let nothing through.
TEST_F(ProbeVolumeLeak, LookupsOnTheInnerFacesReadZero) {
  DarkBuilding b = dark_building(16);
  b.pv.options["lookup_view"] = 1;
  const CaseRender r = render_case(gpu(), b.c, b.pv, "medium");
  EXPECT_EQ(interior_mean(b, r.image), 0.0);
}

}  // namespace
}  // namespace gib
