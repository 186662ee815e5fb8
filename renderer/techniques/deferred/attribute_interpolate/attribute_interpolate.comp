#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/deferred/attribute_interpolate/attribute_interpolate_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#include "surface.glsl"
#include "finite.glsl"
#include "renderer/techniques/deferred/include/deferred_attributes.glsl"

layout(local_size_x = kAttrGroup, local_size_y = kAttrGroup) in;
layout(set = 0, binding = kAttrBindVbuffer, rg32ui) uniform readonly uimage2D vbuffer;
layout(set = 0, binding = kAttrBindBary, rg16f) uniform writeonly image2D out_bary;
layout(set = 0, binding = kAttrBindBaryDeriv, rgba16ui) uniform writeonly uimage2D out_deriv;
layout(set = 0, binding = kAttrBindTangentFrame, rgba16f) uniform writeonly image2D out_frame;
layout(push_constant) uniform Push { AttrPush push; };

// Barycentrics (of b and c) where the ray meets the triangle's plane; not clipped to the
// triangle, so neighbouring-pixel rays give derivatives across its edges.
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
  if (ids.x == kVisibilityNone) {
    imageStore(out_bary, p, vec4(0.0));
    imageStore(out_deriv, p, uvec4(0u));
    imageStore(out_frame, p, vec4(0.0));
    return;
  }
  uint tri = ids.x - 1u;
  GpuTriangle t = gib_triangles[tri];
  GpuVertex va = gib_vertices[t.i0], vb = gib_vertices[t.i1], vc = gib_vertices[t.i2];
  vec3 o, d, dx, dy;
  gib_camera_ray(vec2(p) + 0.5, o, d);
  gib_camera_ray(vec2(p) + vec2(1.5, 0.5), o, dx);
  gib_camera_ray(vec2(p) + vec2(0.5, 1.5), o, dy);
  vec2 bc = plane_barycentrics(o, d, va.position, vb.position, vc.position);
  vec2 bcx = plane_barycentrics(o, dx, va.position, vb.position, vc.position) - bc;
  vec2 bcy = plane_barycentrics(o, dy, va.position, vb.position, vc.position) - bc;
  GibSurface s = gib_surface(tri, bc.x, bc.y, push.nan_guards != 0u);
  // Shading normal facing the camera (surfaces are double-sided), guarded as the G-buffer pass.
  vec3 n = dot(s.normal, d) > 0.0 ? -s.normal : s.normal;
  if (push.nan_guards != 0u && !(gib_finite(n) && abs(dot(n, n) - 1.0) < 0.01))
    n = dot(s.geo_normal, d) > 0.0 ? -s.geo_normal : s.geo_normal;
  // Tangent: dP/du from the triangle's uv mapping; any vector across n where uvs are degenerate.
  vec3 e1 = vb.position - va.position, e2 = vc.position - va.position;
  vec2 t1 = vec2(vb.u, vb.v) - vec2(va.u, va.v), t2 = vec2(vc.u, vc.v) - vec2(va.u, va.v);
  float det = t1.x * t2.y - t2.x * t1.y;
  vec3 tangent = det != 0.0 ? (e1 * t2.y - e2 * t1.y) / det : vec3(0.0);
  vec3 bitangent = det != 0.0 ? (e2 * t1.x - e1 * t2.x) / det : vec3(0.0);
  tangent -= n * dot(n, tangent);
  if (!(dot(tangent, tangent) > 1e-20) || !gib_finite(tangent))
    tangent = abs(n.x) < 0.9 ? cross(n, vec3(1.0, 0.0, 0.0)) : cross(n, vec3(0.0, 1.0, 0.0));
  tangent = normalize(tangent);
  bool front = dot(s.geo_normal, d) < 0.0;
  bool bitangent_negative = dot(cross(n, tangent), bitangent) < 0.0;
  // Pre-rounded to binary16 (ties to even): the stores then keep exactly these values on every
  // device, whatever its float-to-half rounding (deferred_attributes.glsl).
  imageStore(out_bary, p, vec4(gib_round_to_half(bc), 0.0, 0.0));
  uint deriv_x = gib_pack_bary_deriv2(bcx, front, n.z < 0.0), deriv_y = gib_pack_bary_deriv2(bcy, tangent.z < 0.0, bitangent_negative);
  imageStore(out_deriv, p, uvec4(deriv_x & 0xffffu, deriv_x >> 16, deriv_y & 0xffffu, deriv_y >> 16));
  imageStore(out_frame, p, gib_round_to_half(vec4(n.xy, tangent.xy)));
}
