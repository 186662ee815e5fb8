// The reflection passes' settings (cubemap_capture, reflections_rt_cubemap, reflections_resolve),
// part of GowRagnarokSettings (gow_ragnarok.h); gow_ragnarok.md "Reflections".
#pragma once
#include <cstdint>

namespace gib {

enum class ReflectionMode : uint32_t { cubemap = 0, rt_cubemap = 1 };

struct GowReflectionParams {
  uint32_t reflection_mode = uint32_t(ReflectionMode::rt_cubemap);  // 0: the parallax-corrected cube map alone
  uint32_t cubemap_size = 32;         // texels per side of a cube face
  uint32_t cubemap_bounces = 4;       // path vertices of the capture's baked light
  uint32_t ssr_steps = 32;            // screen-space march steps per reflection ray
  float ssr_thickness = 0.15f;        // m behind the depth buffer that still counts as a hit
  float reflection_distance = 30.0f;  // m a reflection ray travels on screen and in the BVH
  uint32_t reflection_history = 64;   // frames the temporal resolve averages at most
};

}  // namespace gib
