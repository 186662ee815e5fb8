// The AOV contract: what every technique's AOVs mean, by light path, so that a technique's AOV
// and the reference's are the same light (cases compare them; cases/README.md "AOVs" says the
// same for case authors). A technique declares an AOV only if it produces it exactly; the
// harness refuses to compare one it does not declare.
//
//   radiance          everything the camera sees: the technique's output.
//   direct            emission seen by the camera, plus light from the sun, local lights,
//                     emissive surfaces and the sky that reaches the first visible surface
//                     with no further bounce (a sky pixel: the sky itself).
//   indirect_diffuse  radiance - direct: light that bounced at least once more before it
//                     reached the first visible surface.
//
//   reflection        light the first visible surface's specular lobe reflects (glossy BRDF
//                     class, brdf.glsl) along its reflection rays: the sky, emissive surfaces
//                     and other surfaces' outgoing light those rays see, not the sun and local
//                     lights sampled at that surface (their highlights are in direct). 0 on
//                     surfaces without a specular lobe. It overlaps direct (the sky and emitters
//                     it sees straight away) and indirect_diffuse (light that bounced before it
//                     met the lobe): it is what a reflection pass computes, not a term of the sum.
//
// So radiance == direct + indirect_diffuse per pixel, for every technique that declares both.
// (For a glossy first hit, direct holds the sky and emitters both lobes see straight away and
// the lights both lobes reflect; indirect_diffuse holds everything that bounced before the first
// hit, whichever lobe reflected it: the name stays, the meaning is "not direct".)
// The reference path tracer splits its paths this way (path_trace.comp: a path's contribution
// is direct while it has at most one vertex after the camera's hit, the hit itself included).
#pragma once
#include <array>
#include <string_view>

namespace gib {

inline constexpr std::string_view kAovRadiance = "radiance";
inline constexpr std::string_view kAovDirect = "direct";
inline constexpr std::string_view kAovIndirectDiffuse = "indirect_diffuse";
inline constexpr std::string_view kAovReflection = "reflection";
inline constexpr std::array<std::string_view, 4> kContractAovs = {kAovRadiance, kAovDirect, kAovIndirectDiffuse,
                                                                   kAovReflection};

}  // namespace gib
