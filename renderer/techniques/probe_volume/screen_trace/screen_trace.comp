// screen_trace: the per-pixel rays marched against the depth buffer first (see screen_trace.h).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/probe_volume/screen_trace/screen_trace_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#include "hash.glsl"
#include "finite.glsl"
#include "sampling.glsl"
#include "surface.glsl"
#include "ycocg_sh.glsl"
layout(push_constant) uniform Push {
  PvParams pv;
  vec4 screen;
};
#include "renderer/techniques/probe_volume/include/pv_common.glsl"
PV_STATE_BUFFER(kPvScreenTraceBindState, readonly)
#include "renderer/techniques/probe_volume/include/pv_volume.glsl"
layout(set = 0, binding = kPvScreenTraceBindPosition, rgba32f) uniform readonly image2D gb_position;
layout(set = 0, binding = kPvScreenTraceBindNormal, rgba16f) uniform readonly image2D gb_normal;
layout(set = 0, binding = kPvScreenTraceBindEmissive, rgba16f) uniform readonly image2D gb_emissive;
layout(set = 0, binding = kPvScreenTraceBindAlbedo, rgba16f) uniform readonly image2D gb_albedo;
layout(set = 0, binding = kPvScreenTraceBindHits, rgba32ui) uniform writeonly uimage2D out_hits;
layout(std430, set = 0, binding = kPvScreenTraceBindStats) buffer StatsBuffer { uvec4 stats; };
layout(local_size_x = kPvScreenTraceGroup, local_size_y = kPvScreenTraceGroup) in;
#define PV_PIXEL_GBUFFER
#include "renderer/techniques/probe_volume/include/pv_pixel.glsl"

// Clip x, y, w of a world point, camera-relative (precise far from the origin): the camera's
// own clip x, y, w are 0, so only the offset from it is transformed.
vec3 clip_xyw(vec3 p) {
  vec4 c = gib_frame.view_proj * vec4(p - gib_frame.camera_pos.xyz, 0.0);
  return c.xyw;
}

void store_world(ivec2 q, float start, uint flags) {
  // Resuming from the last point seen in front of the depth buffer skips what a pixel straddling
  // a silhouette hides (the point is in front of the far surface that pixel shows, already
  // behind the near wall): off by default, the ray is traced whole.
  if (screen.z == 0.0) start = pv_min_start();
  imageStore(out_hits, q, uvec4(0u, 0u, floatBitsToUint(start), flags | kPvPixelWorld));
  atomicAdd(stats.w, 1u);
}

