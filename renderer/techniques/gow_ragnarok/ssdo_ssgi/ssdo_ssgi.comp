// ssdo_ssgi, second dispatch: SSDO and SSGI in one pass, one march per direction serving both
// (see ssdo_ssgi.h); the marches' depth tests read the blocks' surfaces (ss_surfaces, written
// by ssdo_ssgi_surfaces.comp).
#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/gow_ragnarok/ssdo_ssgi/ssdo_ssgi_shared.h"
#include "frame.glsl"
#include "scene.glsl"
GIB_SCENE_BUFFERS(0, kBindSceneFirst)
#include "hash.glsl"
#include "sampling.glsl"
#include "lights.glsl"
#include "finite.glsl"
layout(constant_id = kSsCombinedSpecLocal) const bool kHasLocal = true;
layout(constant_id = kSsCombinedSpecDirections) const uint kDirections = kSsMaxDirections;
layout(constant_id = kSsCombinedSpecCone) const bool kWriteCone = false;
layout(local_size_x = kSsGroup, local_size_y = kSsGroup) in;
layout(set = 0, binding = kSsCombinedBindPosition, rgba32f) uniform readonly image2D gb_position;
layout(set = 0, binding = kSsCombinedBindNormal, rgba16f) uniform readonly image2D gb_normal;
layout(set = 0, binding = kSsCombinedBindAlbedo, rgba16f) uniform readonly image2D gb_albedo;
layout(set = 0, binding = kSsCombinedBindEmissive, rgba16f) uniform readonly image2D gb_emissive;
layout(set = 0, binding = kSsCombinedBindDirect, rgba32f) uniform readonly image2D direct_light;
layout(set = 0, binding = kSsCombinedBindLocalPrev, rgba16f) uniform readonly image2D local_prev;
layout(set = 0, binding = kSsCombinedBindLocal, rgba16f) uniform writeonly image2D out_local;
layout(set = 0, binding = kSsCombinedBindCone, rgba16f) uniform writeonly image2D out_cone;
layout(set = 0, binding = kSsCombinedBindOutIndirect, rgba16f) uniform writeonly image2D out_indirect;
layout(set = 0, binding = kSsCombinedBindOutRadiance, rgba32f) uniform writeonly image2D out_radiance;
layout(set = 0, binding = kSsCombinedBindIndirectPrev, rgba16f) uniform readonly image2D indirect_prev;
layout(set = 0, binding = kSsCombinedBindSurfaces, rg32ui) uniform readonly uimage2D surfaces;
layout(push_constant) uniform Push { SsCombinedPush push; };
#include "renderer/techniques/gow_ragnarok/include/gow_screen_space.glsl"

// A 2x2 quad of threads (4x4 pixels) shares one turned direction set; thread qi of the quad
// marches directions qi, qi + 4, ... from its block's pixel. Each pixel then takes the results
// of the quad's threads whose pixel lies on its own surface (normals within kNormalAgree, the
// thread's point within kPlaneAgree x the view distance of the pixel's plane).
const float kNormalAgree = 0.9;
const float kPlaneAgree = 0.02;
shared vec4 s_pos[kSsGroup][kSsGroup];     // the thread's pixel's position; w: 1 a surface, 0 none
shared vec3 s_normal[kSsGroup][kSsGroup];
shared uvec2 s_bits[kSsGroup][kSsGroup];   // x: open directions (SSDO), y: marched directions
shared vec3 s_gather[kSsGroup][kSsGroup];  // sum of the bounce light its hits gave (SSGI)
// Each quad's directions in the frame of a normal (gow_ss_local_direction), written by the thread
// that marched each: a pixel turns them into its own frame with three multiply-adds, no trig.
shared vec3 s_local[kSsGroup / 2][kSsGroup / 2][kDirections];

bool ssdo_on() { return (push.counts.z & 1u) != 0u; }
bool ssgi_on() { return (push.counts.z & 2u) != 0u; }

// Light leaving pixel h after one bounce: its direct light (last frame's SSDO-lit local lights
// included: this frame's are being computed) without its own emission.
vec3 bounce_at(ivec2 h) {
  vec3 lit = imageLoad(direct_light, h).rgb;
  if (kHasLocal && push.frame.x != 0u) lit += imageLoad(local_prev, h).rgb;
  return max(lit - imageLoad(gb_emissive, h).rgb, vec3(0.0));
}

