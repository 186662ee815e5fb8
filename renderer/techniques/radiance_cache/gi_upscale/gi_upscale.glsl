// gi_upscale kernel, included by gi_upscale_<format>.comp with GI_HISTORY_FORMAT defined
// (0 RGB9E5 in r32ui, 1 rgba16f, 2 r11f_g11f_b10f, 3 rgba32f). See gi_upscale.h.
#include "renderer/techniques/radiance_cache/gi_upscale/gi_upscale_shared.h"
#include "frame.glsl"
#include "sampling.glsl"
#include "packing.glsl"
#include "hash.glsl"
#include "sh.glsl"
#include "finite.glsl"

layout(local_size_x = kUpscaleGroup, local_size_y = kUpscaleGroup) in;
layout(set = 0, binding = kUpscaleBindNormal, rgba16f) uniform readonly image2D gb_normal;
layout(set = 0, binding = kUpscaleBindPosition, rgba32f) uniform readonly image2D gb_position;
layout(set = 0, binding = kUpscaleBindPrevNormal, rgba16f) uniform readonly image2D prev_normal;
layout(set = 0, binding = kUpscaleBindPrevPosition, rgba32f) uniform readonly image2D prev_position;
layout(set = 0, binding = kUpscaleBindShR, rgba16f) uniform readonly image2D sh_r;
layout(set = 0, binding = kUpscaleBindShG, rgba16f) uniform readonly image2D sh_g;
layout(set = 0, binding = kUpscaleBindShB, rgba16f) uniform readonly image2D sh_b;
layout(set = 0, binding = kUpscaleBindPrevFrames, r32f) uniform readonly image2D prev_frames;
layout(set = 0, binding = kUpscaleBindFrames, r32f) uniform writeonly image2D out_frames;
layout(set = 0, binding = kUpscaleBindDirect, rgba16f) uniform readonly image2D gi_direct;
layout(push_constant) uniform Push { UpscalePush push; };
// Pre-exposure (exposure pass): the gather SH and the history hold irradiance / pi x P; P_now
// is this frame's P, P_prev the one last frame's history was stored with.
layout(set = 0, binding = kUpscaleBindExposure, std430) readonly buffer Exposure { float exposure[4]; };

// History storage, one pair of functions per history image (the bounce light's gi_history and
// the direct part's gi_history_direct, same format). STORE returns exactly what a later LOAD
// returns: values are quantised here with a known rounding (the codec's or packHalf2x16), so
// the image's own conversion on store is exact.
#if GI_HISTORY_FORMAT == 0
// The dither of a pixel's RGB9E5 history store (option dither_stores; stochastic rounding keeps
// the temporal filter's expectation moving when a frame's change is below half a unit:
// radiance_cache.md, "Quantised stores").
uint gi_history_dither(ivec2 p) {
  return gib_pcg(uint(p.x) ^ gib_pcg(uint(p.y) ^ gib_pcg(push.frame ^ 0x2545f491u)));
}
#define GI_HISTORY_IO(PREV, OUT, PREV_BIND, OUT_BIND, LOAD, STORE)                            \
  layout(set = 0, binding = PREV_BIND, r32ui) uniform readonly uimage2D PREV;                 \
  layout(set = 0, binding = OUT_BIND, r32ui) uniform writeonly uimage2D OUT;                  \
  vec3 LOAD(ivec2 q) { return gib_unpack_rgb9e5(imageLoad(PREV, q).x); }                      \
  vec3 STORE(ivec2 p, vec3 v) {                                                               \
    uint e = push.dither != 0u ? gib_pack_rgb9e5_dither(v, gi_history_dither(p)) : gib_pack_rgb9e5(v); \
    imageStore(OUT, p, uvec4(e, 0u, 0u, 0u));                                                 \
    return gib_unpack_rgb9e5(e);                                                              \
  }
