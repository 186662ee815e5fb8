// Surface attributes at a hit (triangle + barycentrics), and self-intersection-safe ray origins.
// Requires scene.glsl's buffers (GIB_SCENE_BUFFERS) to be declared first.
//
// Shading normal: the interpolated vertex normal, normalised, bent by the material's normal map
// where it has one (normal_map.glsl). A zero one (a mesh without normals,
// zero input normals) means "none": the face normal is used. A non-finite one (a NaN vertex
// normal reaches every pixel of its triangles, since NaN * 0 is NaN) is the NaN guard's case:
// every pass that interpolates normals calls gib_surface(tri, u, v, nan_guard) with its
// Settings::nan_guards flag; with the guard the face normal is used, without it the NaN goes on
// (the negative control of the degenerate-geometry case). The tests are on the float's bits
// (finite.glsl), so no compiler can fold them away.
#ifndef GIB_SURFACE_GLSL
#define GIB_SURFACE_GLSL
#include "finite.glsl"
#include "normal_map.glsl"
#include "textures.glsl"

struct GibSurface {
  vec3 position;
  vec3 normal;      // interpolated shading normal (unit; geo_normal when zero, or non-finite under the guard)
  vec3 geo_normal;  // unit face normal (arbitrary side; +Y for a zero-area triangle)
  vec2 uv;
  uint material;
  uint instance;
};

GibSurface gib_surface(uint tri, float u, float v, bool nan_guard) {
  GpuTriangle t = gib_triangles[tri];
  GpuVertex a = gib_vertices[t.i0], b = gib_vertices[t.i1], c = gib_vertices[t.i2];
  float w = 1.0 - u - v;
  GibSurface s;
  s.position = a.position * w + b.position * u + c.position * v;
  vec3 g = cross(b.position - a.position, c.position - a.position);
  float gl = length(g);
  s.geo_normal = gl > 0.0 ? g / gl : vec3(0.0, 1.0, 0.0);
  vec3 n = a.normal * w + b.normal * u + c.normal * v;
  float nl = length(n);
  if (!(gib_finite(n) && gib_finite(nl)))
    s.normal = nan_guard ? s.geo_normal : n / nl;
  else
    s.normal = nl > 1e-12 ? n / nl : s.geo_normal;
  s.uv = vec2(a.u, a.v) * w + vec2(b.u, b.v) * u + vec2(c.u, c.v) * v;
  s.instance = t.instance;
  GpuInstance inst = gib_instances[t.instance];
  s.material = inst.material;
  // A normal map bends the shading normal in every pass alike (G-buffer, GI traces, path
  // tracer: the same light paths), sampled bilinearly at level 0 as the material's unfiltered
  // lookups are. A non-finite normal (no guard) passes on untouched. The instance's flag says
  // whether its material has one, so other surfaces never wait on the material's load.
  if ((inst.flags & kGibInstanceNormalMapped) == 0u) return s;
  uint nt = gib_materials[s.material].normal_texture;
  if (nt != GIB_TEXTURE_NO_INDEX && gib_finite(s.normal))
    s.normal = gib_normal_map(s.normal, a.position, b.position, c.position, vec2(a.u, a.v), vec2(b.u, b.v),
                              vec2(c.u, c.v), gib_texture_bilinear(nt, 0u, s.uv).rgb,
                              gib_materials[s.material].normal_scale);
  return s;
}
GibSurface gib_surface(uint tri, float u, float v) { return gib_surface(tri, u, v, true); }

// Offset a ray origin off a surface along its normal by a few float ulps of the position
// (integer offset in the float's bits), so it works equally at the origin and 10 km away
// (after Waechter and Binder, Ray Tracing Gems ch. 6: the method, written anew here).
vec3 gib_offset_ray(vec3 p, vec3 n) {
  const float kOrigin = 1.0 / 32.0, kFloatScale = 1.0 / 65536.0, kIntScale = 256.0;
  ivec3 of = ivec3(kIntScale * n);
  vec3 pi = vec3(intBitsToFloat(floatBitsToInt(p.x) + (p.x < 0.0 ? -of.x : of.x)),
                 intBitsToFloat(floatBitsToInt(p.y) + (p.y < 0.0 ? -of.y : of.y)),
                 intBitsToFloat(floatBitsToInt(p.z) + (p.z < 0.0 ? -of.z : of.z)));
  return vec3(abs(p.x) < kOrigin ? p.x + kFloatScale * n.x : pi.x,
              abs(p.y) < kOrigin ? p.y + kFloatScale * n.y : pi.y,
              abs(p.z) < kOrigin ? p.z + kFloatScale * n.z : pi.z);
}
// Unit face normal of triangle tri on the side `view` comes from (view: a direction towards the
// surface, e.g. the camera ray); `fallback` when the triangle has no area or is not finite.
vec3 gib_face_normal_facing(uint tri, vec3 view, vec3 fallback) {
  GpuTriangle t = gib_triangles[tri];
  vec3 a = gib_vertices[t.i0].position;
  vec3 g = cross(gib_vertices[t.i1].position - a, gib_vertices[t.i2].position - a);
  if (!(dot(g, g) > 0.0) || !gib_finite(g)) return fallback;
  g = normalize(g);
  return dot(g, view) > 0.0 ? -g : g;
}

// A direction sampled around an interpolated normal, leaving a surface whose face normal (on
// the leaving side) is ng: one below the face is mirrored back across the face plane, as the
// reference path tracer continues its paths; with the origin offset along ng no ray starts
// inside the mesh and loses its light to a self-hit.
vec3 gib_above_face(vec3 d, vec3 ng) {
  float below = dot(d, ng);
  return below <= 0.0 ? normalize(d - 2.0 * below * ng) : d;
}

#endif
