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

// Visibility towards wi from the marched directions: their open (1) / blocked (0) results
// weighted by a lobe around wi, exp((cos - 1) / kLobe) (0.03 at 45 degrees, 4e-6 at 90), so a
// light above a table top reads the blocked directions near it, not a mean of the hemisphere
// (a bent cone misreads such a ring of open directions round a blocked top). Where no direction
// is near wi (a light at the horizon), the open fraction.
const float kLobe = 0.08;
float directional_visibility(uint open_bits, uint dirs, float turn, vec3 n, vec3 wi, float open_fraction) {
  float num = 0.0, den = 0.0;
  for (uint i = 0u; i < dirs; ++i) {
    float w = exp((dot(gow_ss_direction(i, dirs, turn, n), wi) - 1.0) / kLobe);
    den += w;
    if ((open_bits & (1u << i)) != 0u) num += w;
  }
  return den > 1e-3 ? num / den : open_fraction;
}

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
  vec3 n = imageLoad(gb_normal, p).xyz;
  if (!(gib_finite(n) && dot(n, n) > 0.25)) {
    // A broken normal (NaN texel) faces the camera when guarded (as direct_lighting), else it
    // stays and poisons the output, as the lighting's would.
    if (push.counts.w != 0u) {
      vec3 o, d;
      gib_camera_ray(vec2(p) + 0.5, o, d);
      n = -d;
    }
  }
  n = normalize(n);
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
  vec3 albedo = imageLoad(gb_albedo, p).rgb;
  vec3 result = vec3(0.0);
  for (uint i = 0u; i < gib_light_count(); ++i) {
    vec3 wi;
    float dist;
    vec3 e = gib_local_light(gib_lights[i], x, wi, dist);
    float c = dot(n, wi);
    if (c <= 0.0 || all(equal(e, vec3(0.0)))) continue;
    float vis = cone.w >= 1.0 ? 1.0 : directional_visibility(open_bits, dirs, rj.x, n, wi, cone.w);
    result += albedo * (c / GIB_PI) * e * vis;
  }
  imageStore(out_light, p, vec4(result, 1.0));
  imageStore(out_cone, p, cone);
}
