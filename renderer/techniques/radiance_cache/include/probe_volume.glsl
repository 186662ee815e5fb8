// Irradiance-volume geometry and sampling (owner: the world-sampling passes probe_trace,
// radiance_cache_update, radiance_cache_shade, irradiance_volume_update; design:
// renderer/techniques/radiance_cache/radiance_cache.md, atlas layout: radiance_cache_shared.h).
//
// Cascade c has 16^3 probes spaced rc_spacing(c) = grid.x * 2^c metres, following the camera in
// whole cells: probe (i,j,k) sits at (rc_base_cell(c) + ijk + 0.5) * spacing, and its atlas slot
// is (rc_base_cell(c) + ijk) & 15 per axis, so a probe keeps its tile while the grid scrolls.
// Tile texel (x, y) of the 8x8 interior (tile coordinates x+1, y+1) stores direction
// gib_oct_decode((vec2(x, y) + 0.5) / 8).
//
// Use (the push constants, named `rc`, and the frame constants come first):
//   #include "frame.glsl"
//   layout(push_constant) uniform Push { RcParams rc; ... };
//   #include "renderer/techniques/radiance_cache/include/probe_volume.glsl"
//   RC_PROBE_IMAGES(binding_irradiance, binding_visibility)  // only to call rc_sample_irradiance
//   vec3 e_over_pi = rc_sample_irradiance(p, n, to_viewer);
// A shader that samples the volumes defines RC_PROBE_RAYS and includes bvh.glsl and surface.glsl
// first: with RcParams.flags.w set, each of the 8 probes around the point is then tested with a
// shadow ray (see rc_sample_irradiance_weight).
// RC_PROBE_IMAGES declares the readonly atlas images rc_probe_irradiance (r32ui RGB9E5
// irradiance / pi) and rc_probe_visibility (rg16f distance moments) and the two texel
// accessors rc_sample_irradiance uses (prototyped here, so a shader that never samples the
// volumes need not declare the images).
#ifndef GIB_PROBE_VOLUME_GLSL
#define GIB_PROBE_VOLUME_GLSL
#include "renderer/techniques/radiance_cache/include/radiance_cache_shared.h"
#include "hash.glsl"
#include "packing.glsl"
#include "octahedral.glsl"

#define RC_PROBE_IMAGES(BI, BV)                                                                  \
  layout(set = 0, binding = (BI), r32ui) uniform readonly uimage2D rc_probe_irradiance;          \
  layout(set = 0, binding = (BV), rg16f) uniform readonly image2D rc_probe_visibility;           \
  uint rc_probe_irradiance_texel(ivec2 p) { return imageLoad(rc_probe_irradiance, p).x; }       \
  vec2 rc_probe_visibility_texel(ivec2 p) { return imageLoad(rc_probe_visibility, p).xy; }

uint rc_probe_irradiance_texel(ivec2 p);
vec2 rc_probe_visibility_texel(ivec2 p);

const float kRcPi = 3.14159265358979;
// Wrap shading floor (DDGI): probes behind the surface still count a little, so a point whose
// probes are all behind it is not black.
const float kRcWrapFloor = 0.2;
// Distances stored in the visibility moments are clamped to this many probe spacings (and
// kRcMaxMomentDistance metres) so the squared moment fits a half float (max 65504).
const float kRcMomentSpacings = 4.0;
const float kRcMaxMomentDistance = 200.0;
// Probes inside geometry (radiance_cache.glsl rc_probe_ray_inside): a hit closer than this many
// spacings means the probe sits on a surface; a probe with more than this fraction of its rays
// inside is not sampled.
const float kRcOnSurface = 1e-3;
const float kRcInsideFraction = 0.25;

uint rc_cascades() { return clamp(uint(rc.grid.y), 1u, kMaxCascades); }
uint rc_rays_per_probe() { return uint(rc.grid.z); }
uint rc_updated_cascade() { return uint(rc.grid.w); }

float rc_spacing(uint c) { return rc.grid.x * float(1u << c); }

ivec3 rc_base_cell(uint c) {
  return ivec3(floor(gib_frame.camera_pos.xyz / rc_spacing(c))) - ivec3(int(kProbeGridDim / 2u));
}

// Grid coordinates (0..15) of probe index 0..4095: x fastest.
ivec3 rc_probe_coord(uint probe) { return ivec3(probe & 15u, (probe >> 4u) & 15u, probe >> 8u); }

vec3 rc_probe_position(uint c, ivec3 ijk) {
  precise vec3 p = (vec3(rc_base_cell(c) + ijk) + 0.5) * rc_spacing(c);
  return p;
}

uvec3 rc_probe_slot(uint c, ivec3 ijk) { return uvec3((rc_base_cell(c) + ijk) & ivec3(int(kProbeGridDim) - 1)); }

