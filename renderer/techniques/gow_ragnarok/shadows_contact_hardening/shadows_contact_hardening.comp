#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/gow_ragnarok/shadows_contact_hardening/shadows_contact_hardening_shared.h"
#include "shadow_filter_kernel.glsl"

// Contact-hardening shadows by marching in shadow-map space (gow_ragnarok.md): `taps` rays from
// the receiver towards an area light of the filter radius, march_distance metres away along the
// sun. At each step a ray compares its own sample (at its height) with the disk sample below it
// (at the receiver's plane); where they disagree the ray crossed a boundary between texels and
// stops, keeping its previous disk result: the depth map is treated as contiguous, so a ray never
// escapes between texels, and the worst case is the PCF result. The filter radius grows from one
// texel at the receiver to the full radius at the light. Taps are filtered comparisons; the
// pattern is turned per pixel. Near a cascade's edge the result blends with the next cascade's
// march (r.blend).
//
// The seed steps all rays together (for each step, every live ray, a bit mask of live rays);
// each ray's result depends on its own samples alone, so marching one ray to its end before the
// next gives the same results bit for bit, and keeps a ray's direction and result in registers
// instead of two per-ray arrays indexed by the mask's bits (which live in thread-local memory).
float contact_hardening(ShadowReceiver r) {
  float vis = 1.0;
  if (r.state == 0) vis = 0.0;
  else if (r.state == 2) {
    float res = push.params.y;
    uint taps = push.counts.x, steps = push.counts.y;
    float own = csm_shadow_tap(r.cascade, r.uv, r.z, res);
    // The dilated min/max bounds the march: past t_max every ray sample is nearer the sun than
    // every occluder in reach, so a ray's result can no longer change (gow_ragnarok.md).
    uint last = min(steps, uint(ceil(r.t_max * float(steps))) + 1u);
    float sum = 0.0;
    for (uint k = 0u; k < taps; ++k) {
      vec2 dir = csm_disk_tap(k, taps, r.rotation);
      float result = own;
      for (uint i = 1u; i <= last; ++i) {
        float t = float(i) / float(steps);
        float size = max(1.0, r.radius_tex * t) / res;
        float ray_z = r.z - t * r.march;
        vec2 d = dir * size;
        float disk_z = r.z + dot(r.slope, d);
        // The ray's and the disk's samples share their texels: one read, two comparisons.
        vec2 vis2 = csm_shadow_tap2(r.cascade, r.uv + d, vec2(min(ray_z, disk_z), disk_z), res);
        if (abs(vis2.x - vis2.y) > 0.99) break;
        result = vis2.y;
      }
      sum += result;
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
  float vis = contact_hardening(r);
  if (r.blend > 0.0) vis = mix(vis, contact_hardening(csm_receiver_in(p, push, r.cascade + 1u)), r.blend);
  imageStore(out_visibility, p, vec4(vis, 0.0, 0.0, 0.0));
}
