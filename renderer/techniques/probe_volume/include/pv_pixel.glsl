// Per-pixel diffuse rays of the probe-volume technique (AC Shadows RTGI, "Per-pixel diffuse
// algorithm", "Translucency: per-pixel indirect"), shared by world_trace, hit_lighting,
// pixel_denoise and pixel_upscale so that each rebuilds the same ray from the same seed (the
// seed keeps only the hit distance: "regenerate the ray direction using the same seed").
//
// Ray pixel q (1/pixel_divisor resolution) traces from the full-resolution pixel
// pv_source_pixel(q): one of its divisor x divisor block, rotating over frames. The direction is
// cosine-distributed about the normal of the side chosen: on a translucent surface the back
// side with probability t / (1 + t) (translucent_rays), whose result is weighted by t / p, the
// front's by (1 - t) / (1 - p), so that the sum estimates (1 - t) E_front + t E_back. Rays start
// pv_min_start() metres along the ray (option min_start, default 0; the seed's 0.05 m) from an
// offset origin and reach pixel_range x the probe trace range of the cascade around the origin.
//
// The irradiance a ray estimates, E = pi x L x weight, is kept as YCoCg with order 1 for Y: Y0 = E_Y
// and the band-1 vector D = E_Y x d', d' the ray direction (mirrored to the front side for a
// back-side ray: "flip backface direction for SH encoding"). It is evaluated for a normal n as
// Y(n) = max(0, Y0 + D . (n - n0)), n0 the normal the ray was traced about, with Co, Cg scaled by
// Y(n) / Y0: exact at n0 (so a flat surface gets the unbiased estimate) and tilting with the
// light's direction elsewhere (pv_eval_irradiance).
// Needs: frame.glsl, hash.glsl, ycocg_sh.glsl, pv_common.glsl; for pv_pixel_ray also surface.glsl
// and sampling.glsl, included first.
#ifndef GIB_PV_PIXEL_GLSL
#define GIB_PV_PIXEL_GLSL

float pv_min_start() { return pv.pixel.x; }

uint pv_divisor() { return pv.flags.z; }

ivec2 pv_source_pixel(ivec2 q) {
  uint div = pv_divisor();
  if (div == 1u) return q;
  uint k = (pv_frame() + uint(q.x) * 3u + uint(q.y) * 5u) & 3u;
  ivec2 p = q * 2 + ivec2(k & 1u, k >> 1u);
  return min(p, ivec2(gib_render_size()) - 1);
}

#ifdef GIB_SURFACE_GLSL  // and sampling.glsl: the ray itself
struct PvPixelRay {
  vec3 origin;
  vec3 dir;
  vec3 encode_dir;  // mirrored to the front for a back-side ray
  float weight;     // side weight ((1 - t) / (1 - p) or t / p)
  bool back;
};

// n: the G-buffer normal (facing the camera), t: translucency.
PvPixelRay pv_pixel_ray(ivec2 q, vec3 position, vec3 n, float translucency) {
  GibRng rng = gib_rng(gib_seed(), pv_frame(), uvec2(q), 41u);
  float p = pv_flag(kPvFlagTranslucentRays) ? translucency / (1.0 + translucency) : 0.0;
  PvPixelRay r;
  r.back = p > 0.0 && gib_next(rng) < p;
  vec3 side = r.back ? -n : n;
  r.dir = gib_cosine_hemisphere(side, gib_next2(rng));
  r.encode_dir = r.back ? r.dir - 2.0 * dot(r.dir, n) * n : r.dir;
  r.weight = r.back ? translucency / p : (1.0 - translucency) / (1.0 - p);
  r.origin = gib_offset_ray(position, side);
  return r;
}

#ifdef PV_PIXEL_GBUFFER  // the includer declared the images gb_normal and gb_emissive
// The ray of ray pixel q traced from source pixel p's G-buffer surface at `position`. A normal
// that is not finite or far from unit (a NaN-injection texel) faces the camera instead.
PvPixelRay pv_pixel_ray_from(ivec2 q, ivec2 p, vec3 position) {
  vec3 n = imageLoad(gb_normal, p).xyz;
  if (!(gib_finite(n) && dot(n, n) > 0.25)) n = normalize(gib_frame.camera_pos.xyz - position);
  return pv_pixel_ray(q, position, normalize(n), imageLoad(gb_emissive, p).w);
}
#endif
#endif

// Y0 of a sample traced about n0, re-evaluated for normal n.
float pv_y_for_normal(float y0, vec3 y1, vec3 n, vec3 n0) { return max(0.0, y0 + dot(y1, n - n0)); }

// Irradiance (rgb, not / pi) from a decoded sample for normal n; n0 the normal it was traced about.
vec3 pv_eval_irradiance(float y0, vec3 y1, vec2 cocg, vec3 n, vec3 n0) {
  if (!(y0 > 0.0)) return vec3(0.0);
  float y = pv_y_for_normal(y0, y1, n, n0);
  return max(gib_ycocg_to_rgb(vec3(y, cocg * (y / y0))), vec3(0.0));
}

#endif  // GIB_PV_PIXEL_GLSL
