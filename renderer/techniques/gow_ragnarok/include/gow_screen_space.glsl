// Screen-space marching shared by ssdo and ssgi (gow_ragnarok.md, "SSDO and SSGI"); the
// sampling pattern is gow_ss_pattern.glsl.
// The includer includes frame.glsl, hash.glsl, sampling.glsl, finite.glsl and binds gb_position
// (rgba32f) and gb_normal (rgba16f).
#ifndef GOW_SCREEN_SPACE_GLSL
#define GOW_SCREEN_SPACE_GLSL

#include "renderer/techniques/gow_ragnarok/include/gow_ss_pattern.glsl"

// Pixel position (x, y) and view depth (clip w) of a world point, camera-relative so a scene
// far from the origin projects as precisely as one at it (the camera's clip x, y, w are 0).
vec3 gow_ss_project(vec3 x) {
  vec4 c = gib_frame.view_proj * vec4(x - gib_frame.camera_pos.xyz, 0.0);
  vec2 ndc = c.xy / c.w;
  return vec3((ndc * 0.5 + 0.5) * vec2(gib_render_size()), c.w);
}

// Distance from the camera to the surface pixel h shows, along the camera's ray towards q: the
// pixel's plane (its G-buffer position and normal) cut by that ray, so a pixel's depth is read
// where q projects inside it, not at its centre (no false blockers on surfaces seen at grazing
// angles). A broken normal or a ray along the plane falls back to the pixel's own distance.
// Camera-relative form: v the unit ray towards q, h_rel the pixel's position less the camera's,
// own its length.
float gow_ss_plane_distance(vec3 v, vec3 h_rel, float own, vec3 hn) {
  float c = dot(v, hn);
  if (!(abs(c) > 0.05)) return own;
  float t = dot(h_rel, hn) / c;
  return t > 0.0 ? t : own;
}

float gow_ss_surface_distance(vec3 q, vec3 hp, vec3 hn) {
  vec3 cam = gib_frame.camera_pos.xyz;
  return gow_ss_plane_distance(normalize(q - cam), hp - cam, length(hp - cam), hn);
}

// The depth-buffer surface at march point q: sets h to the pixel q projects to and returns how
// far that pixel's surface lies in front of q along the camera ray (gow_ss_surface_distance),
// or a negative value where nothing can block there (off screen: `off` set; behind the camera:
// `off` set; sky). The includer binds gb_normal (rgba16f) too.
float gow_ss_gap(vec3 q, out ivec2 h, out bool off) {
  ivec2 size = ivec2(gib_render_size());
  vec3 sp = gow_ss_project(q);
  h = ivec2(floor(sp.xy));
  off = sp.z <= 0.0 || any(lessThan(h, ivec2(0))) || any(greaterThanEqual(h, size));
  if (off) return -1.0;
  vec4 hp = imageLoad(gb_position, h);
  if (hp.w == 0.0) return -1.0;  // sky: nothing in front of the march point
  float dq = length(q - gib_frame.camera_pos.xyz);
  float gap = dq - gow_ss_surface_distance(q, hp.xyz, imageLoad(gb_normal, h).xyz);
  // In front by more than a relative epsilon (the surface the march starts on is never its own
  // blocker).
  return gap > 1e-3 * dq ? gap : -1.0;
}

// Marches from x along d to `radius` in `steps` equal steps (the first at `jitter` of a step):
// returns the pixel of the first depth-buffer surface in front of the march point by at most
// `thickness` (a blocker), or ivec2(-1) where the march leaves the screen or finds none.
ivec2 gow_ss_march(vec3 x, vec3 d, float radius, uint steps, float thickness, float jitter) {
  for (uint s = 0u; s < steps; ++s) {
    ivec2 h;
    bool off;
    float gap = gow_ss_gap(x + d * (radius * (float(s) + jitter) / float(steps)), h, off);
    if (off) return ivec2(-1);
    if (gap > 0.0 && gap < thickness) return h;
  }
  return ivec2(-1);
}

// The G-buffer normal at p, unit; a broken one (NaN texel) faces the camera when `guard` is set
// (as direct_lighting's guard), else it stays and poisons the output, as the lighting's would.
vec3 gow_ss_normal(ivec2 p, bool guard) {
  vec3 n = imageLoad(gb_normal, p).xyz;
  if (guard && !(gib_finite(n) && dot(n, n) > 0.25)) {
    vec3 o, d;
    gib_camera_ray(vec2(p) + 0.5, o, d);
    n = -d;
  }
  return normalize(n);
}

// Visibility towards wi from the marched directions `known` (bit i: direction i of `dirs`, turned
// by `turn` around n): their open (1) / blocked (0) results weighted by a lobe around wi,
// exp((cos - 1) / kSsLobe) (0.03 at 45 degrees, 4e-6 at 90), so a light above a table top reads
// the blocked directions near it, not a mean of the hemisphere (a bent cone misreads such a ring
// of open directions round a blocked top). Where no direction is near wi (a light at the
// horizon), the open fraction.
const float kSsLobe = 0.08;
float gow_ss_visibility(uint open_bits, uint known, uint dirs, float turn, vec3 n, vec3 wi, float open_fraction) {
  float num = 0.0, den = 0.0;
  for (uint i = 0u; i < dirs; ++i) {
    if ((known & (1u << i)) == 0u) continue;
    float w = exp((dot(gow_ss_direction(i, dirs, turn, n), wi) - 1.0) / kSsLobe);
    den += w;
    if ((open_bits & (1u << i)) != 0u) num += w;
  }
  return den > 1e-3 ? num / den : open_fraction;
}

#endif
