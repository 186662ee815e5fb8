// The sampling pattern of gow-ragnarok's screen-space passes (ssdo, ssgi) and the encoding of
// ssdo_ssgi's half-resolution surfaces, without frame or image dependencies so
// tests/gow_ss_test.comp runs them as is. CPU mirror: screen_space_pattern.h.
// The includer includes hash.glsl and sampling.glsl.
#ifndef GOW_SS_PATTERN_GLSL
#define GOW_SS_PATTERN_GLSL
#include "finite.glsl"
#include "octahedral.glsl"
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
// Its coordinates in the normal's frame (gib_onb's t, b, then the normal), unit up to rounding:
// a pass that turns one set into many pixels' frames computes these once.
vec3 gow_ss_local_direction(uint i, uint n, float rotation) {
  float u = (float(i) + 0.5) / float(n);
  float r = sqrt(u);
  float phi = float(i) * kGoldenAngle + 2.0 * GIB_PI * rotation;
  return vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0, 1.0 - u)));
}

vec3 gow_ss_direction(uint i, uint n, float rotation, vec3 normal) {
  vec3 l = gow_ss_local_direction(i, n, rotation);
  vec3 t, b;
  gib_onb(normal, t, b);
  return normalize(t * l.x + b * l.y + normal * l.z);
}

// One texel of ssdo_ssgi's half-resolution surfaces (rg32ui), the surface the march's depth
// tests read for a 2x2 pixel block: one of its pixels. x: the distance from the camera to that
// pixel's G-buffer position (0: no surface, sky; the sign bit set: its normal is unusable, NaN
// or zero, so only the distance serves); y: its normal, octahedral, 15 bits per axis (bits 2-16
// and 17-31), and which pixel of the block it is (bits 0-1: x + 2 y).
struct GowSsSurface {
  float dist;   // >= 0; 0: no surface
  bool plane;   // the normal is usable
  vec3 normal;  // unit where `plane`
  uint pixel;   // 0..3: the block's pixel (x + 2 y)
};

uvec2 gow_ss_pack_surface(float dist, vec3 n, uint pixel) {
  bool plane = gib_finite(n) && dot(n, n) > 0.25;
  uvec2 q = uvec2(floor(clamp(gib_oct_encode(plane ? n : vec3(0.0, 0.0, 1.0)), 0.0, 1.0) * 32767.0 + 0.5));
  uint bits = floatBitsToUint(abs(dist)) | (plane ? 0u : 0x80000000u);
  return uvec2(bits, (pixel & 3u) | (q.x << 2u) | (q.y << 17u));
}

GowSsSurface gow_ss_unpack_surface(uvec2 t) {
  GowSsSurface s;
  s.dist = uintBitsToFloat(t.x & 0x7fffffffu);
  s.plane = (t.x & 0x80000000u) == 0u;
  s.normal = gib_oct_decode(vec2((t.y >> 2u) & 0x7fffu, t.y >> 17u) / 32767.0);
  s.pixel = t.y & 3u;
  return s;
}

#endif