#elif GI_HISTORY_FORMAT == 1
// min() keeps a NaN for the guards to decide (gib_clamp_keep_nan, finite.glsl).
#define GI_HISTORY_IO(PREV, OUT, PREV_BIND, OUT_BIND, LOAD, STORE)                            \
  layout(set = 0, binding = PREV_BIND, rgba16f) uniform readonly image2D PREV;                \
  layout(set = 0, binding = OUT_BIND, rgba16f) uniform writeonly image2D OUT;                 \
  vec3 LOAD(ivec2 q) { return imageLoad(PREV, q).rgb; }                                       \
  vec3 STORE(ivec2 p, vec3 v) {                                                               \
    v = gib_clamp_keep_nan(vec4(v, 0.0), -65504.0, 65504.0).rgb;                              \
    vec3 h = vec3(unpackHalf2x16(packHalf2x16(v.rg)), unpackHalf2x16(packHalf2x16(vec2(v.b, 0.0))).x); \
    imageStore(OUT, p, vec4(h, 1.0));                                                         \
    return h;                                                                                 \
  }
#elif GI_HISTORY_FORMAT == 2
#define GI_HISTORY_IO(PREV, OUT, PREV_BIND, OUT_BIND, LOAD, STORE)                            \
  layout(set = 0, binding = PREV_BIND, r11f_g11f_b10f) uniform readonly image2D PREV;         \
  layout(set = 0, binding = OUT_BIND, r11f_g11f_b10f) uniform writeonly image2D OUT;          \
  vec3 LOAD(ivec2 q) { return imageLoad(PREV, q).rgb; }                                       \
  vec3 STORE(ivec2 p, vec3 v) {                                                               \
    vec3 h = gib_unpack_r11g11b10(gib_pack_r11g11b10(v));                                     \
    imageStore(OUT, p, vec4(h, 1.0));                                                         \
    return h;                                                                                 \
  }
#else
#define GI_HISTORY_IO(PREV, OUT, PREV_BIND, OUT_BIND, LOAD, STORE)                            \
  layout(set = 0, binding = PREV_BIND, rgba32f) uniform readonly image2D PREV;                \
  layout(set = 0, binding = OUT_BIND, rgba32f) uniform writeonly image2D OUT;                 \
  vec3 LOAD(ivec2 q) { return imageLoad(PREV, q).rgb; }                                       \
  vec3 STORE(ivec2 p, vec3 v) {                                                               \
    imageStore(OUT, p, vec4(v, 1.0));                                                         \
    return v;                                                                                 \
  }
#endif
GI_HISTORY_IO(prev_history, out_history, kUpscaleBindPrevHistory, kUpscaleBindHistory, load_history, store_history)
GI_HISTORY_IO(prev_history_direct, out_history_direct, kUpscaleBindPrevHistoryDirect, kUpscaleBindHistoryDirect,
              load_history_direct, store_history_direct)

// value (bounce) and direct are pre-exposed (x P_now) and stored so. The passes after this one
// read the history back (include/gi_history.glsl) and divide P_now out themselves
// (gi_composite, gi_resolve): no absolute-unit copy is written here.
void write_out(ivec2 p, vec3 value, vec3 direct, float frames) {
  store_history(p, value);
  store_history_direct(p, direct);
  imageStore(out_frames, p, vec4(frames, 0.0, 0.0, 0.0));
}

// ---- gather samples: read from the images, or (kTiled) from the group's tile of them.
// true: each group first loads every gather sample its pixels' taps can reach (the 4 bilinear
// taps and the 4x4 fallback around them) into group-shared memory, and every tap reads them
// there; false: each tap reads the images (option upscale_kernel 1). The tile keeps the
// rgba32f position as fp32 and the rgba16f normal, SH and direct part as FP16, packed (each was
// an FP16 value in its image, so unpacking gives back the same numbers): 56 bytes a texel.
// Both kernels give the same output bit for bit.
layout(constant_id = kUpscaleSpecTiled) const bool kTiled = true;
// The tile's side in gather pixels (gi_upscale.cpp: 11, 8 and 6 at divisors 1, 2 and 4), 1 for
// the per-tap kernel, which then reserves no shared memory (on NVIDIA a kernel's shared memory
// takes L1 cache away from image loads).
layout(constant_id = kUpscaleSpecTileSide) const uint kTileSide = 1u;
shared vec4 s_gpos[kTileSide * kTileSide];     // gather sample's full-res position
shared uvec2 s_gnormal[kTileSide * kTileSide];  // and normal
shared uvec4 s_sh_rg[kTileSide * kTileSide];    // SH r, g
shared uvec4 s_sh_b_direct[kTileSide * kTileSide];  // SH b, the direct part
ivec2 g_tile_origin;  // gather pixel of tile texel (0, 0)
int g_tile_w;

