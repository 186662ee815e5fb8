// pixel_upscale: bilateral upscale of the denoised SH, evaluated with each full-resolution
// pixel's normal (see pixel_upscale.h).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/probe_volume/pixel_upscale/pixel_upscale_shared.h"
#include "frame.glsl"
#include "hash.glsl"
#include "finite.glsl"
#include "sampling.glsl"
#include "ycocg_sh.glsl"
layout(push_constant) uniform Push { PvParams pv; };
#include "renderer/techniques/probe_volume/include/pv_common.glsl"
#include "renderer/techniques/probe_volume/include/pv_pixel.glsl"
layout(set = 0, binding = kPvUpscaleBindPosition, rgba32f) uniform readonly image2D gb_position;
layout(set = 0, binding = kPvUpscaleBindNormal, rgba16f) uniform readonly image2D gb_normal;
layout(set = 0, binding = kPvUpscaleBindEmissive, rgba16f) uniform readonly image2D gb_emissive;
#include "renderer/techniques/probe_volume/include/pv_surface.glsl"
layout(set = 0, binding = kPvUpscaleBindGiY, rgba32f) uniform readonly image2D gi_y;
layout(set = 0, binding = kPvUpscaleBindGiC, rgba32f) uniform readonly image2D gi_c;
layout(set = 0, binding = kPvUpscaleBindIrradiance, rgba32f) uniform writeonly image2D out_irradiance;
layout(set = 0, binding = kPvUpscaleBindDirect, rgba32f) uniform writeonly image2D out_direct;
layout(local_size_x = kPvUpscaleGroup, local_size_y = kPvUpscaleGroup) in;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(out_irradiance);
  if (any(greaterThanEqual(p, size))) return;
  imageStore(out_direct, p, vec4(0.0));
  PvSurface a = pv_surface_at(p);
  if (a.depth == 0.0 || a.normal == vec3(0.0)) {
    imageStore(out_irradiance, p, vec4(0.0));
    return;
  }
  ivec2 qsize = imageSize(gi_y);
  float div = float(pv_divisor());
  vec2 g = (vec2(p) + 0.5) / div - 0.5;
  ivec2 q0 = ivec2(floor(g));
  vec2 f = g - vec2(q0);
  vec3 sum = vec3(0.0);
  float weight = 0.0;
  vec3 fallback = vec3(0.0);
  float fallback_w = 0.0;
  for (int k = 0; k < 4; ++k) {
    ivec2 o = ivec2(k & 1, k >> 1);
    ivec2 q = clamp(q0 + o, ivec2(0), qsize - 1);
    PvSurface b = pv_surface_at(pv_source_pixel(q));
    if (b.depth == 0.0) continue;
    vec2 t = mix(1.0 - f, f, vec2(o));
    // The seed's depth weight 1 / (0.1 + |dz|)^2, with normal and material-class terms.
    float dz = abs(b.depth - a.depth);
    float wd = 1.0 / ((0.1 + dz) * (0.1 + dz));
    float wb = pv_bilateral(a, b);
    vec4 y = imageLoad(gi_y, q);
    vec4 c = imageLoad(gi_c, q);
    vec3 e = pv_eval_irradiance(y.x, y.yzw, c.xy, a.normal, b.normal);
    float w = t.x * t.y * wd * wb;
    sum += w * e;
    weight += w;
    fallback += t.x * t.y * wd * e;
    fallback_w += t.x * t.y * wd;
  }
  // No tap on the same surface (a one-pixel feature): the depth-weighted taps.
  vec3 e = weight > 0.0 ? sum / weight : (fallback_w > 0.0 ? fallback / fallback_w : vec3(0.0));
  if (pv_flag(kPvFlagNanGuards) && !gib_finite(e)) e = vec3(0.0);
  imageStore(out_irradiance, p, vec4(e / GIB_PI, 0.0));
}
