#version 460
#extension GL_GOOGLE_include_directive : require
// The separable bilateral gaussian over the gather SH and the gather's direct part, with the
// same weights (see gi_denoise.h): one direction per dispatch, or both in one (kFused).
#include "renderer/techniques/radiance_cache/gi_denoise/gi_denoise_shared.h"
#include "finite.glsl"
#include "packing.glsl"

layout(local_size_x = kDenoiseGroup, local_size_y = kDenoiseGroup) in;
layout(set = 0, binding = kDenoiseBindNormal, rgba16f) uniform readonly image2D gb_normal;
layout(set = 0, binding = kDenoiseBindPosition, rgba32f) uniform readonly image2D gb_position;
layout(set = 0, binding = kDenoiseBindHit, r32f) uniform readonly image2D in_hit;
layout(set = 0, binding = kDenoiseBindInR, rgba16f) uniform readonly image2D in_r;
layout(set = 0, binding = kDenoiseBindInG, rgba16f) uniform readonly image2D in_g;
layout(set = 0, binding = kDenoiseBindInB, rgba16f) uniform readonly image2D in_b;
layout(set = 0, binding = kDenoiseBindOutR, rgba16f) uniform writeonly image2D out_r;
layout(set = 0, binding = kDenoiseBindOutG, rgba16f) uniform writeonly image2D out_g;
layout(set = 0, binding = kDenoiseBindOutB, rgba16f) uniform writeonly image2D out_b;
layout(set = 0, binding = kDenoiseBindInDirect, rgba16f) uniform readonly image2D in_direct;
layout(set = 0, binding = kDenoiseBindOutDirect, rgba16f) uniform writeonly image2D out_direct;
layout(push_constant) uniform Push { DenoisePush push; };
// true: the group preloads its taps into shared memory (the tile: the group's pixels and radius
// more either side along the axis), every tap then reads them there; false: each tap reads the
// images (option denoise_kernel 1). The same values reach the same arithmetic either way.
layout(constant_id = kDenoiseSpecTiled) const bool kTiled = true;
// The tile's texels: kDenoiseGroup x (kDenoiseGroup + 2 radius) when tiled, 1 when not, so the
// per-tap kernel reserves no shared memory (on NVIDIA a kernel's shared memory takes L1 cache
// away from the image loads the per-tap kernel depends on); (kDenoiseGroup + 2 radius)^2 fused.
layout(constant_id = kDenoiseSpecTileTexels) const uint kTileTexels = 1u;
// true (with kTiled): both directions in one dispatch. The group loads its pixels and radius
// more on every side, filters every row of that tile horizontally over its own columns, keeps
// the results in the tile (rounded toward zero to FP16: what the horizontal dispatch's RGBA16F
// store holds, see store()) and filters them vertically. The same values reach the same
// arithmetic as the two dispatches; no gi_denoise_tmp_* images.
layout(constant_id = kDenoiseSpecFused) const bool kFused = false;

// Geometry of gather pixel g: its representative full-res pixel's position (w: distance to the
// camera, 0 for sky) and normal.
void gather_geometry(ivec2 g, out vec4 pos, out vec3 n) {
  int div = int(push.divisor);
  ivec2 p = min(g * div + div / 2, imageSize(gb_position) - 1);
  pos = imageLoad(gb_position, p);
  n = imageLoad(gb_normal, p).xyz;
}

// ---- the tile, 60 bytes a texel: the rgba32f position and the r32f hit distance as fp32; the
// rgba16f normal, SH and direct part as FP16 (the seed's), packed: each was an FP16 value in its
// image, so unpacking gives back the same numbers. A texel outside the image is stored as sky
// (pos.w = 0): both are skipped as taps. The normal's fourth half holds whether the texel's SH
// and direct part are all finite (1) or not (0), tested once per texel for the NaN guard instead
// of once per tap.
shared vec4 s_pos[kTileTexels];
shared float s_hit[kTileTexels];
shared uvec2 s_normal[kTileTexels];
shared uvec4 s_rg[kTileTexels], s_bd[kTileTexels];  // SH r and g; SH b and the direct part

