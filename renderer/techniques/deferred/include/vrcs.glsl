// Variable-rate compute shading: where a pixel's result comes from. Needs `vbuffer` (rg32ui)
// and a readonly buffer `vrcs_rate_words` holding buffer vrcs_rates (deferred_shared.h).
#ifndef GIB_VRCS_GLSL
#define GIB_VRCS_GLSL

// The luminance the rate compares, tone-mapped l = L / (1 + L): steps between bright pixels
// count less, as they do to the eye after tone mapping. NaN or Inf give NaN: never alike.
float gib_vrcs_luma(vec3 c) {
  float l = max(dot(c, vec3(0.2126, 0.7152, 0.0722)), 0.0);
  return l / (1.0 + l);
}

uint gib_vrcs_rate(ivec2 p, uint rate_tiles_x) {
  uint t = uint(p.x) / kVrcsTile + uint(p.y) / kVrcsTile * rate_tiles_x;
  return vrcs_rate_words[kVrcsHeader + t];
}
// The anchor of p's coarse cell and the cell size.
ivec2 gib_vrcs_anchor(ivec2 p, uint rate, out ivec2 size) {
  size = ivec2((rate & kVrcsCoarseX) != 0u ? 2 : 1, (rate & kVrcsCoarseY) != 0u ? 2 : 1);
  return p - ivec2(p.x % size.x, p.y % size.y);
}
// True when q takes its result from anchor a: both geometry of the same instance. A pixel of
// another instance (an edge the rate missed) or off screen shades itself.
bool gib_vrcs_follows(ivec2 q, ivec2 a, ivec2 size_px) {
  if (any(greaterThanEqual(q, size_px)) || q == a) return false;
  uvec2 iq = imageLoad(vbuffer, q).xy, ia = imageLoad(vbuffer, a).xy;
  return iq.x != kVisibilityNone && ia.x != kVisibilityNone && iq.y == ia.y;
}

// Adds this invocation's shaded / covered pixel counts to the statistics words: one atomic per
// subgroup where subgroup arithmetic is compiled in (GIB_VRCS_SUBGROUP_COUNT), else per
// invocation (a hot address: on a CPU device per-invocation atomics cost more than the texturing
// they count). Call from converged control flow of the invocations that shade.
void gib_vrcs_count(uint word, uint shaded, uint of) {
#ifdef GIB_VRCS_SUBGROUP_COUNT
  uint s = subgroupAdd(shaded), o = subgroupAdd(of);
  if (subgroupElect()) {
    atomicAdd(vrcs_rate_words[word], s);
    atomicAdd(vrcs_rate_words[word + 1u], o);
  }
#else
  atomicAdd(vrcs_rate_words[word], shaded);
  atomicAdd(vrcs_rate_words[word + 1u], of);
#endif
}
#endif
