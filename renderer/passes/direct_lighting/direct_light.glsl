// Direct light at one G-buffer pixel: what direct_lighting.comp writes per pixel, shared with
// every pass that shades the same G-buffer (the deferred technique's deferred_lighting, whose
// classified and uber dispatches must agree with this to float precision).
//
// The includer declares, before including this file: the scene buffers (GIB_SCENE_BUFFERS),
// frame.glsl, hash.glsl, material.glsl, bvh_alpha.glsl, lights.glsl, surface.glsl, finite.glsl,
// brdf.glsl;
// the G-buffer images gb_albedo, gb_normal, gb_position, gb_emissive (rgba16f / rgba32f as in
// gbuffer_shared.h) and the visibility buffer `vbuffer`; booleans kHasSun, kHasSky, kHasLocal,
// kHasEmissive (specialization constants: which lights the scene has), kSkyUnoccluded (the
// shadow_mapped mode, DirectLightingParams: the sky's light arrives along the same cosine
// directions, unoccluded, without a ray; emissive surfaces are not sampled). Optionally
// GIB_SUN_VISIBILITY(p): the sun's visibility at pixel p, replacing the sun's shadow ray.
//
// gib_direct_light(p, sky_rays, nan_guards, translucent_path, cloth_path):
//   translucent_path false skips the back-face terms; it gives the same value wherever the
//   pixel's translucency is 0 (no random number is drawn for them either), so a permutation
//   compiled without it agrees bit for bit on opaque pixels. cloth_path false skips the sheen
//   lobe of the cloth BRDF class (G-buffer: sheen in gb_albedo.a, roughness in gb_normal.a);
//   likewise the same value wherever the pixel's sheen is 0.
// The overload with `out float sky_hits` also returns the fraction of the pixel's sky rays that
// met a surface (0 where it traced none: sky pixels, sky_rays 0, no sky or emitter in the
// scene, the shadow_mapped mode's unoccluded sky). A GI technique that adds bounce light to this
// pixel gathers it from those directions only: the rays that escaped have counted the sky there.
#ifndef GIB_DIRECT_LIGHT_GLSL
#define GIB_DIRECT_LIGHT_GLSL
#include "brdf.glsl"

const float kShadowMax = 3.4e38;

// Lambertian response to light arriving from wi with irradiance-like weight e at a point
// with normal n: reflected on the front, transmitted (scaled by translucency) from the back.
vec3 diffuse_response(vec3 albedo, float translucency, vec3 n, vec3 wi) {
  float c = dot(n, wi);
  return c > 0.0 ? albedo * (1.0 - translucency) * c / GIB_PI : albedo * translucency * (-c) / GIB_PI;
}