uvec2 rc_tile_origin(uint c, uvec3 slot) {
  return uvec2((slot.z * kProbeGridDim + slot.x) * kProbeTileSize, (c * kProbeGridDim + slot.y) * kProbeTileSize);
}

float rc_moment_max_distance(uint c) { return min(kRcMomentSpacings * rc_spacing(c), kRcMaxMomentDistance); }

// ---- probe ray directions: spherical Fibonacci, rotated by a random rotation per frame (the
// same for every probe of the frame). Every pass that needs a ray's direction calls this, so
// hit positions rebuilt as probe + dir * distance agree bit for bit (everything precise).
mat3 rc_frame_rotation(uint frame) {
  uint h0 = gib_pcg(frame ^ 0x52c1e5u);
  uint h1 = gib_pcg(h0), h2 = gib_pcg(h1);
  precise float u1 = float(h0 >> 8u) * (1.0 / 16777216.0);
  precise float a2 = 2.0 * kRcPi * float(h1 >> 8u) * (1.0 / 16777216.0);
  precise float a3 = 2.0 * kRcPi * float(h2 >> 8u) * (1.0 / 16777216.0);
  // Uniform random unit quaternion (Shoemake), then its rotation matrix.
  precise float s1 = sqrt(1.0 - u1), s2 = sqrt(u1);
  precise vec4 q = vec4(s1 * sin(a2), s1 * cos(a2), s2 * sin(a3), s2 * cos(a3));
  precise float xx = q.x * q.x, yy = q.y * q.y, zz = q.z * q.z;
  precise float xy = q.x * q.y, xz = q.x * q.z, yz = q.y * q.z;
  precise float wx = q.w * q.x, wy = q.w * q.y, wz = q.w * q.z;
  precise mat3 r = mat3(vec3(1.0 - 2.0 * (yy + zz), 2.0 * (xy + wz), 2.0 * (xz - wy)),
                        vec3(2.0 * (xy - wz), 1.0 - 2.0 * (xx + zz), 2.0 * (yz + wx)),
                        vec3(2.0 * (xz + wy), 2.0 * (yz - wx), 1.0 - 2.0 * (xx + yy)));
  return r;
}

vec3 rc_ray_direction(uint ray, uint rays, mat3 rotation) {
  const float kGoldenAngle = 2.39996322972865332;  // pi (3 - sqrt 5)
  precise float z = 1.0 - (2.0 * float(ray) + 1.0) / float(rays);
  precise float r = sqrt(max(0.0, 1.0 - z * z));
  precise float phi = kGoldenAngle * float(ray);
  precise vec3 d = rotation * vec3(r * cos(phi), r * sin(phi), z);
  return normalize(d);
}

// Hit point of a probe ray (probe + dir * distance): what the radiance cache is keyed by.
vec3 rc_hit_position(vec3 probe, vec3 dir, float dist) {
  precise vec3 p = probe + dir * dist;
  return p;
}

// ---- sampling
// Bilinear sample of a probe tile in direction d; the 1-texel border makes every tap valid.
void rc_tile_taps(uvec2 origin, vec3 d, out ivec2 t0, out vec2 f) {
  vec2 x = vec2(origin) + gib_oct_tile_coord(d, int(kProbeTileInterior)) - 0.5;
  vec2 fl = floor(x);
  t0 = ivec2(fl);
  f = x - fl;
}

vec3 rc_tile_irradiance(uvec2 origin, vec3 d) {
  ivec2 t;
  vec2 f;
  rc_tile_taps(origin, d, t, f);
  vec3 a = gib_unpack_rgb9e5(rc_probe_irradiance_texel(t));
  vec3 b = gib_unpack_rgb9e5(rc_probe_irradiance_texel(t + ivec2(1, 0)));
  vec3 c = gib_unpack_rgb9e5(rc_probe_irradiance_texel(t + ivec2(0, 1)));
  vec3 e = gib_unpack_rgb9e5(rc_probe_irradiance_texel(t + ivec2(1, 1)));
  return mix(mix(a, b, f.x), mix(c, e, f.x), f.y);
}

vec2 rc_tile_moments(uvec2 origin, vec3 d) {
  ivec2 t;
  vec2 f;
  rc_tile_taps(origin, d, t, f);
  vec2 a = rc_probe_visibility_texel(t), b = rc_probe_visibility_texel(t + ivec2(1, 0));
  vec2 c = rc_probe_visibility_texel(t + ivec2(0, 1)), e = rc_probe_visibility_texel(t + ivec2(1, 1));
  return mix(mix(a, b, f.x), mix(c, e, f.x), f.y);
}

