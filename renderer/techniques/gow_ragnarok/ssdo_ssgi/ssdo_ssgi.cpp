#include "renderer/techniques/gow_ragnarok/ssdo_ssgi/ssdo_ssgi.h"

#include <algorithm>
#include <cmath>

#include "renderer/techniques/gow_ragnarok/gow_ragnarok.h"
#include "renderer/techniques/gow_ragnarok/ssdo_ssgi/ssdo_ssgi_shared.h"

namespace gib {
namespace {

// The combined march: the shorter of the two terms' step lengths, out to the longer radius.
struct CombinedMarch {
  uint32_t directions, steps;
  float step;
};
CombinedMarch combined_march(const GowRagnarokSettings& g) {
  const float step = std::min(g.ssdo_radius / float(g.ssdo_steps), g.ssgi_radius / float(g.ssgi_steps));
  const float reach = std::max(g.ssdo ? g.ssdo_radius : 0.0f, g.ssgi ? g.ssgi_radius : 0.0f);
  const auto steps = uint32_t(std::ceil(reach / step - 1e-4f));
  return {std::max(g.ssdo_directions, g.ssgi_directions), std::min(steps, 4 * glsl::kSsMaxSteps), step};
}

class SsdoSsgiPass final : public Pass {
 public:
  PassDecl declare(const Scene& scene, const Settings& s) const override {
    const auto& g = s.params<GowRagnarokSettings>();
    PassDecl d;
    d.name = "ssdo_ssgi";
    if (!g.ss_combined) return d;  // the separate passes run: nothing to write, culled
    const ResourceDesc out = ResourceDesc{Format::rgba32_float, SizeRule::render}.with(non_negative_values());
    // gow_direct (the `direct` AOV, direct_light + ssdo_local_light) is direct_aov's: nothing
    // in the frame reads it, so it costs only where it is asked for.
    d.slots = {{"gbuffer_position", Access::read}, {"gbuffer_normal", Access::read},
               {"gbuffer_albedo", Access::read},   {"gbuffer_emissive", Access::read},
               {"direct_light", Access::read},     {"gow_radiance", Access::write, out}};
    // Each 2x2 block's surface, the one the marches' depth tests read (ssdo_ssgi_surfaces.comp).
    d.slots.push_back({"ss_surfaces", Access::write, ResourceDesc{Format::rg32_uint, SizeRule::half}});
    // The temporal accumulation's histories, in 16-bit floats (8 bytes a pixel where 32-bit took
    // 16, each written and read back every frame): radiance in W/(m^2 sr), stored rounded to
    // nearest and clamped to the half's largest value (the stability scan counts a clamped
    // texel as saturated). Sun-lit surfaces under a 1e5 W/m^2 sun reflect at most 1e5 / pi.
    ResourceDesc history = ResourceDesc{Format::rgba16_float, SizeRule::render}.with(non_negative_values());
    history.persistent = true;
    d.slots.push_back({"ssgi_indirect", Access::write, history});
    d.slots.push_back({"ssgi_indirect", Access::read_prev});
    if (gow_unshadowed_local_lights(scene, s)) {
      // Last frame's: the bounce's local light and the accumulation's history.
      d.slots.push_back({"ssdo_local_light", Access::write, history});
      d.slots.push_back({"ssdo_local_light", Access::read_prev});
      // The debug view only when asked for (option ss_cone): 8 bytes a pixel nothing else reads.
      if (g.ss_cone)
        d.slots.push_back({"ssdo_cone", Access::write,
                           ResourceDesc{Format::rgba16_float, SizeRule::render}.with(finite_values())});
    }
    const CombinedMarch m = combined_march(g);
    const double blocks = std::ceil(s.width / 2.0) * std::ceil(s.height / 2.0);
    d.work = {{"march_steps", g.ssdo || g.ssgi ? blocks * m.directions / 4.0 * m.steps : 0.0}};
    return d;
  }

  void record(RecordContext& ctx) override {
    using namespace glsl;
    const auto& g = ctx.settings.params<GowRagnarokSettings>();
    const bool local = gow_unshadowed_local_lights(ctx.scene, ctx.settings);
    const CombinedMarch m = combined_march(g);
    SsCombinedPush push{{g.ssdo_radius, g.ssgi_radius, m.step, 0.0f},
                        {g.ssdo_thickness, g.ssgi_thickness, 0.0f, 0.0f},
                        {m.directions, m.steps, (g.ssdo ? 1u : 0u) | (g.ssgi ? 2u : 0u),
                         ctx.settings.nan_guards ? 1u : 0u},
                        {ctx.frame > 0 ? 1u : 0u, g.ss_history, 0u, 0u}};
    record_compute(ctx, {.shader = "ssdo_ssgi_surfaces.comp",
                         .images = {{kSsCombinedBindPosition, "gbuffer_position"},
                                    {kSsCombinedBindNormal, "gbuffer_normal"},
                                    {kSsCombinedBindSurfaces, "ss_surfaces"}},
                         .groups_x = div_up(ctx.width("ss_surfaces"), kSsSurfacesGroup),
                         .groups_y = div_up(ctx.height("ss_surfaces"), kSsSurfacesGroup),
                         .label = "ssdo_ssgi/surfaces",
                         .barrier_after = true});
    const bool cone = local && g.ss_cone;
    // Without local lights (or the cone) those bindings hold an RGBA16F image the pass reads or
    // writes anyway, unused.
    record_compute(ctx, {.shader = "ssdo_ssgi.comp",
                         .images = {{kSsCombinedBindPosition, "gbuffer_position"},
                                    {kSsCombinedBindNormal, "gbuffer_normal"},
                                    {kSsCombinedBindAlbedo, "gbuffer_albedo"},
                                    {kSsCombinedBindEmissive, "gbuffer_emissive"},
                                    {kSsCombinedBindDirect, "direct_light"},
                                    {kSsCombinedBindLocalPrev, local ? "ssdo_local_light" : "ssgi_indirect", true},
                                    {kSsCombinedBindLocal, local ? "ssdo_local_light" : "ssgi_indirect"},
                                    {kSsCombinedBindCone, cone ? "ssdo_cone" : "ssgi_indirect"},
                                    {kSsCombinedBindOutIndirect, "ssgi_indirect"},
                                    {kSsCombinedBindOutRadiance, "gow_radiance"},
                                    {kSsCombinedBindIndirectPrev, "ssgi_indirect", true},
                                    {kSsCombinedBindSurfaces, "ss_surfaces"}},
                         .groups_x = div_up(div_up(ctx.width("gow_radiance"), kSsCombinedBlock), kSsGroup),
                         .groups_y = div_up(div_up(ctx.height("gow_radiance"), kSsCombinedBlock), kSsGroup),
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .spec_constants = {{kSsCombinedSpecLocal, local},
                                            {kSsCombinedSpecDirections, m.directions},
                                            {kSsCombinedSpecCone, cone}}});
  }
};

}  // namespace

std::unique_ptr<Pass> make_ssdo_ssgi_pass() { return std::make_unique<SsdoSsgiPass>(); }

}  // namespace gib
