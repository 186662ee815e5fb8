// Probe-volume geometry and buffer accessors shared by every probe-volume pass (layout:
// probe_volume_shared.h; design: renderer/techniques/probe_volume/probe_volume.md).
//
// Cascade c: pv.grid.x x pv.grid.y x pv.grid.x probes (x, y up, z) spaced pv_spacing(c) =
// pv.volume.x * 2^c metres. The volume's minimum corner cell, pv_cascade[c].origin, follows the
// camera (probe_select); a probe of cell k sits at (k + 0.5) * spacing + its relocation offset,
// in slot k mod dims (toroidal addressing: a probe keeps its slot and buffers while the volume
// scrolls; a slot whose cell changed is a new probe).
//
// Use: declare the push constants as `PvParams pv` and include frame.glsl first, then
//   PV_STATE_BUFFER(binding, readonly)   // or with no qualifier to write it
#ifndef GIB_PV_COMMON_GLSL
#define GIB_PV_COMMON_GLSL
#include "renderer/techniques/probe_volume/include/probe_volume_shared.h"
#include "packing.glsl"
#include "octahedral.glsl"

#define PV_STATE_BUFFER(B, QUAL)                                     \
  layout(std430, set = 0, binding = (B)) QUAL buffer PvStateBuffer { \
    PvCascade pv_cascade[kPvMaxCascades];                            \
    PvProbe pv_probes[];                                             \
  };

// The probe G-buffer's depths (half floats, two texels per word) and their accessor:
// pv_texel_depth(probe, t, miss) is texel t's hit distance, `miss` where its ray missed.
#define PV_GBUFFER_DEPTH(B, QUAL)                                                               \
  layout(std430, set = 0, binding = (B)) QUAL buffer DepthBuffer { uint gb_depth[]; };           \
  float pv_texel_depth(uint probe, uint t, float miss) {                                         \
    uint w = gb_depth[pv_gbuffer_index(probe, t) >> 1u];                                         \
    uint h = (t & 1u) != 0u ? w >> 16u : w & 0xffffu;                                           \
    return h == kPvMissDepthBits ? miss : gib_half_to_float(h);                                  \
  }

// The probe lighting buffers, readonly (pv_sample.glsl reads them).
#define PV_PROBE_BUFFERS(BI, BR, BV)                                                                     \
  layout(std430, set = 0, binding = (BI)) readonly buffer PvIrradianceBuffer { uvec2 pv_irradiance[]; }; \
  layout(std430, set = 0, binding = (BR)) readonly buffer PvRadianceBuffer { uvec2 pv_radiance[]; };     \
  layout(std430, set = 0, binding = (BV)) readonly buffer PvVisibilityBuffer { uint pv_visibility[]; };

const float kPvSqrt3 = 1.7320508;

uint pv_cascades() { return min(pv.grid.z, kPvMaxCascades); }
ivec3 pv_dims() { return ivec3(int(pv.grid.x), int(pv.grid.y), int(pv.grid.x)); }
uint pv_probes_per_cascade() { return pv.grid.x * pv.grid.x * pv.grid.y; }
uint pv_probe_count() { return pv_probes_per_cascade() * pv_cascades(); }
float pv_spacing(uint c) { return pv.volume.x * float(1u << c); }
float pv_trace_range(uint c) { return pv.volume.z * pv_spacing(c); }
bool pv_flag(uint f) { return (pv.flags.x & f) != 0u; }
uint pv_frame() { return pv.grid.w; }
uint pv_cascade_of(uint probe) { return probe / pv_probes_per_cascade(); }

// a mod d in [0, d) for any sign of a (GLSL leaves % undefined for negative operands).
ivec3 pv_mod(ivec3 a, ivec3 d) {
  ivec3 r = a - (a / d) * d;
  return r + ivec3(lessThan(r, ivec3(0))) * d;
}

