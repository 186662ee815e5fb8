// ssdo: screen-space directional occlusion of the unshadowed local lights (see ssdo.h).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/gow_ragnarok/ssdo/ssdo_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#include "hash.glsl"
#include "sampling.glsl"
#include "lights.glsl"
#include "finite.glsl"
layout(local_size_x = kSsGroup, local_size_y = kSsGroup) in;
layout(set = 0, binding = kSsdoBindPosition, rgba32f) uniform readonly image2D gb_position;
layout(set = 0, binding = kSsdoBindNormal, rgba16f) uniform readonly image2D gb_normal;
layout(set = 0, binding = kSsdoBindAlbedo, rgba16f) uniform readonly image2D gb_albedo;
layout(set = 0, binding = kSsdoBindLight, rgba32f) uniform writeonly image2D out_light;
layout(set = 0, binding = kSsdoBindCone, rgba16f) uniform writeonly image2D out_cone;
layout(push_constant) uniform Push { ScreenSpacePush push; };
#include "renderer/techniques/gow_ragnarok/include/gow_screen_space.glsl"
#include "renderer/techniques/gow_ragnarok/include/gow_ss_lights.glsl"

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(out_light)))) return;
  vec4 pos = imageLoad(gb_position, p);
  if (pos.w == 0.0) {  // sky: no surface, no local light
    imageStore(out_light, p, vec4(0.0));
    imageStore(out_cone, p, vec4(0.0, 0.0, 0.0, 1.0));
    return;
  }
  vec3 x = pos.xyz;
  vec3 n = gow_ss_normal(p, push.counts.w != 0u);
  // Open directions: bit i for direction i (kSsMaxDirections <= 32); the bent normal and
  // open fraction (ssdo_cone: ambient occlusion, a debug view).
  vec4 cone = vec4(n, 1.0);
  uint dirs = push.counts.x;
  uint open_bits = 0xffffffffu;
  vec2 rj = gow_ss_rotation(gib_seed(), gib_frame_index(), uvec2(p), kSsStreamSsdo);
  if (push.counts.z != 0u) {
    vec3 bent = vec3(0.0);
    open_bits = 0u;
    for (uint i = 0u; i < dirs; ++i) {
      vec3 d = gow_ss_direction(i, dirs, rj.x, n);
      if (gow_ss_march(x, d, push.params.x, push.counts.y, push.params.y, rj.y).x < 0) {
        bent += d;
        open_bits |= 1u << i;
      }
    }
    float v = float(bitCount(open_bits)) / float(dirs);
    cone = vec4(dot(bent, bent) > 0.0 ? normalize(bent) : n, v);
  }
  vec3 result = gow_ss_local_light(x, n, imageLoad(gb_albedo, p).rgb, open_bits, 0xffffffffu, dirs, rj.x, cone.w);
  imageStore(out_light, p, vec4(result, 1.0));
  imageStore(out_cone, p, cone);
}