bool sh_finite(vec4 r, vec4 gg, vec4 b, vec3 d) { return gib_finite(r) && gib_finite(gg) && gib_finite(b) && gib_finite(d); }

uvec2 pack4(vec4 v) { return uvec2(packHalf2x16(v.xy), packHalf2x16(v.zw)); }
vec4 unpack4(uvec2 u) { return vec4(unpackHalf2x16(u.x), unpackHalf2x16(u.y)); }

// Gather pixel g's full-res pixel (final_gather's convention).
ivec2 gather_source(ivec2 g) {
  int div = int(push.divisor);
  return min(g * div + div / 2, imageSize(gb_position) - 1);
}

int tile_index(ivec2 g) {
  ivec2 t = clamp(g - g_tile_origin, ivec2(0), ivec2(g_tile_w - 1));
  return t.y * g_tile_w + t.x;
}

// The gather pixel of the first bilinear tap of full-res pixel p, and p's bilinear fraction.
ivec2 first_tap(ivec2 p, out vec2 f) {
  int div = int(push.divisor);
  vec2 xg = (vec2(p) - float(div / 2)) / float(div);
  ivec2 g0 = ivec2(floor(xg));
  f = xg - vec2(g0);
  return g0;
}

// Loads the group's tile: the gather pixels from one before the group's first tap to two after
// its last (the fallback's 4x4), clamped to the image as the taps are. Called by every thread,
// before any returns; ends with the group barrier.
void load_gather_tile() {
  ivec2 p0 = ivec2(gl_WorkGroupID.xy * kUpscaleGroup);
  vec2 f;
  ivec2 lo = first_tap(p0, f) - 1, hi = first_tap(p0 + int(kUpscaleGroup) - 1, f) + 2;
  g_tile_origin = lo;
  g_tile_w = min(hi.x - lo.x + 1, int(kTileSide));
  int tile_h = min(hi.y - lo.y + 1, int(kTileSide));
  ivec2 gsize = imageSize(sh_r);
  for (int l = int(gl_LocalInvocationIndex); l < g_tile_w * tile_h; l += int(kUpscaleGroup * kUpscaleGroup)) {
    ivec2 g = clamp(lo + ivec2(l % g_tile_w, l / g_tile_w), ivec2(0), gsize - 1);
    ivec2 src = gather_source(g);
    s_gpos[l] = imageLoad(gb_position, src);
    vec4 r = imageLoad(sh_r, g), gg = imageLoad(sh_g, g), b = imageLoad(sh_b, g), d = imageLoad(gi_direct, g);
    // The normal's fourth half: whether this sample's SH and direct part are all finite, tested
    // here once instead of at every tap (tap_sh).
    s_gnormal[l] = pack4(vec4(imageLoad(gb_normal, src).xyz, sh_finite(r, gg, b, d.rgb) ? 1.0 : 0.0));
    s_sh_rg[l] = uvec4(pack4(r), pack4(gg));
    s_sh_b_direct[l] = uvec4(pack4(b), pack4(d));
  }
  barrier();
}

vec4 gather_position(ivec2 g) { return kTiled ? s_gpos[tile_index(g)] : imageLoad(gb_position, gather_source(g)); }
vec3 gather_normal(ivec2 g) { return (kTiled ? unpack4(s_gnormal[tile_index(g)]) : imageLoad(gb_normal, gather_source(g))).xyz; }

// How much gather sample g (a gather-res pixel) lies on the surface at x with normal n: normal
// agreement times distance from the plane; 0 when that gather pixel saw the sky.
float tap_similarity(ivec2 g, vec3 x, vec3 n, float dist) {
  vec4 gp = gather_position(g);
  if (gp.w == 0.0) return 0.0;
  vec3 gn = gather_normal(g);
  float s = pow(max(0.0, dot(n, gn)), kUpscaleNormalPower) * exp(-abs(dot(n, gp.xyz - x)) / (dist * kUpscaleDepthSigma));
  // Guard: a tap with a non-finite similarity (NaN normal) is not on any surface. (Its SH are
  // checked where they are loaded anyway: loading them here too cost gi_upscale +27% on an H100.)
  if (push.nan_guards != 0u && !gib_finite(s)) return 0.0;
  return s;
}

