// A G-buffer pixel as a shadow receiver in the cascaded shadow map (shadow_cascades.glsl), shared by
// shadows_pcf and shadows_contact_hardening: its cascade, shadow-map position, biased depth,
// receiver-plane depth slope, filter radius in texels, the tap rotation (jitter) and the dilated
// min/max early-out (seed: "Use dilated min/max depth to early out if fully in or out of shadow,
// tighten range of ray trace").
//
// The includer declares: frame.glsl, hash.glsl, shadow_cascades_shared.h, CSM_SHADOW_MAP_BOUND with
// images shadow_map, shadow_minmax, gb_position, gb_normal; shadow_cascades.glsl; push `push`. Its
// main calls csm_receiver_setup before any thread returns.
#ifndef GIB_SHADOW_RECEIVER_GLSL
#define GIB_SHADOW_RECEIVER_GLSL

struct ShadowReceiver {
  int state;         // -1: no pixel (sky) or beyond the cascades (lit); 0 fully shadowed; 1 fully lit; 2 filter
  uint cascade;
  float blend;       // weight of cascade + 1 near this cascade's edge (csm_cascade_blend; 0: none)
  vec2 uv;
  float z;           // biased receiver depth
  vec2 slope;        // depth change per unit of uv offset on the receiver's plane
  float radius_tex;  // area-light radius in texels (>= 1)
  float march;       // march distance in depth units
  float t_max;       // fraction of the march beyond which every ray sample is lit
  float rotation;    // tap-pattern rotation (radians)
};

// The frame's cascades, light basis and camera position: the same for every pixel of the
// dispatch, so each workgroup builds them once (csm_receiver_setup) and its receivers read them
// here instead of each thread rebuilding up to six cascades (selection, seam blend, projection).
shared ShadowCascade s_csm_cascades[kShadowMaxCascades];
shared ShadowBasis s_csm_basis;
shared vec3 s_csm_camera;

// Builds the shared cascades; every thread of the workgroup calls it before its first receiver
// (it holds a barrier: call it before any thread returns).
void csm_receiver_setup(ShadowCascadePush sp) {
  uint lane = gl_LocalInvocationIndex;
  if (lane < uint(sp.params.x)) {
    vec3 cam, fwd;
    float tan_y, aspect;
    csm_camera(cam, fwd, tan_y, aspect);
    ShadowBasis b = csm_shadow_basis(gib_frame.sun_dir.xyz);
    s_csm_cascades[lane] = csm_cascade(lane, cam, fwd, tan_y, aspect, b, sp);
    if (lane == 0u) {
      s_csm_basis = b;
      s_csm_camera = cam;
    }
  }
  barrier();
}

// Pixel p as a receiver in cascade `cascade` (selected: csm_receiver; or the next one, for the
// seam blend). `cascade` kShadowMaxCascades: the first that holds its filter footprint (the
// first csm_cascade_holds accepts, as csm_select_cascade). Reads csm_receiver_setup's cascades.
ShadowReceiver csm_receiver_in(ivec2 p, ShadowCascadePush sp, uint cascade) {
  ShadowReceiver r;
  r.state = -1;
  r.blend = 0.0;
  vec4 pos = imageLoad(gb_position, p);
  if (pos.w == 0.0) return r;
  ShadowBasis b = s_csm_basis;
  float radius_m = csm_filter_radius(sp);
  vec3 x_rel = pos.xyz - s_csm_camera;
  uint cascades = uint(sp.params.x);
  float margin_texels = 2.0 + sp.area.w;
  if (cascade < kShadowMaxCascades) r.cascade = cascade;
  else {
    r.cascade = kShadowMaxCascades;
    for (uint i = 0u; i < cascades; ++i)
      if (csm_cascade_holds(s_csm_cascades[i], b, sp, x_rel, radius_m, margin_texels)) {
        r.cascade = i;
        break;
      }
    if (r.cascade >= kShadowMaxCascades) return r;
    bool has_next = r.cascade + 1u < cascades;
    r.blend = csm_cascade_blend_of(s_csm_cascades[r.cascade], s_csm_cascades[has_next ? r.cascade + 1u : r.cascade],
                                   has_next, b, sp, x_rel, radius_m, margin_texels);
  }
  ShadowCascade c = s_csm_cascades[r.cascade];
  float res = sp.params.y, texel = csm_texel_size(c, sp);
  vec3 n = imageLoad(gb_normal, p).xyz;
  if (!(dot(n, n) > 0.25 && dot(n, n) < 4.0)) n = b.s;  // a broken normal: no offset, flat slope
  n = normalize(n);
  // The normal offset faces the sun side of the surface (light reaching a back face is lit from behind).
  vec3 ns = dot(n, b.s) >= 0.0 ? n : -n;
  vec3 q = csm_shadow_project(c, b, x_rel + ns * (sp.area.w * texel));
  r.uv = q.xy;
  r.z = q.z - sp.area.z / c.z_range;
  // Receiver plane: dot(ns, dx) = 0 gives d(dot(x, s)) = -(ns.r da + ns.u db) / ns.s; depth runs
  // the other way, and one unit of uv is 2 half_extent metres. Grazing planes are clamped.
  float nss = max(dot(ns, b.s), 0.25);
  r.slope = vec2(dot(ns, b.r), dot(ns, b.u)) / nss * (2.0 * c.half_extent / c.z_range);
  r.radius_tex = max(1.0, radius_m / texel);
  r.march = sp.area.y / c.z_range;
  r.t_max = 1.0;
  GibRng rng = gib_rng(gib_seed(), gib_frame_index(), uvec2(p), 7u);
  r.rotation = 6.28318531 * gib_next(rng);
  r.state = 2;
  if (sp.counts.w != 0u) {
    // One min/max texel per kShadowMinMaxTile^2 shadow-map texels, dilated by the filter radius.
    ivec2 tile = ivec2(clamp(r.uv, vec2(0.0), vec2(1.0)) * res) / int(kShadowMinMaxTile);
    int tiles = int(res) / int(kShadowMinMaxTile);
    tile = clamp(tile, ivec2(0), ivec2(tiles - 1));
    vec2 mm = imageLoad(shadow_minmax, ivec2(int(r.cascade) * tiles + tile.x, tile.y)).xy;
    float spread = length(r.slope) * r.radius_tex / res;  // receiver-plane depth change over the disk
    if (r.z + spread <= mm.x) r.state = 1;
    else if (r.z - spread > mm.y) r.state = 0;
    else r.t_max = clamp((r.z + spread - mm.x) / max(r.march, 1e-20), 0.0, 1.0);
  }
  return r;
}

// Pixel p in the cascade selected for it (r.blend: how much of the next one to blend in).
ShadowReceiver csm_receiver(ivec2 p, ShadowCascadePush sp) { return csm_receiver_in(p, sp, kShadowMaxCascades); }

#endif