bool all_finite(vec4 r, vec4 g, vec4 b, vec4 d) { return gib_finite(r) && gib_finite(g) && gib_finite(b) && gib_finite(d); }

uvec2 pack4(vec4 v) { return uvec2(packHalf2x16(v.xy), packHalf2x16(v.zw)); }
vec4 unpack4(uvec2 u) { return vec4(unpackHalf2x16(u.x), unpackHalf2x16(u.y)); }
uvec2 pack4_rtz(vec4 v) { return uvec2(gib_pack_half2x16_rtz(v.xy), gib_pack_half2x16_rtz(v.zw)); }

// Tile layout: tile_w x tile_h texels (the group, widened by radius either side along the axis)
// from image texel `origin`, row-major, so neighbouring threads load neighbouring texels.
void load_tile(ivec2 origin, int tile_w, int tile_h, ivec2 size) {
  for (int l = int(gl_LocalInvocationIndex); l < tile_w * tile_h; l += int(kDenoiseGroup * kDenoiseGroup)) {
    ivec2 q = origin + ivec2(l % tile_w, l / tile_w);
    vec4 pos = vec4(0.0), r = vec4(0.0), g = vec4(0.0), b = vec4(0.0), d = vec4(0.0);
    vec3 n = vec3(0.0);
    float hit = 0.0;
    if (all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size))) {
      gather_geometry(q, pos, n);
      hit = imageLoad(in_hit, q).x;
      r = imageLoad(in_r, q);
      g = imageLoad(in_g, q);
      b = imageLoad(in_b, q);
      d = imageLoad(in_direct, q);
    }
    s_pos[l] = pos;
    s_hit[l] = hit;
    s_normal[l] = pack4(vec4(n, all_finite(r, g, b, d) ? 1.0 : 0.0));
    s_rg[l] = uvec4(pack4(r), pack4(g));
    s_bd[l] = uvec4(pack4(b), pack4(d));
  }
}

// ---- the filter, shared by both layouts.
struct Sums {
  vec4 r, g, b, d;
  float w, wd;
};

// Tap weights at offset k for the centre (pos_c, n_c, h_c): wd the geometry weight (the direct
// part's), w the SH taps' (wd, times the hit-distance weight when it is on).
void tap_weights(int k, float inv_two_sigma2, vec4 pos_c, vec3 n_c, float h_c, vec4 pos_q, vec3 n_q, float h_q,
                 out float w, out float wd) {
  wd = exp(-float(k * k) * inv_two_sigma2);
  wd *= pow(max(0.0, dot(n_c, n_q)), kDenoiseNormalPower);
  wd *= exp(-abs(dot(n_c, pos_q.xyz - pos_c.xyz)) / (pos_c.w * kDenoiseDepthSigma));
  w = wd;
  if (push.hit_weight != 0u) {
    float dh = abs(h_q - h_c) / max(max(h_q, h_c), 1e-6);
    w *= exp(-(dh * dh) / (kDenoiseHitSigma * kDenoiseHitSigma));
  }
}

// values_finite: all_finite(tr, tg, tb, td), which the guard needs.
void add_tap(float w, float wd, bool values_finite, vec4 tr, vec4 tg, vec4 tb, vec4 td, inout Sums s) {
  // Guard: skip a tap whose weight (a NaN normal) or value is not finite: weight 0 would not
  // do, 0 x NaN is NaN.
  if (push.nan_guards != 0u && !(gib_finite(w) && gib_finite(wd) && values_finite)) return;
  s.r += w * tr;
  s.g += w * tg;
  s.b += w * tb;
  s.w += w;
  s.d += wd * td;
  s.wd += wd;
}

// The filtered values, packed as FP16 rounded toward zero: the horizontal direction's output.
// Its dispatch stores them so (exact in an RGBA16F image on any device; lavapipe's own store
// rounds toward zero too), the fused kernel keeps them in the tile: both give the vertical
// direction the same numbers.
struct Packed {
  uvec4 rg, bd;  // SH r and g; SH b and the direct part
};

