#ifndef GIB_SAMPLING_GLSL
#define GIB_SAMPLING_GLSL
const float GIB_PI = 3.14159265358979;

// Orthonormal basis around n (Duff et al. 2017, branchless).
void gib_onb(vec3 n, out vec3 t, out vec3 b) {
  float s = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (s + n.z);
  float c = n.x * n.y * a;
  t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
  b = vec3(c, s + n.y * n.y * a, -n.y);
}

// Cosine-weighted direction around n; pdf = cos / pi.
vec3 gib_cosine_hemisphere(vec3 n, vec2 u) {
  float r = sqrt(u.x), phi = 2.0 * GIB_PI * u.y;
  vec3 t, b;
  gib_onb(n, t, b);
  return normalize(t * (r * cos(phi)) + b * (r * sin(phi)) + n * sqrt(max(0.0, 1.0 - u.x)));
}

// Uniform direction in the cone around axis with cos(half angle) = cos_max; pdf = 1/(2 pi (1-cos_max)).
vec3 gib_uniform_cone(vec3 axis, float cos_max, vec2 u) {
  float cos_t = 1.0 - u.x * (1.0 - cos_max);
  float sin_t = sqrt(max(0.0, 1.0 - cos_t * cos_t));
  float phi = 2.0 * GIB_PI * u.y;
  vec3 t, b;
  gib_onb(axis, t, b);
  return normalize(t * (sin_t * cos(phi)) + b * (sin_t * sin(phi)) + axis * cos_t);
}

float gib_luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }
#endif