// Gather sample g's SH (r, g, b) and direct part; false when the guards are on and one is not
// finite (such a tap is not on any surface).
bool tap_sh(ivec2 g, out vec4 r, out vec4 gg, out vec4 b, out vec3 d) {
  if (kTiled) {
    int t = tile_index(g);
    uvec4 rg = s_sh_rg[t], bd = s_sh_b_direct[t];
    r = unpack4(rg.xy);
    gg = unpack4(rg.zw);
    b = unpack4(bd.xy);
    d = unpack4(bd.zw).rgb;
    return push.nan_guards == 0u || unpack4(s_gnormal[t]).w != 0.0;  // sh_finite, tested at the load
  }
  r = imageLoad(sh_r, g);
  gg = imageLoad(sh_g, g);
  b = imageLoad(sh_b, g);
  d = imageLoad(gi_direct, g).rgb;
  return push.nan_guards == 0u || sh_finite(r, gg, b, d);
}

// 4-tap bilateral upscale of the denoised gather SH, evaluated with the full-res normal, and of
// the direct part with the same weights (it is irradiance / pi at the gather normals already).
// Returns false when no gather sample around p lies on p's surface.
bool upscale(ivec2 p, vec3 x, vec3 n, float dist, out vec3 irradiance, out vec3 direct) {
  irradiance = vec3(0.0);
  direct = vec3(0.0);
  vec3 acc_d = vec3(0.0);
  ivec2 gsize = imageSize(sh_r);
  vec2 f;
  ivec2 g0 = first_tap(p, f);
  vec4 acc_r = vec4(0.0), acc_g = vec4(0.0), acc_b = vec4(0.0);
  float acc_w = 0.0, best = 0.0;
  ivec2 best_g = ivec2(-1);
  for (int i = 0; i < 4; ++i) {
    ivec2 o = ivec2(i & 1, i >> 1);
    ivec2 g = clamp(g0 + o, ivec2(0), gsize - 1);
    float similar = tap_similarity(g, x, n, dist);
    if (push.nan_guards != 0u && similar == 0.0) continue;  // 0 x NaN would still be NaN
    vec4 r, gg, b;
    vec3 d;
    if (!tap_sh(g, r, gg, b, d)) continue;
    if (similar > best) {
      best = similar;
      best_g = g;
    }
    float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y) * similar;
    acc_r += w * r;
    acc_g += w * gg;
    acc_b += w * b;
    acc_d += w * d;
    acc_w += w;
  }
  if (acc_w > 1e-4) {
    acc_r /= acc_w;
    acc_g /= acc_w;
    acc_b /= acc_w;
    acc_d /= acc_w;
  } else {
    // The bilinear weight sits on other surfaces: take the most similar of the 4 taps, or on
    // thin silhouettes, where none of them lies on this surface (their gather pixels saw the
    // sky or another object), the most similar sample of the surrounding 4x4.
    if (best <= 1e-3)
      for (int j = -1; j <= 2; ++j)
        for (int i = -1; i <= 2; ++i) {
          ivec2 g = clamp(g0 + ivec2(i, j), ivec2(0), gsize - 1);
          float similar = tap_similarity(g, x, n, dist);
          if (similar > best) {
            best = similar;
            best_g = g;
          }
        }
    if (best <= 1e-3 || !tap_sh(best_g, acc_r, acc_g, acc_b, acc_d)) return false;
  }
  vec3 e = vec3(gib_sh2_irradiance(acc_r, n), gib_sh2_irradiance(acc_g, n), gib_sh2_irradiance(acc_b, n));
  if (push.nan_guards != 0u && !gib_finite(e)) return false;
  irradiance = gib_max0_keep_nan(e);  // gib_sh2_irradiance returns irradiance / pi
  direct = gib_max0_keep_nan(acc_d);
  return true;
}

// One of the 4 last-frame texels around a reprojection: its G-buffer sample and history.
struct PrevTap {
  vec4 position;
  vec3 normal, history, history_direct;
  float frames;
};