// The depth-buffer surface at march point q, as gow_ss_gap (gow_screen_space.glsl) finds it, but
// read from the half-size surfaces: the block q projects to stands for its four pixels with the
// one pixel its texel holds (h set to that pixel, hn to its normal; vec3(0) where the normal is
// unusable, which then faces nothing). One 8-byte load per test, from an image a sixteenth the
// size of gbuffer_position + gbuffer_normal, in place of those two loads.
float surface_gap(vec3 q, out ivec2 h, out vec3 hn, out bool off) {
  ivec2 size = ivec2(gib_render_size());
  vec3 sp = gow_ss_project(q);
  ivec2 px = ivec2(floor(sp.xy));
  off = sp.z <= 0.0 || any(lessThan(px, ivec2(0))) || any(greaterThanEqual(px, size));
  hn = vec3(0.0);
  h = px;
  if (off) return -1.0;
  GowSsSurface sf = gow_ss_unpack_surface(imageLoad(surfaces, px >> 1).xy);
  if (sf.dist == 0.0) return -1.0;  // sky: nothing in front of the march point
  h = (px & ~1) + ivec2(sf.pixel & 1u, sf.pixel >> 1u);
  vec3 rel = q - gib_frame.camera_pos.xyz;
  float dq = length(rel);
  float d = sf.dist;
  if (sf.plane) {
    vec3 o, vh;
    gib_camera_ray(vec2(h) + 0.5, o, vh);
    d = gow_ss_plane_distance(rel / dq, vh * sf.dist, sf.dist, sf.normal);
    hn = sf.normal;
  }
  float gap = dq - d;
  // In front by more than a relative epsilon (the surface the march starts on is never its own
  // blocker).
  return gap > 1e-3 * dq ? gap : -1.0;
}

// One march along d from x serving both terms, steps of push.radius.z: SSDO's blocker (a
// surface in front by less than its thickness within its radius) and SSGI's hit (the same with
// its own thickness and radius; hn its normal); each as the separate passes' gow_ss_march
// would find it.
void march(vec3 x, vec3 d, float jitter, out bool blocked, out ivec2 hit, out vec3 hit_normal) {
  blocked = false;
  hit = ivec2(-1);
  hit_normal = vec3(0.0);
  bool want_ssdo = ssdo_on(), want_ssgi = ssgi_on();
  for (uint s = 0u; s < push.counts.y; ++s) {
    float t = push.radius.z * (float(s) + jitter);
    want_ssdo = want_ssdo && t < push.radius.x;
    want_ssgi = want_ssgi && t < push.radius.y;
    if (!(want_ssdo || want_ssgi)) return;
    ivec2 h;
    vec3 hn;
    bool off;
    float gap = surface_gap(x + d * t, h, hn, off);
    if (off) return;
    if (gap <= 0.0) continue;
    if (want_ssdo && gap < push.thickness.x) {
      blocked = true;
      want_ssdo = false;
    }
    if (want_ssgi && gap < push.thickness.y) {
      hit = h;
      hit_normal = hn;
      want_ssgi = false;
    }
  }
}

// Temporal accumulation: this frame's estimate averaged with the history at the pixel's
// position in last frame's image (prev_view_proj), over at most push.frame.y frames; the count
// rides in ssgi_indirect's alpha. A history that is off screen, from no frame, or not finite
// (nan_guards) restarts at this frame.
void accumulate(vec3 x, inout vec3 local, inout vec3 indirect, out float count) {
  vec4 prev_local = vec4(0.0), prev_indirect = vec4(0.0);
  if (push.frame.x != 0u) {
    vec4 c = gib_frame.prev_view_proj * vec4(x, 1.0);
    ivec2 size = imageSize(indirect_prev);
    vec2 f = (c.xy / c.w * 0.5 + 0.5) * vec2(size);
    if (c.w > 0.0 && all(greaterThanEqual(f, vec2(0.0))) && all(lessThan(f, vec2(size)))) {
      prev_indirect = imageLoad(indirect_prev, ivec2(f));
      if (kHasLocal) prev_local = imageLoad(local_prev, ivec2(f));
    }
  }
  if (push.counts.w != 0u && !(gib_finite(prev_indirect) && gib_finite(prev_local.rgb))) prev_indirect = vec4(0.0);
  count = min(prev_indirect.a + 1.0, float(push.frame.y));
  local = mix(prev_local.rgb, local, 1.0 / count);
  indirect = mix(prev_indirect.rgb, indirect, 1.0 / count);
}