void main() {
  ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(q, imageSize(out_hits)))) return;
  ivec2 p = pv_source_pixel(q);
  vec4 pos = imageLoad(gb_position, p);
  if (pos.w == 0.0) {
    imageStore(out_hits, q, uvec4(0u));
    return;
  }
  atomicAdd(stats.x, 1u);
  PvPixelRay r = pv_pixel_ray_from(q, p, pos.xyz);
  uint flags = kPvPixelValid | (r.back ? kPvPixelBack : 0u);
  uint steps = uint(screen.x);
  // Back-side rays of translucent surfaces skip the screen (what is behind is not on it).
  if (steps == 0u || r.back) {
    store_world(q, pv_min_start(), flags);
    return;
  }
  // The indoor / outdoor class of the side the ray leaves from (pv_point_indoor): a screen
  // result of the other class goes to the BVH (below).
  vec3 n0 = imageLoad(gb_normal, p).xyz;
  bool indoor = pv_point_indoor(pos.xyz, gib_finite(n0) && dot(n0, n0) > 0.25 ? normalize(n0) : vec3(0.0));
  float range = pv_pixel_range(pos.xyz);
  // The march's end: the range, or just before the camera plane if the ray crosses it.
  vec3 c0 = clip_xyw(r.origin), cd = clip_xyw(r.origin + r.dir) - c0;
  float t_end = range;
  const float kNearW = 1e-3;
  if (c0.z + cd.z * t_end < kNearW) t_end = max((kNearW - c0.z) / cd.z, 0.0);
  bool clipped = t_end < range;
  vec3 c1 = c0 + cd * t_end;
  vec2 size = vec2(gib_render_size());
  float thickness = screen.y;
  float last = pv_min_start();  // the last distance known to be in front of the depth buffer
  for (uint i = 1u; i <= steps; ++i) {
    // Uniform steps on screen: 1/w and the ray parameter over w are linear there.
    float u = float(i) / float(steps);
    float inv_w = mix(1.0 / c0.z, 1.0 / c1.z, u);
    float t = mix(0.0, t_end / c1.z, u) / inv_w;
    if (t < pv_min_start()) continue;
    vec2 ndc = mix(c0.xy / c0.z, c1.xy / c1.z, u);
    vec2 pixel = (ndc * 0.5 + 0.5) * size;
    if (any(lessThan(pixel, vec2(0.0))) || any(greaterThanEqual(pixel, size))) {
      store_world(q, last, flags);  // left the screen
      return;
    }
    ivec2 hp = ivec2(pixel);
    vec4 hpos = imageLoad(gb_position, hp);
    if (hpos.w == 0.0) {
      last = t;  // the sky: nothing in front of it
      continue;
    }
    // Against the plane of the surface the pixel shows (its normal faces the camera), not the
    // distance at the pixel's centre: a wall seen at a grazing angle changes distance a lot
    // across one pixel, and a point just behind it would compare as in front.
    vec3 x = r.origin + r.dir * t;
    vec3 hn = normalize(imageLoad(gb_normal, hp).xyz);
    float height = dot(x - hpos.xyz, hn);
    if (height >= 0.0) {
      last = t;  // in front of what the camera sees
      continue;
    }
    if (-height > thickness) {
      store_world(q, last, flags);  // behind it: back to the last visible point, then the BVH
      return;
    }
    // The visible surface faces the camera: a ray arriving at it from behind (or along it)
    // passed through something the screen does not show. The BVH decides.
    float facing = dot(r.dir, hn);
    if (!(facing < -1e-3)) {
      store_world(q, last, flags);
      return;
    }
    // On screen: the hit's material from the G-buffer at that pixel, the distance to the
    // visible surface's plane along the ray (the point lit downstream lies on it).
    uvec2 mat = pv_pack_material(imageLoad(gb_albedo, hp).rgb, imageLoad(gb_emissive, hp).w, vec3(0.0));
    float hit_t = max(dot(hpos.xyz - r.origin, hn) / facing, pv_min_start());
    // ... and only near the point the pixel shows: a pixel straddling a silhouette shows the far
    // surface, whose plane the ray may cross far from it, beyond the near wall it really hit.
    if (distance(r.origin + r.dir * hit_t, hpos.xyz) > 2.0 * max(thickness, 0.02 * hpos.w)) {
      store_world(q, last, flags);
      return;
    }
    // ... and only where the lookups that light it are of the ray's own class. The plane of the
    // pixel's surface runs on past the surface's edge: where a floor meets a wall, the point on
    // the floor's plane may lie inside the wall, past the indoor volume's boundary, and would
    // light the hit with the outdoor probes (extreme-range's closed building: 3.6e3 x the
    // reference). A ray that really leaves its class (through a window) needs the BVH as well.
    if (pv_point_indoor(r.origin + r.dir * hit_t, hn) != indoor) {
      store_world(q, last, flags);
      return;
    }
    imageStore(out_hits, q, uvec4(mat.x, pv_pack_normal16(hn), floatBitsToUint(hit_t), flags | kPvPixelHit | kPvPixelScreen));
    atomicAdd(stats.y, 1u);
    return;
  }
  if (clipped) {
    store_world(q, last, flags);
    return;
  }
  // The whole range stayed in front of the depth buffer: a miss settled on screen, its end lit by
  // the radiance probes of the end's class. Only within the ray's class: a pixel straddling a
  // floor-wall corner shows the floor at its centre, and a point beyond the wall, over the floor's
  // plane, compares as in front (extreme-range: the interior 2.5x the reference from such ends).
  if (pv_point_indoor(r.origin + r.dir * range, vec3(0.0)) != indoor) {
    store_world(q, last, flags);
    return;
  }
  imageStore(out_hits, q, uvec4(0u, 0u, floatBitsToUint(range), flags | kPvPixelScreen));
  atomicAdd(stats.z, 1u);
}
