// The cascaded sun shadow map (shadow_maps, shadow_minmax, shadows_pcf and gow-ragnarok's
// shadows_contact_hardening): cascade set-up, projection, selection, the
// filtered (bilinear comparison) tap and the filter disk. Every function here has a CPU mirror
// in renderer/passes/shadow_cascades.h, and tests/test_gow_shadows.cpp checks
// the two agree.
//
// Coordinates are camera-relative (x_rel = world position - camera position) so that a scene
// 10 km from the origin projects as precisely as one at it. The cascade centres are snapped to
// whole texels in a world-fixed light frame (stable under camera translation).
//
// The includer declares, before including this file: frame.glsl, shadow_cascades_shared.h.
#ifndef GIB_SHADOW_CASCADES_GLSL
#define GIB_SHADOW_CASCADES_GLSL

struct ShadowBasis {
  vec3 r, u, s;  // light-space right, up, and s: towards the sun
};
struct ShadowCascade {
  vec2 offset;        // camera-relative light-space (r, u) of the cascade's centre
  float half_extent;  // metres from the centre to a side
  float z_top;        // camera-relative dot(x, s) that maps to depth 0 (nearest the sun)
  float z_range;      // metres of depth 0..1
};

const float kCsmGoldenAngle = 2.39996323;

ShadowBasis csm_shadow_basis(vec3 sun_dir) {
  ShadowBasis b;
  b.s = normalize(sun_dir);
  vec3 ref = abs(b.s.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
  b.r = normalize(cross(ref, b.s));
  b.u = cross(b.s, b.r);
  return b;
}

// The bounding sphere of the view-frustum slice between view distances n and f (measured along
// the view axis) of a camera with tan(fov_y / 2) = tan_y and width / height = aspect: its
// centre's distance along the axis (x) and its radius (y).
vec2 csm_slice_sphere(float n, float f, float tan_y, float aspect) {
  float a2 = tan_y * tan_y * (1.0 + aspect * aspect);  // squared tan of the corner ray's angle
  float c = min(0.5 * (f + n) * (1.0 + a2), f);
  float r = max(sqrt((c - n) * (c - n) + a2 * n * n), sqrt((f - c) * (f - c) + a2 * f * f));
  return vec2(c, r);
}

// Cascade i of the set in p for a camera at cam looking along fwd.
ShadowCascade csm_cascade(uint i, vec3 cam, vec3 fwd, float tan_y, float aspect, ShadowBasis b, ShadowCascadePush p) {
  float n = i == 0u ? p.params.w : p.splits[i - 1u];
  float f = p.splits[i];
  vec2 sphere = csm_slice_sphere(n, f, tan_y, aspect);
  float res = p.params.y;
  // Two texels of margin so the snapped square still holds the sphere.
  float texel = 2.0 * sphere.y / (res - 2.0);
  vec3 centre = fwd * sphere.x;
  vec2 cam_l = vec2(dot(cam, b.r), dot(cam, b.u));
  vec2 world_l = cam_l + vec2(dot(centre, b.r), dot(centre, b.u));
  ShadowCascade c;
  c.offset = floor(world_l / texel) * texel - cam_l;
  c.half_extent = 0.5 * texel * res;
  c.z_top = dot(centre, b.s) + sphere.y + p.params.z;
  c.z_range = 2.0 * sphere.y + p.params.z;
  return c;
}

// (u, v, depth) of a camera-relative point in cascade c: u, v in [0, 1] across the cascade's
// square (v = 0 at texel row 0), depth 0 nearest the sun.
vec3 csm_shadow_project(ShadowCascade c, ShadowBasis b, vec3 x_rel) {
  vec2 l = vec2(dot(x_rel, b.r), dot(x_rel, b.u)) - c.offset;
  return vec3(l / (2.0 * c.half_extent) + 0.5, (c.z_top - dot(x_rel, b.s)) / c.z_range);
}

// Metres per shadow-map texel of cascade c.
float csm_texel_size(ShadowCascade c, ShadowCascadePush p) { return 2.0 * c.half_extent / p.params.y; }

// Whether cascade c's square holds x_rel with margin_m metres plus margin_texels texels to spare
// and its depth range holds it (the test csm_select_cascade applies to each cascade in turn).
bool csm_cascade_holds(ShadowCascade c, ShadowBasis b, ShadowCascadePush p, vec3 x_rel, float margin_m,
                       float margin_texels) {
  vec3 q = csm_shadow_project(c, b, x_rel);
  float m = margin_m / (2.0 * c.half_extent) + margin_texels / p.params.y;
  return all(greaterThanEqual(q.xy, vec2(m))) && all(lessThanEqual(q.xy, vec2(1.0 - m))) && q.z >= 0.0 && q.z <= 1.0;
}

// The first cascade whose square holds x_rel with margin_m metres plus margin_texels texels to
// spare and whose depth range holds it; kShadowMaxCascades when none does (the point is lit:
// beyond the shadowed distance).
uint csm_select_cascade(vec3 cam, vec3 fwd, float tan_y, float aspect, ShadowBasis b, ShadowCascadePush p,
                        vec3 x_rel, float margin_m, float margin_texels) {
  for (uint i = 0u; i < uint(p.params.x); ++i)
    if (csm_cascade_holds(csm_cascade(i, cam, fwd, tan_y, aspect, b, p), b, p, x_rel, margin_m, margin_texels)) return i;
  return kShadowMaxCascades;
}

// The seam blend of csm_cascade_blend with the cascades already built: c is cascade i (the one
// selected for x_rel), next cascade i + 1, has_next false where i is the last cascade.
float csm_cascade_blend_of(ShadowCascade c, ShadowCascade next, bool has_next, ShadowBasis b, ShadowCascadePush p,
                           vec3 x_rel, float margin_m, float margin_texels) {
  float band = p.blend.x;
  if (!(band > 0.0) || !has_next) return 0.0;
  vec3 q = csm_shadow_project(c, b, x_rel);
  float m = margin_m / (2.0 * c.half_extent) + margin_texels / p.params.y;
  float d = min(min(q.x - m, q.y - m), min(1.0 - m - q.x, 1.0 - m - q.y));
  float w = clamp(1.0 - d / band, 0.0, 1.0);
  if (w <= 0.0) return 0.0;
  return csm_cascade_holds(next, b, p, x_rel, margin_m, margin_texels) ? w : 0.0;
}

// The weight of cascade i + 1 at x_rel, a point whose selected cascade is i: the seam blend.
// With d the distance (in units of cascade i's width) from x_rel to the nearest side of the
// square csm_select_cascade accepts in cascade i (the same margins), the weight rises linearly
// from 0 at d = band to 1 at d = 0, where selection would pass to cascade i + 1. 0 when the band
// is 0 (blending off), i is the last cascade, or cascade i + 1 does not hold the point with its
// margins (nothing to blend into).
float csm_cascade_blend(vec3 cam, vec3 fwd, float tan_y, float aspect, ShadowBasis b, ShadowCascadePush p, uint i,
                        vec3 x_rel, float margin_m, float margin_texels) {
  bool has_next = i + 1u < uint(p.params.x);
  ShadowCascade c = csm_cascade(i, cam, fwd, tan_y, aspect, b, p);
  ShadowCascade next = has_next ? csm_cascade(i + 1u, cam, fwd, tan_y, aspect, b, p) : c;
  return csm_cascade_blend_of(c, next, has_next, b, p, x_rel, margin_m, margin_texels);
}

// Tap k of n of the filter disk (a golden-angle spiral: even area density, no two taps closer
// than about 1.2 / sqrt(n) of the radius), turned by `rotation` radians; inside the unit disk.
vec2 csm_disk_tap(uint k, uint n, float rotation) {
  float r = sqrt((float(k) + 0.5) / float(n));
  float a = float(k) * kCsmGoldenAngle + rotation;
  return r * vec2(cos(a), sin(a));
}

// The camera frame from the frame constants.
void csm_camera(out vec3 cam, out vec3 fwd, out float tan_y, out float aspect) {
  cam = gib_frame.camera_pos.xyz;
  vec4 h = gib_frame.inv_view_proj_rel * vec4(0.0, 0.0, 0.5, 1.0);
  fwd = normalize(h.xyz / h.w);
  tan_y = gib_frame.camera_pos.w;
  aspect = float(gib_frame.frame_info.y) / float(gib_frame.frame_info.z);
}

// tan of the sun's angular radius (frame: cos of it).
float csm_sun_tan() {
  float c = clamp(gib_frame.sun_dir.w, 1e-4, 1.0);
  return sqrt(max(1.0 - c * c, 0.0)) / c;
}

// Area-light radius (m): authored (> 0) or the sun's, seen from the march distance.
float csm_filter_radius(ShadowCascadePush p) {
  return p.area.x > 0.0 ? p.area.x : p.area.y * csm_sun_tan();
}

#ifdef CSM_SHADOW_MAP_BOUND
// Filtered comparisons at (u, v) of cascade `cascade` against two depths z.x and z.y from one
// read of the four nearest texels: each texel compared (1: lit, the stored surface is no nearer
// the sun than z) and bilinearly weighted; texels are clamped to the cascade's own square.
// shadow_map is the atlas as a sampled image. Where the four texels lie inside the cascade (all
// but its outermost texel ring) one textureGather at their shared corner reads them; the corner
// sits half a texel from any texel centre, so the gather's own coordinate rounding cannot pick
// another quad. Elsewhere four texelFetch read the clamped texels. Both return the stored
// values unchanged, so the result is that of four separate loads bit for bit.
vec2 csm_shadow_tap2(uint cascade, vec2 uv, vec2 z, float res) {
  vec2 t = uv * res - 0.5;
  vec2 i0 = floor(t);
  vec2 f = t - i0;
  float x0 = float(cascade) * res;
  float d00, d10, d01, d11;
  if (all(greaterThanEqual(i0, vec2(0.0))) && all(lessThan(i0, vec2(res - 1.0)))) {
    // The quad's shared corner, texel (i0 + 1) of the cascade in the atlas, in its normalised
    // coordinates (within a rounding of it: the gather tolerates half a texel).
    vec4 g = textureGather(shadow_map, (vec2(x0 + 1.0, 1.0) + i0) / vec2(textureSize(shadow_map, 0)));
    d01 = g.x;  // gather order: (i0, j1), (i1, j1), (i1, j0), (i0, j0)
    d11 = g.y;
    d10 = g.z;
    d00 = g.w;
  } else {
    ivec2 a = ivec2(clamp(i0, vec2(0.0), vec2(res - 1.0))) + ivec2(int(x0), 0);
    ivec2 b = ivec2(clamp(i0 + 1.0, vec2(0.0), vec2(res - 1.0))) + ivec2(int(x0), 0);
    d00 = texelFetch(shadow_map, ivec2(a.x, a.y), 0).x;
    d10 = texelFetch(shadow_map, ivec2(b.x, a.y), 0).x;
    d01 = texelFetch(shadow_map, ivec2(a.x, b.y), 0).x;
    d11 = texelFetch(shadow_map, ivec2(b.x, b.y), 0).x;
  }
  vec2 l00 = vec2(greaterThanEqual(vec2(d00), z)), l10 = vec2(greaterThanEqual(vec2(d10), z));
  vec2 l01 = vec2(greaterThanEqual(vec2(d01), z)), l11 = vec2(greaterThanEqual(vec2(d11), z));
  return mix(mix(l00, l10, f.x), mix(l01, l11, f.x), f.y);
}

// One filtered comparison (csm_shadow_tap2 with one depth).
float csm_shadow_tap(uint cascade, vec2 uv, float z, float res) { return csm_shadow_tap2(cascade, uv, vec2(z), res).x; }
#endif

#endif
