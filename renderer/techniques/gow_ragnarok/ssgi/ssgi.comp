// ssgi: screen-space one-bounce indirect diffuse, and the frame's direct + indirect (see ssgi.h).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/gow_ragnarok/ssgi/ssgi_shared.h"
#include "frame.glsl"
#include "hash.glsl"
#include "sampling.glsl"
#include "finite.glsl"
layout(constant_id = kSsgiSpecLocal) const bool kHasLocal = true;
layout(local_size_x = kSsGroup, local_size_y = kSsGroup) in;
layout(set = 0, binding = kSsgiBindPosition, rgba32f) uniform readonly image2D gb_position;
layout(set = 0, binding = kSsgiBindNormal, rgba16f) uniform readonly image2D gb_normal;
layout(set = 0, binding = kSsgiBindAlbedo, rgba16f) uniform readonly image2D gb_albedo;
layout(set = 0, binding = kSsgiBindEmissive, rgba16f) uniform readonly image2D gb_emissive;
layout(set = 0, binding = kSsgiBindDirect, rgba32f) uniform readonly image2D direct_light;
layout(set = 0, binding = kSsgiBindLocal, rgba32f) uniform readonly image2D local_light;
layout(set = 0, binding = kSsgiBindOutDirect, rgba32f) uniform writeonly image2D out_direct;
layout(set = 0, binding = kSsgiBindOutIndirect, rgba32f) uniform writeonly image2D out_indirect;
layout(set = 0, binding = kSsgiBindOutRadiance, rgba32f) uniform writeonly image2D out_radiance;
layout(push_constant) uniform Push { ScreenSpacePush push; };
#include "renderer/techniques/gow_ragnarok/include/gow_screen_space.glsl"

// The `direct` AOV at pixel h: direct_light plus the SSDO-occluded local lights.
vec3 direct_at(ivec2 h) {
  vec3 d = imageLoad(direct_light, h).rgb;
  if (kHasLocal) d += imageLoad(local_light, h).rgb;
  return d;
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(out_radiance)))) return;
  vec3 direct = direct_at(p);
  vec3 indirect = vec3(0.0);
  vec4 pos = imageLoad(gb_position, p);
  if (pos.w != 0.0 && push.counts.z != 0u) {
    vec3 n = gow_ss_normal(p, push.counts.w != 0u);
    vec2 rj = gow_ss_rotation(gib_seed(), gib_frame_index(), uvec2(p), kSsStreamSsgi);
    uint dirs = push.counts.x;
    vec3 gathered = vec3(0.0);
    for (uint i = 0u; i < dirs; ++i) {
      vec3 d = gow_ss_direction(i, dirs, rj.x, n);
      ivec2 h = gow_ss_march(pos.xyz, d, push.params.x, push.counts.y, push.params.y, rj.y);
      if (h.x < 0) continue;  // off screen, or nothing within reach: no bounce found (the sky's light is direct)
      // Only the side of the hit that faces the receiver reflects towards it.
      if (dot(imageLoad(gb_normal, h).xyz, d) >= 0.0) continue;
      // Light the hit reflects after one bounce: its direct light without its own emission
      // (emission reaching the receiver straight away is direct, counted by direct_lighting's rays).
      gathered += max(direct_at(h) - imageLoad(gb_emissive, h).rgb, vec3(0.0));
    }
    // Cosine-weighted directions: the Lambertian estimate is albedo x the mean radiance found.
    indirect = imageLoad(gb_albedo, p).rgb * gathered / float(dirs);
  }
  imageStore(out_direct, p, vec4(direct, 1.0));
  imageStore(out_indirect, p, vec4(indirect, 1.0));
  imageStore(out_radiance, p, vec4(direct + indirect, 1.0));
}
