// The sampling pattern of gow-ragnarok's screen-space passes (ssdo, ssgi), without frame or
// image dependencies so tests/gow_ss_test.comp runs it as is. CPU mirror: screen_space_pattern.h.
// The includer includes hash.glsl and sampling.glsl.
#ifndef GOW_SS_PATTERN_GLSL
#define GOW_SS_PATTERN_GLSL
const float kGoldenAngle = 2.39996322972865332;  // pi (3 - sqrt 5)

// The pattern's turn for one pixel and frame (x, whole turns) and the march's first step (y, in
// steps): the first two numbers of the pass's stream, both in [0, 1).
vec2 gow_ss_rotation(uint seed, uint frame, uvec2 p, uint stream) {
  GibRng r = gib_rng(seed, frame, p, stream);
  return gib_next2(r);
}

// Direction i of n around the normal: cosine-weighted (equal-area rings of r^2 = (i + 0.5) / n
// on the unit disk, lifted to the hemisphere), spread by the golden angle and turned by
// `rotation` whole turns. Each direction stands for 1 / n of the cosine-weighted hemisphere.
vec3 gow_ss_direction(uint i, uint n, float rotation, vec3 normal) {
  float u = (float(i) + 0.5) / float(n);
  float r = sqrt(u);
  float phi = float(i) * kGoldenAngle + 2.0 * GIB_PI * rotation;
  vec3 t, b;
  gib_onb(normal, t, b);
  return normalize(t * (r * cos(phi)) + b * (r * sin(phi)) + normal * sqrt(max(0.0, 1.0 - u)));
}

#endif
