#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/passes/gbuffer/gbuffer_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#include "hash.glsl"
#include "material.glsl"
#include "surface.glsl"
#include "finite.glsl"
#include "decals.glsl"

layout(local_size_x = kGbufferGroup, local_size_y = kGbufferGroup) in;
layout(set = 0, binding = kGbufferBindVbuffer, rg32ui) uniform readonly uimage2D vbuffer;
layout(set = 0, binding = kGbufferBindAlbedo, rgba16f) uniform writeonly image2D out_albedo;
layout(set = 0, binding = kGbufferBindNormal, rgba16f) uniform writeonly image2D out_normal;
layout(set = 0, binding = kGbufferBindPosition, rgba32f) uniform writeonly image2D out_position;
layout(set = 0, binding = kGbufferBindEmissive, rgba16f) uniform writeonly image2D out_emissive;
layout(push_constant) uniform Push { GbufferPush push; };

// Barycentrics (of b and c) where the ray meets the triangle's plane; not clipped to the
// triangle, so neighbouring-pixel rays give derivatives even across its edges.
vec2 plane_barycentrics(vec3 o, vec3 d, vec3 a, vec3 b, vec3 c) {
  vec3 e1 = b - a, e2 = c - a;
  vec3 pv = cross(d, e2);
  float det = dot(e1, pv);
  if (abs(det) < 1e-30) return vec2(0.0);
  float inv = 1.0 / det;
  vec3 tv = o - a;
  vec3 qv = cross(tv, e1);
  return vec2(dot(tv, pv) * inv, dot(d, qv) * inv);
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(vbuffer)))) return;
  uvec2 ids = imageLoad(vbuffer, p).xy;
  bool inject = push.inject_nan != 0u && all(equal(uvec2(p), uvec2(push.inject_x, push.inject_y)));
  if (ids.x == kVisibilityNone) {
    imageStore(out_albedo, p, vec4(0.0));
    imageStore(out_normal, p, inject ? vec4(gib_nan()) : vec4(0.0));
    imageStore(out_position, p, vec4(0.0));
    imageStore(out_emissive, p, vec4(0.0));
    return;
  }
  uint tri = ids.x - 1u;
  GpuTriangle t = gib_triangles[tri];
  vec3 a = gib_vertices[t.i0].position, b = gib_vertices[t.i1].position, c = gib_vertices[t.i2].position;
  vec3 o, d, dx, dy;
  gib_camera_ray(vec2(p) + 0.5, o, d);
  gib_camera_ray(vec2(p) + vec2(1.5, 0.5), o, dx);
  gib_camera_ray(vec2(p) + vec2(0.5, 1.5), o, dy);
  vec2 bc = plane_barycentrics(o, d, a, b, c);
  vec2 bcx = plane_barycentrics(o, dx, a, b, c) - bc;
  vec2 bcy = plane_barycentrics(o, dy, a, b, c) - bc;
  GibSurface s = gib_surface(tri, bc.x, bc.y, push.nan_guards != 0u);
  vec2 uva = vec2(gib_vertices[t.i0].u, gib_vertices[t.i0].v);
  vec2 uvb = vec2(gib_vertices[t.i1].u, gib_vertices[t.i1].v);
  vec2 uvc = vec2(gib_vertices[t.i2].u, gib_vertices[t.i2].v);
  vec2 duv_dx = (uvb - uva) * bcx.x + (uvc - uva) * bcx.y;
  vec2 duv_dy = (uvb - uva) * bcy.x + (uvc - uva) * bcy.y;
  GpuMaterial m = gib_materials[s.material];
  vec3 albedo = gib_material_albedo_filtered(m, s.uv, duv_dx, duv_dy);
  // Shading normal faces the camera: surfaces are double-sided.
  vec3 n = dot(s.normal, d) > 0.0 ? -s.normal : s.normal;
  // Guard: gib_surface already replaces a zero or NaN interpolated normal by the face normal;
  // an infinite or overflowing vertex normal still gives a non-unit or NaN one here.
  if (push.nan_guards != 0u && !(gib_finite(n) && abs(dot(n, n) - 1.0) < 0.01))
    n = dot(s.geo_normal, d) > 0.0 ? -s.geo_normal : s.geo_normal;
  if (inject) n = vec3(gib_nan());
  // Projected decals recolour the albedo here (the deferred technique does it in its own
  // gbuffer_update pass); no decals: the loop does not run.
  albedo = gib_decal_blend(albedo, gib_decals_at(s.position, n));
  imageStore(out_albedo, p, vec4(albedo, m.sheen));
  imageStore(out_normal, p, vec4(n, m.roughness));
  imageStore(out_position, p, vec4(s.position, distance(s.position, o)));
  imageStore(out_emissive, p, vec4(gib_material_emissive_filtered(m, s.uv, duv_dx, duv_dy), m.translucency));
}
