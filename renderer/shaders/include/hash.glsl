// Deterministic random numbers: every sequence is seeded from (seed, frame, pixel, purpose).
#ifndef GIB_HASH_GLSL
#define GIB_HASH_GLSL
uint gib_pcg(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}
struct GibRng { uint state; };
GibRng gib_rng(uint seed, uint frame, uvec2 pixel, uint stream) {
  GibRng r;
  r.state = gib_pcg(seed ^ gib_pcg(frame ^ gib_pcg(pixel.x ^ gib_pcg(pixel.y ^ gib_pcg(stream)))));
  return r;
}
float gib_next(inout GibRng r) {
  r.state = r.state * 747796405u + 2891336453u;
  uint word = ((r.state >> ((r.state >> 28u) + 4u)) ^ r.state) * 277803737u;
  word = (word >> 22u) ^ word;
  return float(word >> 8) * (1.0 / 16777216.0);  // [0, 1)
}
vec2 gib_next2(inout GibRng r) { return vec2(gib_next(r), gib_next(r)); }
#endif