// A history texel as the RGBA16F image keeps it: clamped to the half's largest value (a NaN
// kept for the guards to see), rounded to nearest even by packHalf2x16 (lavapipe and NVIDIA), so
// every device stores it exactly and this frame's outputs add what the history holds.
vec3 history_value(vec3 v) {
  v = gib_clamp_keep_nan(vec4(v, 0.0), -65504.0, 65504.0).rgb;
  return vec3(unpackHalf2x16(packHalf2x16(v.rg)), unpackHalf2x16(packHalf2x16(vec2(v.b, 0.0))).x);
}

// The unshadowed local lights through SSDO's visibility, as gow_ss_local_light
// (gow_ss_lights.glsl) computes them, with the quad's directions from s_local in the pixel's
// frame (t, b, n): per light and direction one dot product and the lobe's exp.
vec3 local_light(vec3 x, vec3 n, vec3 t, vec3 b, vec3 albedo, uint open_bits, uint known, uvec2 q, float open_fraction) {
  vec3 result = vec3(0.0);
  for (uint k = 0u; k < gib_light_count(); ++k) {
    vec3 wi;
    float dist;
    vec3 e = gib_local_light(gib_lights[k], x, wi, dist);
    float c = dot(n, wi);
    if (c <= 0.0 || all(equal(e, vec3(0.0)))) continue;
    float vis = 1.0;
    if (open_fraction < 1.0) {
      vec3 wl = vec3(dot(t, wi), dot(b, wi), c);
      float num = 0.0, den = 0.0;
      for (uint bits = known; bits != 0u; bits &= bits - 1u) {
        uint i = uint(findLSB(bits));
        float w = exp((dot(s_local[q.y][q.x][i], wl) - 1.0) / kSsLobe);
        den += w;
        if ((open_bits & (1u << i)) != 0u) num += w;
      }
      vis = den > 1e-3 ? num / den : open_fraction;
    }
    result += albedo * (c / GIB_PI) * e * vis;
  }
  return result;
}

