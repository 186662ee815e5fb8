#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/gow_ragnarok/cubemap_capture/cubemap_capture_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#include "hash.glsl"
#include "material.glsl"
#include "bvh.glsl"
#include "lights.glsl"
#include "surface.glsl"
#include "finite.glsl"
#include "renderer/techniques/gow_ragnarok/include/gow_cubemap.glsl"
layout(constant_id = 0) const bool kHasSun = true;
layout(constant_id = 1) const bool kHasLocal = true;

layout(local_size_x = kCubemapCaptureGroup, local_size_y = kCubemapCaptureGroup) in;
layout(set = 0, binding = kCubemapCaptureBindSum, rgba32f) uniform image2D sum_image;
layout(push_constant) uniform Push { CubemapCapturePush push; };

const float kFar = 3.4e38;

// Sun and local lights at a Lambertian point, with shadow rays.
vec3 lights_at(vec3 x, vec3 n, vec3 albedo, inout GibRng rng) {
  vec3 sum = vec3(0.0);
  if (kHasSun && gib_frame.sun_irradiance.w > 0.0) {
    vec3 wi = gib_uniform_cone(gib_frame.sun_dir.xyz, gib_frame.sun_dir.w, gib_next2(rng));
    float c = dot(n, wi);
    if (c > 0.0 && !trace_any(gib_offset_ray(x, n), wi, 0.0, kFar)) sum += c * gib_frame.sun_irradiance.rgb;
  }
  if (kHasLocal) {
    for (uint i = 0u; i < gib_light_count(); ++i) {
      vec3 wi;
      float dist;
      vec3 e = gib_local_light(gib_lights[i], x, wi, dist);
      float c = dot(n, wi);
      if (c > 0.0 && !trace_any(gib_offset_ray(x, n), wi, 0.0, dist * 0.999)) sum += c * e;
    }
  }
  return sum * albedo / GIB_PI;
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  uint n = push.size;
  if (p.x >= int(6u * n) || p.y >= int(n)) return;
  GpuBvhNode root = gib_bvh_nodes[0];
  vec3 o = 0.5 * (root.bmin + root.bmax);
  GibRng rng = gib_rng(gib_seed(), push.frame, uvec2(p), 23u);
  uint face = uint(p.x) / n;
  vec2 st = (vec2(float(uint(p.x) - face * n), float(p.y)) + gib_next2(rng)) / float(n) * 2.0 - 1.0;
  vec3 d = normalize(gow_cube_dir(face, st));
  vec3 throughput = vec3(1.0), radiance = vec3(0.0);
  for (uint depth = 0u; depth <= push.bounces; ++depth) {
    GibHit hit;
    if (!trace_closest(o, d, 0.0, kFar, hit)) {
      radiance += throughput * gib_sky_radiance(d);
      break;
    }
    GibSurface s = gib_surface(hit.triangle, hit.u, hit.v, push.nan_guards != 0u);
    GpuMaterial m = gib_materials[s.material];
    vec3 nrm = dot(s.normal, d) > 0.0 ? -s.normal : s.normal;
    vec3 ng = dot(s.geo_normal, d) > 0.0 ? -s.geo_normal : s.geo_normal;
    vec3 albedo = gib_material_albedo(m, s.uv);
    radiance += throughput * gib_material_emissive(m, s.uv);
    if (depth == push.bounces) break;
    radiance += throughput * lights_at(s.position, nrm, albedo, rng);
    d = gib_above_face(gib_cosine_hemisphere(nrm, gib_next2(rng)), ng);
    o = gib_offset_ray(s.position, ng);
    throughput *= albedo;
  }
  vec4 prev = imageLoad(sum_image, p);
  if (push.nan_guards != 0u && !gib_finite(radiance)) radiance = vec3(0.0), prev.a -= 1.0;
  imageStore(sum_image, p, prev + vec4(radiance, 1.0));
}
