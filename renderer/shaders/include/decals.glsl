// Box-projected decals (Scene::decals; the seed's projected decals, blended into the G-buffer):
// what they do to a surface's albedo at world position x with shading normal n. Used by every
// pass that writes or evaluates a surface's albedo for direct light (gbuffer, the deferred
// technique's gbuffer_update, the path tracer). CPU mirror: renderer/scene/material_eval.h
// (decal_weight, decals_at), same formulas and operation order.
//
//   gib_decal_weight(d, x, n)  coverage in [0, 1]: opacity x shape mask (rect: the box's face;
//                              disc: the ellipse inscribed in it) x facing fade (1 where n is
//                              within 60 degrees of the decal's +z, 0 beyond 75.5 degrees)
//   gib_decals_at(x, n)        every decal in scene order reduced to albedo' = albedo * k + c:
//                              returns vec4(c, k), so a coarse (VRCS) cell can share it
//   gib_decal_blend(albedo, kc) applies it
#ifndef GIB_DECALS_GLSL
#define GIB_DECALS_GLSL
#include "frame.glsl"

float gib_decal_weight(GpuDecal d, vec3 x, vec3 n) {
  precise vec3 r = x - d.centre.xyz;
  precise float lx = (d.axis_x.x * r.x + d.axis_x.y * r.y + d.axis_x.z * r.z) * d.axis_x.w;
  precise float ly = (d.axis_y.x * r.x + d.axis_y.y * r.y + d.axis_y.z * r.z) * d.axis_y.w;
  precise float lz = (d.axis_z.x * r.x + d.axis_z.y * r.y + d.axis_z.z * r.z) * d.axis_z.w;
  if (!(abs(lx) <= 0.5 && abs(ly) <= 0.5 && abs(lz) <= 0.5)) return 0.0;
  precise float r2 = lx * lx + ly * ly;
  if (d.centre.w != 0.0 && r2 > 0.25) return 0.0;  // disc
  precise float c = d.axis_z.x * n.x + d.axis_z.y * n.y + d.axis_z.z * n.z;
  precise float fade = clamp((c - 0.25) * 4.0, 0.0, 1.0);
  precise float w = d.albedo.a * fade;
  return w;
}

vec4 gib_decals_at(vec3 x, vec3 n) {
  precise vec3 c = vec3(0.0);
  precise float k = 1.0;
  for (uint i = 0u; i < gib_decal_count(); ++i) {
    GpuDecal d = gib_frame.decals[i];
    float w = gib_decal_weight(d, x, n);
    if (w <= 0.0) continue;
    c = c * (1.0 - w) + d.albedo.rgb * w;
    k = k * (1.0 - w);
  }
  return vec4(c, k);
}

vec3 gib_decal_blend(vec3 albedo, vec4 kc) {
  precise vec3 r = albedo * kc.w + kc.rgb;
  return r;
}

#endif