// Slot index within a cascade: x fastest, then z, then y.
uint pv_slot_index(ivec3 slot) { return uint(slot.x) + pv.grid.x * (uint(slot.z) + pv.grid.x * uint(slot.y)); }
ivec3 pv_slot_of_index(uint i) {
  uint x = pv.grid.x;
  return ivec3(int(i % x), int(i / (x * x)), int((i / x) % x));
}
uint pv_probe_index(uint c, ivec3 cell) { return c * pv_probes_per_cascade() + pv_slot_index(pv_mod(cell, pv_dims())); }
// The cell slot `slot` holds under volume origin `origin`: the one in [origin, origin + dims)
// congruent to it.
ivec3 pv_cell_of_slot(ivec3 origin, ivec3 slot) { return origin + pv_mod(slot - origin, pv_dims()); }

vec3 pv_cell_position(uint c, ivec3 cell) {
  precise vec3 p = (vec3(cell) + 0.5) * pv_spacing(c);
  return p;
}

// The class of a point seen from the side of unit normal n (zero: the point itself), indoor
// when 5 cm off that side lies in an indoor volume (the seed classifies the two faces of a
// translucent surface separately). Outdoor for every point when indoor_classes is off.
bool pv_point_indoor(vec3 x, vec3 n) { return pv_flag(kPvFlagIndoor) && gib_indoor(x + n * 0.05); }

// ---- tile addressing
uint pv_gbuffer_index(uint probe, uint t) { return probe * kPvGbufferTexels + t; }
uint pv_irradiance_index(uint probe, ivec2 t) { return probe * kPvIrradianceTexels + uint(t.y) * kPvIrradianceSide + uint(t.x); }
uint pv_radiance_index(uint probe, ivec2 t) { return probe * kPvRadianceTexels + uint(t.y) * kPvRadianceSide + uint(t.x); }
// Direction of G-buffer texel t (0..399): the centre of texel (t % 20, t / 20) of the
// octahedral square; a quarter-resolution trace uses the centre of its 2x2 block.
vec3 pv_gbuffer_direction(uint t, bool quarter) {
  vec2 xy = vec2(t % kPvGbufferSide, t / kPvGbufferSide);
  vec2 uv = quarter ? (floor(xy * 0.5) * 2.0 + 1.0) / float(kPvGbufferSide) : (xy + 0.5) / float(kPvGbufferSide);
  return gib_oct_decode(uv);
}

// Solid angle of an octahedral texel whose centre is direction d (unit), relative to a texel on
// an axis: texels cover equal areas of the octahedron |x| + |y| + |z| = 1, and an area there at
// P = d / |d|_1 subtends cos / |P|^2 = (1 / sqrt(3)) / |P|^3 of it, |P| = 1 / |d|_1: so |d|_1^3
// (1 on an axis, 3 sqrt(3) = 5.2 on a diagonal).
float pv_texel_solid_angle(vec3 d) {
  float l1 = abs(d.x) + abs(d.y) + abs(d.z);
  return l1 * l1 * l1;
}

// The irradiance tile's equator vertices (kPvIrradianceInterior odd). The octahedral square's edge
// midpoints are the octahedron's vertices +x, -x, +y, -y, where the map folds onto itself: the
// mirrored border (gib_oct_border_source) copies the edge's middle interior texel into the
// middle border texel, so a bilinear lookup at +-x or +-y reads that texel alone, whose
// direction lies 14 degrees above the equator (towards +z): every wall or floor normal read
// the irradiance of a direction tilted towards +z. The middle border texel k (0: right, 1:
// left, 2: top, 3: bottom) holds instead the irradiance at the middle texel's direction
// reflected below the equator, so the lookup at the vertex averages the two, 14 degrees above
// and below. pv_irradiance_vertex_texel(k): the border texel; pv_irradiance_vertex_direction(k):
// the direction its value is convolved for.
ivec2 pv_irradiance_vertex_texel(uint k) {
  int m = int(kPvIrradianceInterior + 1u) / 2, last = int(kPvIrradianceInterior) + 1;
  return k == 0u ? ivec2(last, m) : k == 1u ? ivec2(0, m) : k == 2u ? ivec2(m, 0) : ivec2(m, last);
}
vec3 pv_irradiance_vertex_direction(uint k) {
  ivec2 at = pv_irradiance_vertex_texel(k);
  int n = int(kPvIrradianceInterior);
  ivec2 inner = clamp(at, ivec2(1), ivec2(n));
  vec3 d = gib_oct_texel_direction(inner, n);
  return vec3(d.xy, -d.z);
}
// Index 0..3 of the vertex texel `at` is, or 4.
uint pv_irradiance_vertex_of(ivec2 at) {
  for (uint k = 0u; k < 4u; ++k)
    if (all(equal(at, pv_irradiance_vertex_texel(k)))) return k;
  return 4u;
}