// Last frame's history at x: bilinear over the 4 texels around its reprojection, each kept
// only if it passes the disocclusion tests. Returns false when none does or x was off screen.
// The 4 texels' loads are all issued before any test (clamped to the image; a texel outside it
// is still skipped): tap by tap, each tap's history waited for its position and normal and the
// tests on them, and the reprojection was 42% of the pass (0.054 of 0.130 ms on an H100 at
// 1600x900); issued together, the pass reads 0.107 ms. The same values meet the same arithmetic.
bool reproject(vec3 x, vec3 n, out vec3 prev, out vec3 prev_direct, out float frames) {
  prev = vec3(0.0);
  prev_direct = vec3(0.0);
  frames = 0.0;
  if (push.history_valid == 0u) return false;
  vec4 clip = gib_frame.prev_view_proj * vec4(x, 1.0);
  if (clip.w <= 0.0) return false;
  vec2 ndc = clip.xy / clip.w;
  if (any(greaterThan(abs(ndc), vec2(1.0)))) return false;
  ivec2 full = imageSize(prev_position);
  vec2 px = (ndc * 0.5 + 0.5) * vec2(full) - 0.5;  // texel centres at integers
  ivec2 q0 = ivec2(floor(px));
  vec2 f = px - vec2(q0);
  vec3 sum = vec3(0.0), sum_d = vec3(0.0);
  float sum_n = 0.0, sum_w = 0.0;
  PrevTap taps[4];
  for (int i = 0; i < 4; ++i) {
    ivec2 q = clamp(q0 + ivec2(i & 1, i >> 1), ivec2(0), full - 1);
    taps[i] = PrevTap(imageLoad(prev_position, q), imageLoad(prev_normal, q).xyz, load_history(q),
                      load_history_direct(q), imageLoad(prev_frames, q).x);
  }
  for (int i = 0; i < 4; ++i) {
    ivec2 o = ivec2(i & 1, i >> 1);
    ivec2 q = q0 + o;
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, full))) continue;
    float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
    if (w <= 0.0) continue;
    if (push.disocclusion != 0u) {
      vec4 qp = taps[i].position;
      if (qp.w == 0.0) continue;
      vec3 qn = taps[i].normal;
      if (abs(dot(qn, x - qp.xyz)) > kUpscaleDepthTolerance * clip.w) continue;
      if (dot(n, qn) < kUpscaleNormalCos) continue;
      if (push.nan_guards != 0u && !gib_finite(qn)) continue;  // the NaN compares above pass
    }
    vec3 h = taps[i].history, hd = taps[i].history_direct;
    float hn = taps[i].frames;
    // Guard: a non-finite history texel is dropped (formats 1-3 can hold NaN and Inf; RGB9E5
    // cannot: its decode is always finite, so only n is tested).
#if GI_HISTORY_FORMAT == 0
    if (push.nan_guards != 0u && !gib_finite(hn)) continue;
#else
    if (push.nan_guards != 0u && !(gib_finite(h) && gib_finite(hd) && gib_finite(hn))) continue;
#endif
    sum += w * h;
    sum_d += w * hd;
    sum_n += w * hn;
    sum_w += w;
  }
  if (sum_w < 1e-2) return false;
  // Last frame's history was stored x P_prev: bring it to this frame's P_now.
  float rescale = exposure[kUpscaleExposureNow] / exposure[kUpscaleExposurePrev];
  prev = sum / sum_w * rescale;
  prev_direct = sum_d / sum_w * rescale;
  frames = sum_n / sum_w;
  return true;
}

void main() {
  if (kTiled) load_gather_tile();
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(out_frames)))) return;
  vec4 pos = imageLoad(gb_position, p);
  if (pos.w == 0.0) {  // sky
    write_out(p, vec3(0.0), vec3(0.0), 0.0);
    return;
  }
  vec3 n = normalize(imageLoad(gb_normal, p).xyz);
  vec3 curr = vec3(0.0), curr_d = vec3(0.0), prev, prev_d;
  float frames;
  // Guard: no upscale around a broken (non-finite) normal; the pixel keeps its history.
  bool have_curr = (push.nan_guards == 0u || gib_finite(n)) && upscale(p, pos.xyz, n, pos.w, curr, curr_d);
  bool have_prev = reproject(pos.xyz, n, prev, prev_d, frames);
  if (!have_prev) frames = 0.0;  // rejected: restart the average
  if (!have_curr) {
    write_out(p, prev, prev_d, frames);  // nothing new here this frame: keep what history says
    return;
  }
  // New = (n Prev + Curr) / (n + 1), n = min(n + 1, n_max)  [Mattauch 2010], both parts alike.
  write_out(p, (frames * prev + curr) / (frames + 1.0), (frames * prev_d + curr_d) / (frames + 1.0),
            min(frames + 1.0, push.max_frames));
}