void main() {
  uvec2 lt = gl_LocalInvocationID.xy;
  ivec2 block = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(out_radiance);
  ivec2 origin = block * int(kSsCombinedBlock);
  uint frame = gib_frame_index();
  bool guard = push.counts.w != 0u;
  uint dirs = push.counts.x;
  // The block's marched pixel: ssdo_ssgi_surfaces chose it (the same hash stream, its first
  // number); the second is the march's first step.
  GibRng rng = gib_rng(gib_seed(), frame, uvec2(block), kSsCombinedStream);
  vec2 u = gib_next2(rng);  // x: start pixel (the surfaces pass's), y: the march's first step (in steps)
  float turn = gow_ss_rotation(gib_seed(), frame, uvec2(block) >> 1u, kSsCombinedStream + 1u).x;
  ivec2 rep = ivec2(-1);
  vec4 rpos = vec4(0.0);
  if (all(lessThan(origin, size))) {
    uvec2 own = imageLoad(surfaces, block).xy;
    if ((own.x & 0x7fffffffu) != 0u) {
      rep = origin + ivec2(own.y & 1u, (own.y >> 1u) & 1u);
      rpos = imageLoad(gb_position, rep);
    }
  }
  vec3 rn = vec3(0.0, 0.0, 1.0);
  uint open_bits = 0u, marched = 0u;
  vec3 gathered = vec3(0.0);
  if (rep.x >= 0) {
    rn = gow_ss_normal(rep, guard);
    vec3 rt, rb;
    gib_onb(rn, rt, rb);
    uint qi = (lt.x & 1u) | ((lt.y & 1u) << 1u);
    for (uint i = qi; i < dirs && (ssdo_on() || ssgi_on()); i += 4u) {
      vec3 l = gow_ss_local_direction(i, dirs, turn);
      s_local[lt.y >> 1u][lt.x >> 1u][i] = l;
      vec3 d = normalize(rt * l.x + rb * l.y + rn * l.z);  // gow_ss_direction(i, dirs, turn, rn)
      bool blocked;
      ivec2 hit;
      vec3 hit_normal;
      march(rpos.xyz, d, u.y, blocked, hit, hit_normal);
      marched |= 1u << i;
      if (!blocked) open_bits |= 1u << i;
      // Only the side of the hit that faces the receiver reflects towards it.
      if (hit.x >= 0 && dot(hit_normal, d) < 0.0) gathered += bounce_at(hit);
    }
  }
  s_pos[lt.y][lt.x] = vec4(rpos.xyz, rep.x >= 0 ? 1.0 : 0.0);
  s_normal[lt.y][lt.x] = rn;
  s_bits[lt.y][lt.x] = uvec2(open_bits, marched);
  s_gather[lt.y][lt.x] = gathered;
  barrier();

  uvec2 quad = lt & ~1u;
  vec3 cam = gib_frame.camera_pos.xyz;
  for (uint j = 0u; j < 4u; ++j) {
    ivec2 p = origin + ivec2(j & 1u, j >> 1u);
    if (any(greaterThanEqual(p, size))) continue;
    vec4 pos = p == rep ? rpos : imageLoad(gb_position, p);
    vec3 direct = imageLoad(direct_light, p).rgb;
    vec3 local = vec3(0.0), indirect = vec3(0.0);
    vec4 cone = vec4(0.0, 0.0, 0.0, 1.0);
    if (pos.w != 0.0) {
      vec3 n = p == rep ? rn : gow_ss_normal(p, guard);
      float view = length(pos.xyz - cam);
      // The quad's threads on this pixel's surface; none: its own block's (the pixel's block
      // has a surface, so its thread marched one).
      uint use = 0u;
      for (uint t = 0u; t < 4u; ++t) {
        uvec2 c = quad + uvec2(t & 1u, t >> 1u);
        vec4 tp = s_pos[c.y][c.x];
        if (tp.w != 0.0 && dot(n, s_normal[c.y][c.x]) > kNormalAgree &&
            abs(dot(tp.xyz - pos.xyz, n)) < kPlaneAgree * view)
          use |= 1u << t;
      }
      if (use == 0u) use = 1u << ((lt.x & 1u) | ((lt.y & 1u) << 1u));
      uint known = 0u, open_all = 0u;
      vec3 sum = vec3(0.0);
      for (uint t = 0u; t < 4u; ++t) {
        if ((use & (1u << t)) == 0u) continue;
        uvec2 c = quad + uvec2(t & 1u, t >> 1u);
        known |= s_bits[c.y][c.x].y;
        open_all |= s_bits[c.y][c.x].x;
        sum += s_gather[c.y][c.x];
      }
      float marched_count = float(bitCount(known));
      vec3 pt, pb;
      gib_onb(n, pt, pb);
      uvec2 q = lt >> 1u;
      cone = vec4(n, 1.0);
      if (ssdo_on() && known != 0u) {
        cone.w = float(bitCount(open_all)) / marched_count;
        if (kWriteCone) {
          // The mean open direction: the sum of the open directions, turned into n's frame once.
          vec3 open_sum = vec3(0.0);
          for (uint bits = open_all; bits != 0u; bits &= bits - 1u) open_sum += s_local[q.y][q.x][findLSB(bits)];
          vec3 bent = pt * open_sum.x + pb * open_sum.y + n * open_sum.z;
          if (dot(bent, bent) > 0.0) cone.xyz = normalize(bent);
        }
      }
      vec3 albedo = imageLoad(gb_albedo, p).rgb;
      if (kHasLocal) local = local_light(pos.xyz, n, pt, pb, albedo, open_all, known, q, cone.w);
      // Cosine-weighted directions: the Lambertian estimate is albedo x the mean radiance found.
      if (ssgi_on() && known != 0u) indirect = albedo * sum / marched_count;
    }
    float count = 0.0;
    if (pos.w != 0.0) accumulate(pos.xyz, local, indirect, count);
    local = history_value(local);
    indirect = history_value(indirect);
    if (kHasLocal) imageStore(out_local, p, vec4(local, 1.0));
    if (kHasLocal && kWriteCone) imageStore(out_cone, p, cone);
    imageStore(out_indirect, p, vec4(indirect, count));
    imageStore(out_radiance, p, vec4(direct + local + indirect, 1.0));
  }
}
