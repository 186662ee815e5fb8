// Screen-space marching shared by ssdo and ssgi (gow_ragnarok.md, "SSDO and SSGI"); the
// sampling pattern is gow_ss_pattern.glsl.
// The includer includes frame.glsl, hash.glsl, sampling.glsl and binds gb_position (rgba32f).
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
float gow_ss_surface_distance(vec3 q, vec3 hp, vec3 hn) {
  vec3 cam = gib_frame.camera_pos.xyz;
  vec3 v = normalize(q - cam);
  float c = dot(v, hn);
  float own = length(hp - cam);
  if (!(abs(c) > 0.05)) return own;
  float t = dot(hp - cam, hn) / c;
  return t > 0.0 ? t : own;
}

// Marches from x along d to `radius` in `steps` equal steps (the first at `jitter` of a step):
// returns the pixel of the first depth-buffer surface in front of the march point by at most
// `thickness` (a blocker), or ivec2(-1) where the march leaves the screen or finds none.
// The includer binds gb_normal (rgba16f) too.
ivec2 gow_ss_march(vec3 x, vec3 d, float radius, uint steps, float thickness, float jitter) {
  ivec2 size = ivec2(gib_render_size());
  vec3 cam = gib_frame.camera_pos.xyz;
  for (uint s = 0u; s < steps; ++s) {
    float t = radius * (float(s) + jitter) / float(steps);
    vec3 q = x + d * t;
    vec3 sp = gow_ss_project(q);
    if (sp.z <= 0.0) return ivec2(-1);
    ivec2 h = ivec2(floor(sp.xy));
    if (any(lessThan(h, ivec2(0))) || any(greaterThanEqual(h, size))) return ivec2(-1);
    vec4 hp = imageLoad(gb_position, h);
    if (hp.w == 0.0) continue;  // sky: nothing in front of the march point
    float dq = length(q - cam);
    // In front by more than a relative epsilon (the surface the march starts on is never its
    // own blocker), and by less than the thickness.
    float gap = dq - gow_ss_surface_distance(q, hp.xyz, imageLoad(gb_normal, h).xyz);
    if (gap > 1e-3 * dq && gap < thickness) return h;
  }
  return ivec2(-1);
}

#endif
