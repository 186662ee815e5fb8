#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/reference/path_trace/path_trace_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#include "hash.glsl"
#include "material.glsl"
layout(constant_id = kPathTraceSpecSun) const bool kHasSun = true;
layout(constant_id = kPathTraceSpecLocal) const bool kHasLocal = true;
layout(constant_id = kPathTraceSpecAlpha) const bool kHasAlpha = true;
// Stochastic opacity needs a fresh decision per ray; alpha masks ignore the seed.
uint g_alpha_seed = 0u;
#define GIB_ALPHA_TEST
#include "alpha_strategy.glsl"
bool gib_alpha_accept(uint triangle, float u, float v, inout uint calls, uint ray_key) {
  return !kHasAlpha || gib_alpha_strategy_accept(triangle, u, v, calls, ray_key, gib_pcg(g_alpha_seed ^ triangle),
                                                 gib_frame.alpha_info.x, gib_frame.alpha_info.y);
}
#include "bvh.glsl"
#include "lights.glsl"
#include "surface.glsl"
#include "finite.glsl"
#include "brdf.glsl"
#include "decals.glsl"

layout(local_size_x = kPathTraceGroup, local_size_y = kPathTraceGroup) in;
layout(set = 0, binding = kPathTraceBindRadiance, rgba32f) uniform image2D sum_radiance;
layout(set = 0, binding = kPathTraceBindDirect, rgba32f) uniform image2D sum_direct;
layout(set = 0, binding = kPathTraceBindIndirect, rgba32f) uniform image2D sum_indirect;
layout(set = 0, binding = kPathTraceBindReflection, rgba32f) uniform image2D sum_reflection;
layout(push_constant) uniform Push { PathTracePush push; };

const float kFar = 3.4e38;

bool shadow(vec3 o, vec3 d, float tmax, inout GibRng rng) {
  g_alpha_seed = uint(gib_next(rng) * 16777216.0);
  return trace_any(o, d, 0.0, tmax);
}

// The glossy lobes at a vertex; push.glossy_masking 0 drops the specular lobe's masking (G = 1:
// V = 1 / (4 nl nv)), the negative control of the glossy furnace.
void glossy_eval(vec3 n, vec3 wo, vec3 wi, vec3 albedo, float roughness, float metalness, out vec3 fs, out vec3 fd) {
  gib_glossy_eval(n, wo, wi, albedo, roughness, metalness, fs, fd);
  if (push.glossy_masking == 0u && any(greaterThan(fs, vec3(0.0)))) {
    float a = gib_ggx_alpha(roughness), nl = dot(n, wi), nv = dot(n, wo);
    fs /= gib_ggx_v(a, nl, nv) * 4.0 * nl * nv;
  }
}

// Next-event estimation at a glossy surface (brdf.glsl's glossy class, front side only).
vec3 light_direct_glossy(vec3 x, vec3 n, vec3 albedo, float roughness, float metalness, vec3 wo, inout GibRng rng) {
  vec3 sum = vec3(0.0);
  vec3 fs, fd;
  if (kHasSun && gib_frame.sun_irradiance.w > 0.0) {
    vec3 wi = gib_uniform_cone(gib_frame.sun_dir.xyz, gib_frame.sun_dir.w, gib_next2(rng));
    float c = dot(n, wi);
    glossy_eval(n, wo, wi, albedo, roughness, metalness, fs, fd);
    if (c > 0.0 && !shadow(gib_offset_ray(x, n), wi, kFar, rng)) sum += (fs + fd) * c * gib_frame.sun_irradiance.rgb;
  }
  if (kHasLocal) {
    for (uint i = 0u; i < gib_light_count(); ++i) {
      vec3 wi;
      float dist;
      vec3 e = gib_local_light(gib_lights[i], x, wi, dist);
      float c = dot(n, wi);
      if (c <= 0.0 || all(equal(e, vec3(0.0)))) continue;
      glossy_eval(n, wo, wi, albedo, roughness, metalness, fs, fd);
      if (!shadow(gib_offset_ray(x, n), wi, dist * 0.999, rng)) sum += (fs + fd) * c * e;
    }
  }
  return sum;
}

