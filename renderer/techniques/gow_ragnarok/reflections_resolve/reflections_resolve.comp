#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/gow_ragnarok/reflections_resolve/reflections_resolve_shared.h"
#include "frame.glsl"
#include "finite.glsl"

layout(local_size_x = kReflResolveGroup, local_size_y = kReflResolveGroup) in;
layout(set = 0, binding = kReflResolveBindTrace, rgba32f) uniform readonly image2D trace;
layout(set = 0, binding = kReflResolveBindPosition, rgba32f) uniform readonly image2D gb_position;
layout(set = 0, binding = kReflResolveBindHistory, rgba32f) uniform readonly image2D history;
layout(set = 0, binding = kReflResolveBindOut, rgba32f) uniform writeonly image2D out_reflection;
layout(push_constant) uniform Push { ReflResolvePush push; };

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(out_reflection);
  if (any(greaterThanEqual(p, size))) return;
  vec4 cur = imageLoad(trace, min(p / 2, imageSize(trace) - 1));
  vec4 pos = imageLoad(gb_position, p);
  if (cur.a == 0.0 || pos.w == 0.0) {
    imageStore(out_reflection, p, vec4(0.0));
    return;
  }
  vec4 prev = vec4(0.0);
  if (push.has_history != 0u) {
    vec4 c = gib_frame.prev_view_proj * vec4(pos.xyz, 1.0);
    if (c.w > 0.0) {
      vec2 f = (c.xy / c.w * 0.5 + 0.5) * vec2(size);
      if (all(greaterThanEqual(f, vec2(0.0))) && all(lessThan(f, vec2(size)))) prev = imageLoad(history, ivec2(f));
    }
  }
  if (push.nan_guards != 0u && !(gib_finite(prev.rgb) && gib_finite(prev.a))) prev = vec4(0.0);
  float n = min(prev.a + 1.0, push.history);
  imageStore(out_reflection, p, vec4(mix(prev.rgb, cur.rgb, 1.0 / n), n));
}