Packed result_rtz(Sums s) {
  // The centre's own weight is 1 (k = 0, identical geometry), so sum_w >= 1, unless guards
  // skipped it (then every tap may be gone and the result is 0).
  float inv = 1.0 / max(s.w, 1e-6);
  return Packed(uvec4(pack4_rtz(s.r * inv), pack4_rtz(s.g * inv)), uvec4(pack4_rtz(s.b * inv), pack4_rtz(s.d / max(s.wd, 1e-6))));
}

void store(ivec2 g, Sums s, bool horizontal) {
  if (horizontal) {
    Packed h = result_rtz(s);
    imageStore(out_r, g, unpack4(h.rg.xy));
    imageStore(out_g, g, unpack4(h.rg.zw));
    imageStore(out_b, g, unpack4(h.bd.xy));
    imageStore(out_direct, g, unpack4(h.bd.zw));
    return;
  }
  float inv = 1.0 / max(s.w, 1e-6);
  imageStore(out_r, g, s.r * inv);
  imageStore(out_g, g, s.g * inv);
  imageStore(out_b, g, s.b * inv);
  imageStore(out_direct, g, s.d / max(s.wd, 1e-6));
}

void store_sky(ivec2 g) {
  imageStore(out_r, g, vec4(0.0));
  imageStore(out_g, g, vec4(0.0));
  imageStore(out_b, g, vec4(0.0));
  imageStore(out_direct, g, vec4(0.0));
}

// The filter over the tile around texel `centre`, taps `stride` apart; false for a sky centre
// (its output is 0).
bool filter_tile(int centre, int stride, int radius, float inv_two_sigma2, out Sums s) {
  s = Sums(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), 0.0, 0.0);
  vec4 pos_c = s_pos[centre];
  if (pos_c.w == 0.0) return false;
  vec3 n_c = unpack4(s_normal[centre]).xyz;
  float h_c = s_hit[centre];
  for (int k = -radius; k <= radius; ++k) {
    int t = centre + k * stride;
    vec4 pos_q = s_pos[t];
    if (pos_q.w == 0.0) continue;  // sky, or outside the image
    float w, wd;
    vec4 normal_q = unpack4(s_normal[t]);
    tap_weights(k, inv_two_sigma2, pos_c, n_c, h_c, pos_q, normal_q.xyz, s_hit[t], w, wd);
    if (wd <= 0.0) continue;
    uvec4 rg = s_rg[t], bd = s_bd[t];
    add_tap(w, wd, normal_q.w != 0.0, unpack4(rg.xy), unpack4(rg.zw), unpack4(bd.xy), unpack4(bd.zw), s);
  }
  return true;
}

// Horizontal outputs a thread of the fused kernel keeps until the group has read every input:
// kDenoiseGroup x (kDenoiseGroup + 2 radius) of them, 128 at the largest fused radius (4).
const int kFusedPerThread = 2;