// Finest cascade whose probe lattice encloses q (grid coordinates g in [0, 15]^3); outside every
// cascade: the coarsest, g clamped (the edge probes extrapolate).
uint rc_select_cascade(vec3 q, out vec3 g) {
  uint n = rc_cascades();
  for (uint c = 0u; c < n; ++c) {
    g = q / rc_spacing(c) - vec3(rc_base_cell(c)) - 0.5;
    if (all(greaterThanEqual(g, vec3(0.0))) && all(lessThanEqual(g, vec3(float(kProbeGridDim - 1u))))) return c;
  }
  g = clamp(g, vec3(0.0), vec3(float(kProbeGridDim - 1u)));
  return n - 1u;
}

#ifdef RC_PROBE_RAYS
// Probe rays (RcParams.flags.w): is the probe at `probe` hidden from the surface point p (normal
// n, facing the sampler)? A shadow ray from p, offset off the surface, to the probe. The
// Chebyshev test on filtered distance moments only lowers a hidden probe's weight (a wall probe
// 0.2 m outside a 0.3 m wall keeps ~1e-3 of it, more while its moments are young), and at a
// 1e7:1 range (sunlit exterior, 1e-2 interior) that residue is the whole answer: the
// extreme-range case read 3300x the reference without this test.
bool rc_probe_hidden(vec3 p, vec3 n, vec3 probe) {
  vec3 o = gib_offset_ray(p, n);
  vec3 to_probe = probe - o;
  float r = length(to_probe);
  return r > 1e-6 && trace_any(o, to_probe / r, 0.0, r);
}
#endif

// Irradiance / pi at p for normal n from last-written probes, and the sum of the weights that
// produced it (0: no probe around p was ever updated; the result is then 0). Weights: trilinear
// x wrap shading ((n . to_probe + 1) / 2)^2 + 0.2 x Chebyshev visibility (rc.bias.z) on the
// distance moments; p is first biased by normal_bias * n + view_bias * to_viewer. With probe rays
// (RC_PROBE_RAYS and rc.flags.w) probes hidden from p are left out; when every probe is hidden
// (p in a pocket smaller than the probe spacing, or near a wall in a coarse cascade) the result
// is 0: the earlier fallback, the moment-weighted blend of all 8, carried a sunlit exterior's
// probes into a closed interior (extreme-range: 638x the reference after 256 frames -> 1.71).
vec3 rc_sample_irradiance_weight(vec3 p, vec3 n, vec3 to_viewer, out float weight) {
  vec3 q = p + rc.bias.x * n + rc.bias.y * to_viewer;
  vec3 g;
  uint c = rc_select_cascade(q, g);
  ivec3 i0 = min(ivec3(floor(g)), ivec3(int(kProbeGridDim) - 2));
  vec3 f = g - vec3(i0);
  ivec3 base = rc_base_cell(c);
  float spacing = rc_spacing(c);
  vec3 sum = vec3(0.0);
  weight = 0.0;
  for (int k = 0; k < 8; ++k) {
    ivec3 o = ivec3(k & 1, (k >> 1) & 1, k >> 2);
    ivec3 cell = base + i0 + o;
    vec3 probe = (vec3(cell) + 0.5) * spacing;
    uvec2 origin = rc_tile_origin(c, uvec3(cell & ivec3(int(kProbeGridDim) - 1)));
    vec3 to_probe = probe - q;
    float r = length(to_probe);
    vec3 dir = r > 1e-6 ? to_probe / r : n;
    vec2 m = rc_tile_moments(origin, -dir);
    // Loaded with the moments, before the tests that may skip the probe: its loads no longer
    // wait for the moments' and the visibility's (the same values either way).
    vec3 irradiance = rc_tile_irradiance(origin, n);
    // Moments 0: never updated, or inside geometry (irradiance_volume_update's iv_finish_texel).
    if (m.x <= 0.0) continue;
    float wrap = (dot(dir, n) + 1.0) * 0.5;
    float w = wrap * wrap + kRcWrapFloor;
    if (rc.bias.z > 0.5 && r > m.x) {
      float variance = max(abs(m.y - m.x * m.x), 1e-4 * spacing * spacing);
      float d = r - m.x;
      float cheb = variance / (variance + d * d);
      w *= max(cheb * cheb * cheb, 0.0);
    }
    w = max(w, 1e-5);
    vec3 t = mix(vec3(1.0) - f, f, vec3(o));
    w *= t.x * t.y * t.z;
#ifdef RC_PROBE_RAYS
    if (rc.flags.w != 0u && w > 0.0 && rc_probe_hidden(p, n, probe)) continue;
#endif
    sum += w * irradiance;
    weight += w;
  }
  return weight > 0.0 ? sum / weight : vec3(0.0);
}

vec3 rc_sample_irradiance(vec3 p, vec3 n, vec3 to_viewer) {
  float w;
  return rc_sample_irradiance_weight(p, n, to_viewer, w);
}
#endif  // GIB_PROBE_VOLUME_GLSL