// Next-event estimation at x towards the sun and every local light. sheen > 0: the cloth class's
// sheen lobe (brdf.glsl) seen from wo joins the Lambertian front response.
vec3 light_direct(vec3 x, vec3 n, vec3 albedo, float translucency, float sheen, float roughness, vec3 wo,
                  inout GibRng rng) {
  vec3 sum = vec3(0.0);
  if (kHasSun && gib_frame.sun_irradiance.w > 0.0) {
    vec3 wi = gib_uniform_cone(gib_frame.sun_dir.xyz, gib_frame.sun_dir.w, gib_next2(rng));
    float c = dot(n, wi);
    float f = c > 0.0 ? (1.0 - translucency) * c : translucency * (-c);
    float lobe = sheen > 0.0 ? gib_sheen_lobe(sheen, roughness, n, wi, wo) * max(c, 0.0) : 0.0;
    if ((f > 0.0 || lobe > 0.0) && !shadow(gib_offset_ray(x, c > 0.0 ? n : -n), wi, kFar, rng)) {
      sum += albedo / GIB_PI * f * gib_frame.sun_irradiance.rgb;
      if (sheen > 0.0) sum += lobe * gib_frame.sun_irradiance.rgb;
    }
  }
  if (kHasLocal) {
    for (uint i = 0u; i < gib_light_count(); ++i) {
      vec3 wi;
      float dist;
      vec3 e = gib_local_light(gib_lights[i], x, wi, dist);
      float c = dot(n, wi);
      float f = c > 0.0 ? (1.0 - translucency) * c : translucency * (-c);
      float lobe = sheen > 0.0 ? gib_sheen_lobe(sheen, roughness, n, wi, wo) * max(c, 0.0) : 0.0;
      if ((f <= 0.0 && lobe <= 0.0) || all(equal(e, vec3(0.0)))) continue;
      if (!shadow(gib_offset_ray(x, c > 0.0 ? n : -n), wi, dist * 0.999, rng)) {
        sum += albedo / GIB_PI * f * e;
        if (sheen > 0.0) sum += lobe * e;
      }
    }
  }
  return sum;
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(sum_radiance)))) return;
  vec3 acc_radiance = vec3(0.0), acc_direct = vec3(0.0), acc_indirect = vec3(0.0), acc_reflection = vec3(0.0);
  bool inject = push.inject_nan != 0u && all(equal(uvec2(p), uvec2(push.inject_x, push.inject_y)));
  uint accepted = 0u;
  for (uint s = 0u; s < push.spp; ++s) {
    GibRng rng = gib_rng(gib_seed(), push.sample_base + s, uvec2(p), 7u);
    vec3 o, d;
    gib_camera_ray(vec2(p) + gib_next2(rng), o, d);
    vec3 throughput = vec3(1.0);
    // The part of throughput that left the first hit through its specular lobe (the reflection
    // AOV: what that lobe reflects of everything its rays see; 0 unless the first hit is glossy).
    vec3 throughput_refl = vec3(0.0);
    vec3 direct = vec3(0.0), indirect = vec3(0.0), reflection = vec3(0.0);
    for (uint depth = 0u; depth <= push.max_bounces; ++depth) {
      // Light that reaches the first hit straight from a source is direct; the rest indirect.
      bool primary = depth <= 1u;
      GibHit hit;
      g_alpha_seed = uint(gib_next(rng) * 16777216.0);
      if (!trace_closest(o, d, 0.0, kFar, hit)) {
        vec3 sky = gib_sky_radiance(d);
        vec3 l = throughput * sky;
        if (primary) direct += l; else indirect += l;
        reflection += throughput_refl * sky;
        break;
      }
      GibSurface surf = gib_surface(hit.triangle, hit.u, hit.v, push.nan_guards != 0u);
      GpuMaterial m = gib_materials[surf.material];
      vec3 n = dot(surf.normal, d) > 0.0 ? -surf.normal : surf.normal;
      vec3 albedo = gib_decal_blend(gib_material_albedo(m, surf.uv), gib_decals_at(surf.position, n));
      vec3 wo = -d;
      vec3 ng = dot(surf.geo_normal, d) > 0.0 ? -surf.geo_normal : surf.geo_normal;
      vec3 emitted = gib_material_emissive(m, surf.uv);
      vec3 e = throughput * emitted;
      if (primary) direct += e; else indirect += e;
      reflection += throughput_refl * emitted;
      if (depth == push.max_bounces) break;
      if (m.brdf == GIB_BRDF_GLOSSY) {
        // Glossy: NEE with both lobes, then one sample of the lobe mixture weighted by the
        // mixture's density (one-sample MIS, balance heuristic): f cos / pdf per lobe.
        vec3 ld = light_direct_glossy(surf.position, n, albedo, m.roughness, m.metalness, wo, rng);
        if (depth == 0u) direct += throughput * ld; else indirect += throughput * ld;
        reflection += throughput_refl * ld;
        float p_spec = gib_glossy_spec_probability(n, wo, albedo, m.metalness);
        vec2 u = gib_next2(rng);
        d = gib_glossy_sample(n, wo, m.roughness, p_spec, u, gib_next(rng));
        float pdf = gib_glossy_pdf(n, wo, d, m.roughness, p_spec);
        vec3 fs, fd;
        glossy_eval(n, wo, d, albedo, m.roughness, m.metalness, fs, fd);
        float c = dot(n, d);
        if (!(pdf > 0.0 && c > 0.0)) break;  // below the surface: masked, the lobe's loss
        vec3 w_spec = fs * (c / pdf), w = (fs + fd) * (c / pdf);
        float below = dot(d, ng);
        if (below <= 0.0) d = normalize(d - 2.0 * below * ng);
        o = gib_offset_ray(surf.position, ng);
        throughput_refl = depth == 0u ? w_spec : throughput_refl * w;
        throughput *= w;
        if (depth >= 3u) {
          float survive = min(max(throughput.r, max(throughput.g, throughput.b)), 1.0);
          if (gib_next(rng) >= survive) break;
          throughput /= survive;
          throughput_refl /= survive;
        }
        continue;
      }
      vec3 ld = light_direct(surf.position, n, albedo, m.translucency, m.sheen, m.roughness, wo, rng);
      vec3 nee = throughput * ld;
      if (depth == 0u) direct += nee; else indirect += nee;
      reflection += throughput_refl * ld;
      // Continue: reflect, or transmit to the back side with probability = translucency.
      bool transmit = m.translucency > 0.0 && gib_next(rng) < m.translucency;
      vec3 side = transmit ? -n : n;
      vec3 side_g = transmit ? -ng : ng;
      d = gib_cosine_hemisphere(side, gib_next2(rng));
      // An interpolated normal can send the ray below the real surface: mirror it back across
      // the face plane rather than kill the path, so albedo-1 scenes keep all their energy.
      float below = dot(d, side_g);
      if (below <= 0.0) d = normalize(d - 2.0 * below * side_g);
      o = gib_offset_ray(surf.position, side_g);
      // Cosine-sampled continuation: weight pi x BRDF (the cloth's lobe on the front only).
      vec3 w = m.sheen > 0.0 ? albedo + GIB_PI * gib_sheen_lobe(m.sheen, m.roughness, n, d, wo) : albedo;
      throughput *= w;
      throughput_refl *= w;
      if (depth >= 3u) {
        float survive = min(max(throughput.r, max(throughput.g, throughput.b)), 1.0);
        if (gib_next(rng) >= survive) break;
        throughput /= survive;
        throughput_refl /= survive;
      }
    }
    if (inject && s == 0u) direct = indirect = reflection = vec3(gib_nan());
    // Guard: one non-finite sample would poison the running sums for good; drop it (the count
    // then holds only the samples added).
    if (push.nan_guards != 0u && !(gib_finite(direct) && gib_finite(indirect) && gib_finite(reflection))) continue;
    acc_radiance += direct + indirect;
    acc_direct += direct;
    acc_indirect += indirect;
    acc_reflection += reflection;
    ++accepted;
  }
  float n = float(accepted);
  imageStore(sum_radiance, p, imageLoad(sum_radiance, p) + vec4(acc_radiance, n));
  imageStore(sum_direct, p, imageLoad(sum_direct, p) + vec4(acc_direct, n));
  imageStore(sum_indirect, p, imageLoad(sum_indirect, p) + vec4(acc_indirect, n));
  imageStore(sum_reflection, p, imageLoad(sum_reflection, p) + vec4(acc_reflection, n));
}