// ---- G-buffer texel codecs (probe_volume_shared.h)
uvec2 pv_pack_material(vec3 albedo, float translucency, vec3 emission) {
  uvec4 a = uvec4(clamp(vec4(albedo, translucency), 0.0, 1.0) * 255.0 + 0.5);
  return uvec2(a.x | (a.y << 8u) | (a.z << 16u) | (a.w << 24u), gib_pack_rgb9e5(emission));
}
vec4 pv_unpack_albedo(uvec2 m) {
  return vec4(m.x & 255u, (m.x >> 8u) & 255u, (m.x >> 16u) & 255u, m.x >> 24u) * (1.0 / 255.0);
}
uint pv_pack_normal_shadow(vec3 n, float sun) {
  uvec2 o = uvec2(clamp(gib_oct_encode(n), 0.0, 1.0) * 4095.0 + 0.5);
  return o.x | (o.y << 12u) | (uint(clamp(sun, 0.0, 1.0) * 255.0 + 0.5) << 24u);
}
// The per-pixel hit normal (pixel_hits.y): octahedral 16+16 bits.
uint pv_pack_normal16(vec3 n) {
  uvec2 o = uvec2(clamp(gib_oct_encode(n), 0.0, 1.0) * 65535.0 + 0.5);
  return o.x | (o.y << 16u);
}
vec3 pv_unpack_normal16(uint w) { return gib_oct_decode(vec2(w & 0xffffu, w >> 16u) * (1.0 / 65535.0)); }
vec3 pv_unpack_normal(uint w) { return gib_oct_decode(vec2(w & 4095u, (w >> 12u) & 4095u) * (1.0 / 4095.0)); }
float pv_unpack_shadow(uint w) { return float(w >> 24u) * (1.0 / 255.0); }

#if defined(GIB_BVH_GLSL) && defined(GIB_SURFACE_GLSL)
// The sun's visibility (0/1) from a hit at x whose seen side has normal n: one shadow ray to the
// sun's centre from the side the sun lights (either side of a translucent surface); 0 with the
// sun off or behind an opaque surface.
float pv_sun_visibility(vec3 x, vec3 n, float translucency) {
  if (gib_frame.sun_irradiance.w <= 0.0) return 0.0;
  vec3 l = gib_frame.sun_dir.xyz;
  float c = dot(n, l);
  if (!(c > 0.0 || translucency > 0.0)) return 0.0;
  return trace_any(gib_offset_ray(x, c > 0.0 ? n : -n), l, 0.0, 3.4e38) ? 0.0 : 1.0;
}
#endif

#ifdef GIB_LIGHTS_GLSL  // and sampling.glsl
// The seed's estimate of a probe's sun and sky light (AC Shadows "Lighting update"): the sun
// by its height, times middle grey, where the probe does not see the sky, plus the sky seen
// straight up. Compared between updates, it rescales probes that are not relit.
float pv_sun_sky_estimate(float sky_visibility) {
  vec3 e = vec3(0.0);
  if (gib_frame.sun_irradiance.w > 0.0)
    e += (gib_frame.sun_dir.y + 1.0) * 0.5 * gib_frame.sun_irradiance.rgb * 0.18 * (1.0 - sky_visibility);
  e += gib_sky_radiance(vec3(0.0, 1.0, 0.0));
  return gib_luminance(e);
}

#endif

#endif  // GIB_PV_COMMON_GLSL
