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
// So radiance == direct + indirect_diffuse per pixel, for every technique that declares both.
// The reference path tracer splits its paths this way (path_trace.comp: a path's contribution
// is direct while it has at most one vertex after the camera's hit, the hit itself included).
#pragma once
#include <array>
#include <string_view>

namespace gib {

inline constexpr std::string_view kAovRadiance = "radiance";
inline constexpr std::string_view kAovDirect = "direct";
inline constexpr std::string_view kAovIndirectDiffuse = "indirect_diffuse";
inline constexpr std::array<std::string_view, 3> kContractAovs = {kAovRadiance, kAovDirect, kAovIndirectDiffuse};

}  // namespace gib
