#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/passes/shadows_pcf/shadows_pcf_shared.h"
#include "shadow_filter_kernel.glsl"

// Poisson-style PCF: the mean of `taps` filtered comparisons over a disk of the area-light radius
// (the same radius contact hardening reaches at its full march distance), each against the
// receiver's plane, the pattern turned per pixel. Near a cascade's edge the result blends with
// the next cascade's (r.blend, csm_cascade_blend), so the filter's resolution does not jump at
// the seam.
float pcf(ShadowReceiver r) {
  float vis = 1.0;
  if (r.state == 0) vis = 0.0;
  else if (r.state == 2) {
    float res = push.params.y, sum = 0.0;
    uint taps = push.counts.x;
    for (uint k = 0u; k < taps; ++k) {
      vec2 d = csm_disk_tap(k, taps, r.rotation) * (r.radius_tex / res);
      sum += csm_shadow_tap(r.cascade, r.uv + d, r.z + dot(r.slope, d), res);
    }
    vis = sum / float(taps);
  }
  return vis;
}

void main() {
  csm_receiver_setup(push);
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(out_visibility)))) return;
  ShadowReceiver r = csm_receiver(p, push);
  float vis = pcf(r);
  if (r.blend > 0.0) vis = mix(vis, pcf(csm_receiver_in(p, push, r.cascade + 1u)), r.blend);
  imageStore(out_visibility, p, vec4(vis, 0.0, 0.0, 0.0));
}
