// ssdo_ssgi: SSDO and SSGI in one pass (option ss_combined 1, the default), as the seed ships
// them: each G-buffer texel a pixel shades is read once, and one march per direction serves
// both terms (SSDO's blocker and SSGI's bounce, each with its own radius and thickness, on steps
// of the shorter of the two step lengths). Each thread shades a 2x2 pixel block and marches from
// one of its pixels (chosen per frame by a hash); the four threads of a 2x2 quad (4x4 pixels)
// share one turned direction set of max(ssdo_directions, ssgi_directions) directions, each
// marching a quarter of them, and every pixel takes the results of the quad's threads on its own
// surface (depth and normal agreement). A pixel so reads the whole direction set at a sixteenth
// of the marches. Two dispatches: ssdo_ssgi_surfaces.comp picks each block's marched pixel and
// writes it to ss_surfaces (half size, 8 bytes a texel: distance, normal, which pixel), which
// the marches' depth tests read in place of the full-size G-buffer (ssdo_ssgi.comp). The bounce at a hit reads direct_light and last frame's ssdo_local_light (this
// frame's is being computed here). Outputs as the separate passes (ssdo/, ssgi/: option
// ss_combined 0, kept for comparison): ssdo_local_light where the scene has unshadowed local
// lights, ssgi_indirect and gow_radiance; the debug view ssdo_cone only with option ss_cone 1.
// gow_direct (the `direct` AOV) is written by direct_aov, only where it is asked for. The two histories (ssdo_local_light, ssgi_indirect) are RGBA16F, the separate
// passes' images RGBA32F.
// Seed: God of War Ragnarök, "Raytraced Cubemaps" profile: "SSR, SSDO and SSGI: 4.23ms,
// combined to avoid sampling G-Buffer data twice" (PS5, 4K); SSR stays in reflections_rt_cubemap.
// Limits: as ssdo and ssgi, plus: the results are shared over 4x4 pixels (blocky noise where
// a surface is only a pixel or two wide: such a pixel keeps its own block's quarter of the set);
// a moving camera bounces last frame's local light at the same pixel, not reprojected.
#pragma once
#include <memory>

#include "renderer/graph/pass.h"

namespace gib {
std::unique_ptr<Pass> make_ssdo_ssgi_pass();
}
