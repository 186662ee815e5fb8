// Which cascade surrounds a point (needs pv_common.glsl and PV_STATE_BUFFER(...) declared).
#ifndef GIB_PV_VOLUME_GLSL
#define GIB_PV_VOLUME_GLSL

// The finest cascade whose probes surround x (between the first and last probe planes of
// every axis); kPvMaxCascades when none does.
uint pv_cascade_at(vec3 x) {
  for (uint c = 0u; c < pv_cascades(); ++c) {
    vec3 g = x / pv_spacing(c) - 0.5 - vec3(pv_cascade[c].origin.xyz);
    if (all(greaterThanEqual(g, vec3(0.0))) && all(lessThan(g, vec3(pv_dims() - 1)))) return c;
  }
  return kPvMaxCascades;
}

// How far a per-pixel ray from x reaches: pixel_range x the probe trace range of the cascade
// around x (the coarsest one outside the volume).
float pv_pixel_range(vec3 x) { return pv.volume.w * pv_trace_range(min(pv_cascade_at(x), pv_cascades() - 1u)); }

#endif  // GIB_PV_VOLUME_GLSL
