#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/gow_ragnarok/reflections_rt_cubemap/reflections_rt_cubemap_shared.h"
#include "frame.glsl"
#include "vbuffer_shared.h"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#include "hash.glsl"
#include "bvh.glsl"
#include "lights.glsl"
#include "surface.glsl"
#include "brdf.glsl"
#include "renderer/techniques/gow_ragnarok/include/gow_cubemap.glsl"
layout(constant_id = kReflTraceSpecMode) const uint kMode = 1u;

layout(local_size_x = kReflTraceGroup, local_size_y = kReflTraceGroup) in;
layout(set = 0, binding = kReflTraceBindVbuffer, rg32ui) uniform readonly uimage2D vbuffer;
layout(set = 0, binding = kReflTraceBindPosition, rgba32f) uniform readonly image2D gb_position;
layout(set = 0, binding = kReflTraceBindNormal, rgba16f) uniform readonly image2D gb_normal;
layout(set = 0, binding = kReflTraceBindAlbedo, rgba16f) uniform readonly image2D gb_albedo;
layout(set = 0, binding = kReflTraceBindScreen, rgba32f) uniform readonly image2D screen;
layout(set = 0, binding = kReflTraceBindCubemap, rgba32f) uniform readonly image2D cubemap;
layout(set = 0, binding = kReflTraceBindOut, rgba32f) uniform writeonly image2D out_trace;
layout(std430, set = 0, binding = kReflTraceBindStats) buffer Stats { uint stats[]; };
layout(push_constant) uniform Push { ReflTracePush push; };

const float kFar = 3.4e38;
const float kMinT = 0.02;  // m: a screen hit nearer than this is the pixel's own surface

vec3 cubemap_radiance(vec3 d) {
  vec4 s = imageLoad(cubemap, gow_cube_texel(d, push.cubemap_size));
  return s.a > 0.0 ? s.rgb / s.a : vec3(0.0);
}

// Clip x, y, w of a world point, camera-relative (the camera's own clip x, y, w are 0).
vec3 clip_xyw(vec3 p) { return (gib_frame.view_proj * vec4(p - gib_frame.camera_pos.xyz, 0.0)).xyw; }

// The pixel showing world point x, if x is on screen and the G-buffer there shows it (not
// something in front of it).
bool on_screen(vec3 x, out ivec2 pixel) {
  vec3 c = clip_xyw(x);
  if (!(c.z > 1e-4)) return false;
  vec2 size = vec2(gib_render_size());
  vec2 f = (c.xy / c.z * 0.5 + 0.5) * size;
  if (any(lessThan(f, vec2(0.0))) || any(greaterThanEqual(f, size))) return false;
  pixel = ivec2(f);
  vec4 hp = imageLoad(gb_position, pixel);
  return hp.w > 0.0 && distance(hp.xyz, x) < max(0.05, 0.01 * hp.w);
}

// March the ray on screen (uniform steps in screen space) against the G-buffer's distances:
// a hit is a step that lands behind the surface a pixel shows by less than the thickness.
bool screen_trace(vec3 o, vec3 d, out ivec2 pixel) {
  vec3 c0 = clip_xyw(o);
  float t_end = push.distance;
  vec3 cd = clip_xyw(o + d) - c0;
  const float kNearW = 1e-3;
  if (c0.z + cd.z * t_end < kNearW) t_end = max((kNearW - c0.z) / cd.z, 0.0);
  vec3 c1 = c0 + cd * t_end;
  vec2 size = vec2(gib_render_size());
  vec3 cam = gib_frame.camera_pos.xyz;
  for (uint i = 1u; i <= push.ssr_steps; ++i) {
    float u = float(i) / float(push.ssr_steps);
    float inv_w = mix(1.0 / c0.z, 1.0 / c1.z, u);
    float t = mix(0.0, t_end / c1.z, u) / inv_w;
    vec2 f = (mix(c0.xy / c0.z, c1.xy / c1.z, u) * 0.5 + 0.5) * size;
    if (any(lessThan(f, vec2(0.0))) || any(greaterThanEqual(f, size))) return false;
    if (t < kMinT) continue;
    ivec2 hp = ivec2(f);
    vec4 hpos = imageLoad(gb_position, hp);
    if (hpos.w == 0.0) continue;  // the sky: nothing in front of it
    float behind = distance(o + d * t, cam) - hpos.w;
    if (behind < 0.0) continue;
    if (behind > push.ssr_thickness) return false;  // passed behind something: the BVH decides
    pixel = hp;
    return true;
  }
  return false;
}

