// NaN guards (Settings::nan_guards, docs/architecture.md "Determinism and numerical stability"): finiteness tests on the
// float's bits. Integer compares, so a compiler that assumes no NaN/Inf in float arithmetic
// (fast-math style optimisations are allowed without the float-controls execution modes) cannot
// fold them away, unlike isnan()/isinf() or x == x.
//   bool gib_finite(float|vec2|vec3|vec4)  // no NaN and no +-Inf
//   float gib_nan()                         // a quiet NaN, for debug injection
//   bool gib_is_nan(float)
//   gib_max0_keep_nan(float|vec3), gib_clamp_keep_nan(float|vec4, lo, hi)
#ifndef GIB_FINITE_GLSL
#define GIB_FINITE_GLSL

bool gib_finite(float x) { return (floatBitsToUint(x) & 0x7f800000u) != 0x7f800000u; }
bool gib_finite(vec2 v) { return gib_finite(v.x) && gib_finite(v.y); }
bool gib_finite(vec3 v) { return gib_finite(v.x) && gib_finite(v.y) && gib_finite(v.z); }
bool gib_finite(vec4 v) { return gib_finite(v.xy) && gib_finite(v.zw); }

float gib_nan() { return uintBitsToFloat(0x7fc00000u); }
bool gib_is_nan(float x) { return (floatBitsToUint(x) & 0x7fffffffu) > 0x7f800000u; }

// max(x, 0) and clamp(x, lo, hi) that keep a NaN. GLSL leaves max/min/clamp undefined for a NaN
// operand; LLVM's maxnum (lavapipe) returns the other operand, so a plain max(x, 0) would hide
// a NaN as 0 on some devices and not on others. Value paths use these, so that what happens to
// a NaN is decided by the explicit guards (nan_guards), the same everywhere, and the guards'
// negative control (nan_guards 0) sees the NaN. Integer tests: no compiler may turn them back
// into fmax. -0 is kept.
float gib_max0_keep_nan(float x) {
  uint u = floatBitsToUint(x);
  return (u > 0x80000000u && u <= 0xff800000u) ? 0.0 : x;  // negative non-zero, -Inf -> 0
}
vec3 gib_max0_keep_nan(vec3 v) { return vec3(gib_max0_keep_nan(v.x), gib_max0_keep_nan(v.y), gib_max0_keep_nan(v.z)); }
float gib_clamp_keep_nan(float x, float lo, float hi) { return gib_is_nan(x) ? x : clamp(x, lo, hi); }
vec4 gib_clamp_keep_nan(vec4 v, float lo, float hi) {
  return vec4(gib_clamp_keep_nan(v.x, lo, hi), gib_clamp_keep_nan(v.y, lo, hi), gib_clamp_keep_nan(v.z, lo, hi),
              gib_clamp_keep_nan(v.w, lo, hi));
}

#endif  // GIB_FINITE_GLSL