vec3 gib_direct_light(ivec2 p, uint sky_rays, bool nan_guards, bool translucent_path, bool cloth_path,
                      out float sky_hits) {
  sky_hits = 0.0;
  vec4 pos = imageLoad(gb_position, p);
  if (pos.w == 0.0) {
    vec3 o, d;
    gib_camera_ray(vec2(p) + 0.5, o, d);
    return gib_sky_radiance(d);
  }
  vec4 albedo_sheen = imageLoad(gb_albedo, p);
  vec3 albedo = albedo_sheen.rgb;
  vec4 normal_rough = imageLoad(gb_normal, p);
  vec3 n = normal_rough.xyz;
  // Cloth: the sheen lobe needs the direction towards the camera.
  float sheen = cloth_path ? albedo_sheen.a : 0.0;
  vec3 wo = vec3(0.0);
  if (sheen > 0.0) {
    vec3 o, d;
    gib_camera_ray(vec2(p) + 0.5, o, d);
    wo = -d;
  }
  if (nan_guards && !(gib_finite(n) && dot(n, n) > 0.25)) {
    // Guard: a broken normal (NaN texel in the G-buffer) is lit as if facing the camera, so the
    // pixel stays finite; the G-buffer is rewritten every frame, so nothing carries it over.
    vec3 o, d;
    gib_camera_ray(vec2(p) + 0.5, o, d);
    n = -d;
  }
  vec4 em = imageLoad(gb_emissive, p);
  float translucency = translucent_path ? em.w : 0.0;
  vec3 x = pos.xyz;
  GibRng rng = gib_rng(gib_seed(), gib_frame_index(), uvec2(p), 1u);
  vec3 result = em.rgb;

  if (kHasSun && gib_frame.sun_irradiance.w > 0.0) {
#ifdef GIB_SUN_VISIBILITY
    // The sun's visibility from a shadow pass of the technique: light from the sun's centre, scaled.
    vec3 wi = gib_frame.sun_dir.xyz;
    // The traced mode's cone sample, drawn and dropped, so that the sky directions below are
    // the traced mode's: the two modes then differ only in what occludes (the agreement test).
    if (kSkyUnoccluded) gib_next2(rng);
#else
    vec3 wi = gib_uniform_cone(gib_frame.sun_dir.xyz, gib_frame.sun_dir.w, gib_next2(rng));
#endif
    vec3 resp = diffuse_response(albedo, translucency, n, wi);
    if (sheen > 0.0) resp += gib_sheen_lobe(sheen, normal_rough.a, n, wi, wo) * max(dot(n, wi), 0.0);
#ifdef GIB_SUN_VISIBILITY
    result += resp * gib_frame.sun_irradiance.rgb * clamp(GIB_SUN_VISIBILITY(p), 0.0, 1.0);
#else
    if (any(greaterThan(resp, vec3(0.0)))) {
      vec3 side = dot(n, wi) > 0.0 ? n : -n;
      if (!trace_any(gib_offset_ray(x, side), wi, 0.0, kShadowMax)) result += resp * gib_frame.sun_irradiance.rgb;
    }
#endif
  }
  if ((kSkyUnoccluded ? kHasSky : (kHasSky || kHasEmissive)) && sky_rays > 0u) {
    // Cosine-distributed rays: each carries albedo * the radiance it finds straight away, the
    // sky's where it escapes, an emissive surface's emission where it hits one (light that
    // reaches this surface with no further bounce: direct, by the AOV contract). shadow_mapped
    // (kSkyUnoccluded): the sky seen unoccluded along the same directions, no ray, no emission.
    // The rays leave as the reference's path continuation does (path_trace.comp): a direction
    // below the face (the interpolated normal leans past it on curved meshes) is mirrored back
    // across the face plane, and the origin is offset along the face normal, so no ray starts
    // inside the mesh and loses its light to a self-hit.
    vec3 ng = n;
    uint ids = imageLoad(vbuffer, p).x;
    if (ids != kVisibilityNone) {
      vec3 o, d;
      gib_camera_ray(vec2(p) + 0.5, o, d);
      ng = gib_face_normal_facing(ids - 1u, d, n);
    }
    vec3 sky = vec3(0.0), sheen_sky = vec3(0.0);
    uint hits = 0u;
    for (uint i = 0u; i < sky_rays; ++i) {
      bool back = translucency > 0.0 && gib_next(rng) < translucency;
      vec3 side = back ? -n : n, side_g = back ? -ng : ng;
      vec3 wi = gib_above_face(gib_cosine_hemisphere(side, gib_next2(rng)), side_g);
      vec3 found = vec3(0.0);
      if (kSkyUnoccluded) {
        found = gib_sky_radiance(wi);
      } else if (kHasEmissive) {
        GibHit hit;
        if (!trace_closest(gib_offset_ray(x, side_g), wi, 0.0, kShadowMax, hit)) {
          found = kHasSky ? gib_sky_radiance(wi) : vec3(0.0);
        } else {
          GibSurface s = gib_surface(hit.triangle, hit.u, hit.v, nan_guards);
          found = gib_material_emissive(gib_materials[s.material], s.uv);
          ++hits;
        }
      } else if (!trace_any(gib_offset_ray(x, side_g), wi, 0.0, kShadowMax)) {
        found = gib_sky_radiance(wi);
      } else {
        ++hits;
      }
      sky += found;
      // Cosine-sampled: a ray's weight for the lobe is pi x lobe (cloth has no back side).
      if (sheen > 0.0) sheen_sky += GIB_PI * gib_sheen_lobe(sheen, normal_rough.a, n, wi, wo) * found;
    }
    result += albedo * sky / float(sky_rays);
    if (sheen > 0.0) result += sheen_sky / float(sky_rays);
    sky_hits = float(hits) / float(sky_rays);
  }
  if (kHasLocal) {
    for (uint i = 0u; i < gib_light_count(); ++i) {
      vec3 wi;
      float dist;
      vec3 e = gib_local_light(gib_lights[i], x, wi, dist);
      if (all(equal(e, vec3(0.0)))) continue;
      vec3 resp = diffuse_response(albedo, translucency, n, wi);
      if (sheen > 0.0) resp += gib_sheen_lobe(sheen, normal_rough.a, n, wi, wo) * max(dot(n, wi), 0.0);
      if (all(equal(resp, vec3(0.0)))) continue;
      vec3 side = dot(n, wi) > 0.0 ? n : -n;
      if (!trace_any(gib_offset_ray(x, side), wi, 0.0, dist * 0.999)) result += resp * e;
    }
  }
  return result;
}

vec3 gib_direct_light(ivec2 p, uint sky_rays, bool nan_guards, bool translucent_path, bool cloth_path) {
  float sky_hits;
  return gib_direct_light(p, sky_rays, nan_guards, translucent_path, cloth_path, sky_hits);
}

#endif