void main() {
  ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(q, imageSize(out_trace)))) return;
  ivec2 full = ivec2(gib_render_size());
  // The 2x2 block's pixel traced this frame rotates, so the resolve sees all four over 4 frames.
  ivec2 p = min(2 * q + ivec2(push.frame & 1u, (push.frame >> 1u) & 1u), full - 1);
  vec4 pos = imageLoad(gb_position, p);
  uint tri = imageLoad(vbuffer, p).x;
  if (pos.w == 0.0 || tri == kVisibilityNone) {
    imageStore(out_trace, q, vec4(0.0));
    return;
  }
  GpuMaterial m = gib_materials[gib_instances[gib_triangles[tri - 1u].instance].material];
  if (m.brdf != GIB_BRDF_GLOSSY) {
    imageStore(out_trace, q, vec4(0.0));
    return;
  }
  atomicAdd(stats[kReflStatSamples], 1u);
  vec3 n = normalize(imageLoad(gb_normal, p).xyz);
  vec3 albedo = imageLoad(gb_albedo, p).rgb;
  vec3 wo = normalize(gib_frame.camera_pos.xyz - pos.xyz);
  float nv = dot(n, wo);
  GibRng rng = gib_rng(gib_seed(), push.frame, uvec2(p), 29u);
  float a = gib_ggx_alpha(m.roughness);
  vec3 wi = reflect(-wo, gib_ggx_sample_vndf(n, wo, a, gib_next2(rng)));
  float nl = dot(n, wi);
  if (!(nv > 0.0 && nl > 0.0)) {
    atomicAdd(stats[kReflStatMasked], 1u);
    imageStore(out_trace, q, vec4(0.0, 0.0, 0.0, 1.0));
    return;
  }
  // f cos / pdf of the visible-normal sample: F D V nl / (G1 D / (4 nv)) = F V 4 nl nv / G1.
  vec3 weight = gib_schlick(gib_glossy_f0(albedo, m.metalness), nv) * (gib_ggx_v(a, nl, nv) * 4.0 * nl * nv / gib_ggx_g1(a, nv));
  GpuBvhNode root = gib_bvh_nodes[0];
  vec3 capture = 0.5 * (root.bmin + root.bmax);
  vec3 o = gib_offset_ray(pos.xyz, n);
  vec3 colour;
  ivec2 hp;
  if (kMode == 0u) {
    colour = cubemap_radiance(gow_box_project(pos.xyz, wi, root.bmin, root.bmax, capture));
    atomicAdd(stats[kReflStatCubemap], 1u);
  } else if (screen_trace(o, wi, hp)) {
    colour = imageLoad(screen, hp).rgb;
    atomicAdd(stats[kReflStatScreen], 1u);
  } else {
    GibHit hit;
    if (trace_closest(o, wi, 0.0, kFar, hit)) {
      vec3 x = o + wi * hit.t;
      if (on_screen(x, hp)) {
        colour = imageLoad(screen, hp).rgb;
        atomicAdd(stats[kReflStatBvhScreen], 1u);
      } else {
        colour = cubemap_radiance(x - capture);
        atomicAdd(stats[kReflStatCubemap], 1u);
      }
    } else {
      colour = gib_sky_radiance(wi);
      atomicAdd(stats[kReflStatSky], 1u);
    }
  }
  imageStore(out_trace, q, vec4(weight * colour, 1.0));
}