void fused(ivec2 g, ivec2 size, int radius, float inv_two_sigma2) {
  // Every thread loads (no early return before the barriers).
  int tile_w = int(kDenoiseGroup) + 2 * radius;
  load_tile(ivec2(gl_WorkGroupID.xy * kDenoiseGroup) - radius, tile_w, tile_w, size);
  barrier();
  // Horizontal: every row of the tile, over the group's columns (tile columns radius ..
  // radius + kDenoiseGroup - 1), whose taps all lie in the tile.
  const int threads = int(kDenoiseGroup * kDenoiseGroup), outputs = int(kDenoiseGroup) * tile_w;
  Packed h[kFusedPerThread];
  bool h_finite[kFusedPerThread];
  for (int i = 0; i < kFusedPerThread; ++i) {
    int l = int(gl_LocalInvocationIndex) + i * threads;
    if (l >= outputs) break;
    int centre = (l / int(kDenoiseGroup)) * tile_w + l % int(kDenoiseGroup) + radius;
    Sums s;
    // A sky texel's output is 0 (the horizontal dispatch's store_sky); texels outside the image
    // are sky in the tile, and the vertical taps skip both by their position anyway.
    h[i] = filter_tile(centre, 1, radius, inv_two_sigma2, s) ? result_rtz(s) : Packed(uvec4(0u), uvec4(0u));
    h_finite[i] = all_finite(unpack4(h[i].rg.xy), unpack4(h[i].rg.zw), unpack4(h[i].bd.xy), unpack4(h[i].bd.zw));
  }
  barrier();
  // The horizontal results replace the gather's values in the tile, with their own finiteness
  // (the normal's fourth half), as the vertical dispatch loads them from gi_denoise_tmp_*.
  for (int i = 0; i < kFusedPerThread; ++i) {
    int l = int(gl_LocalInvocationIndex) + i * threads;
    if (l >= outputs) break;
    int centre = (l / int(kDenoiseGroup)) * tile_w + l % int(kDenoiseGroup) + radius;
    s_rg[centre] = h[i].rg;
    s_bd[centre] = h[i].bd;
    s_normal[centre] = pack4(vec4(unpack4(s_normal[centre]).xyz, h_finite[i] ? 1.0 : 0.0));
  }
  barrier();
  if (any(greaterThanEqual(g, size))) return;
  ivec2 c = ivec2(gl_LocalInvocationID.xy) + radius;  // the centre in the tile
  Sums s;
  if (filter_tile(c.y * tile_w + c.x, tile_w, radius, inv_two_sigma2, s))
    store(g, s, false);
  else
    store_sky(g);
}

void main() {
  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(out_r);
  int radius = int(push.radius);
  float inv_two_sigma2 = radius > 0 ? 2.0 / float(radius * radius) : 0.0;  // sigma = radius / 2
  ivec2 axis = ivec2(push.axis_x, push.axis_y);
  bool horizontal = axis.x != 0;
  if (kTiled && kFused) {
    fused(g, size, radius, inv_two_sigma2);
    return;
  }
  Sums s = Sums(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), 0.0, 0.0);
  if (kTiled) {
    // Every thread loads (no early return before the barrier).
    int tile_w = int(kDenoiseGroup) + 2 * radius * axis.x, tile_h = int(kDenoiseGroup) + 2 * radius * axis.y;
    load_tile(ivec2(gl_WorkGroupID.xy * kDenoiseGroup) - radius * axis, tile_w, tile_h, size);
    barrier();
    if (any(greaterThanEqual(g, size))) return;
    ivec2 c = ivec2(gl_LocalInvocationID.xy) + radius * axis;  // the centre in the tile
    if (filter_tile(c.y * tile_w + c.x, axis.x + axis.y * tile_w, radius, inv_two_sigma2, s))
      store(g, s, horizontal);
    else
      store_sky(g);
    return;
  }
  if (any(greaterThanEqual(g, size))) return;
  vec4 pos_c;
  vec3 n_c;
  gather_geometry(g, pos_c, n_c);
  if (pos_c.w == 0.0) {
    store_sky(g);
    return;
  }
  float h_c = imageLoad(in_hit, g).x;
  for (int k = -radius; k <= radius; ++k) {
    ivec2 q = g + k * axis;
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
    vec4 pos_q;
    vec3 n_q;
    gather_geometry(q, pos_q, n_q);
    if (pos_q.w == 0.0) continue;
    float w, wd;
    tap_weights(k, inv_two_sigma2, pos_c, n_c, h_c, pos_q, n_q, imageLoad(in_hit, q).x, w, wd);
    if (wd <= 0.0) continue;
    vec4 tr = imageLoad(in_r, q), tg = imageLoad(in_g, q), tb = imageLoad(in_b, q), td = imageLoad(in_direct, q);
    add_tap(w, wd, all_finite(tr, tg, tb, td), tr, tg, tb, td, s);
  }
  store(g, s, horizontal);
}
