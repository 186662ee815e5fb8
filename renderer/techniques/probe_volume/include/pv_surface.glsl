// The G-buffer surface under a ray pixel (its source pixel, pv_pixel.glsl), for the per-pixel
// filters (pixel_denoise, pixel_upscale): images gb_position, gb_normal, gb_emissive must be
// declared by the includer.
#ifndef GIB_PV_SURFACE_GLSL
#define GIB_PV_SURFACE_GLSL

struct PvSurface {
  vec3 position;
  vec3 normal;
  float depth;        // distance to the camera (0: sky)
  bool translucent;   // the material-ID class of the seed's denoiser mask
};

PvSurface pv_surface_at(ivec2 p) {
  PvSurface s;
  vec4 pos = imageLoad(gb_position, p);
  s.position = pos.xyz;
  s.depth = pos.w;
  vec3 n = imageLoad(gb_normal, p).xyz;
  s.normal = gib_finite(n) && dot(n, n) > 0.25 ? normalize(n) : vec3(0.0);
  s.translucent = imageLoad(gb_emissive, p).w > 0.0;
  return s;
}

// Bilateral weight of surface b for filtering at surface a: same plane (distance along a's
// normal within 2% of the depth), similar normal (cos^8), and (material_mask) the same class.
float pv_bilateral(PvSurface a, PvSurface b) {
  if (b.depth == 0.0) return 0.0;
  if (pv_flag(kPvFlagMaterialMask) && a.translucent != b.translucent) return 0.0;
  float plane = abs(dot(b.position - a.position, a.normal)) / (0.02 * a.depth);
  float wn = max(dot(a.normal, b.normal), 0.0);
  wn *= wn;
  wn *= wn;
  return max(0.0, 1.0 - plane) * wn * wn;
}

#endif  // GIB_PV_SURFACE_GLSL
