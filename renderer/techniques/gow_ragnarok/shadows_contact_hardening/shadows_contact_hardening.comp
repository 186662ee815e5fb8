#version 460
#extension GL_GOOGLE_include_directive : require
#include "renderer/techniques/gow_ragnarok/shadows_contact_hardening/shadows_contact_hardening_shared.h"
#include "shadow_filter_kernel.glsl"

// Contact-hardening shadows by marching in shadow-map space (gow_ragnarok.md): `taps` rays from
// the receiver towards an area light of the filter radius, march_distance metres away along the
// sun, stepped together (step by step, every live ray). At each step a ray compares its own
// sample (at its height) with the disk sample below it (at the receiver's plane); where they
// disagree the ray crossed a boundary between texels and stops, keeping its previous disk
// result: the depth map is treated as contiguous, so a ray never escapes between texels, and
// the worst case is the PCF result. The filter radius grows from one texel at the receiver to
// the full radius at the light. Taps are filtered comparisons; the pattern is turned per pixel.
// Near a cascade's edge the result blends with the next cascade's march (r.blend).
float contact_hardening(ShadowReceiver r) {
  float vis = 1.0;
  if (r.state == 0) vis = 0.0;
  else if (r.state == 2) {
    float res = push.params.y;
    uint taps = push.counts.x, steps = push.counts.y;
    float results[kShadowMaxTaps];
    vec2 dirs[kShadowMaxTaps];
    float own = csm_shadow_tap(r.cascade, r.uv, r.z, res);
    for (uint k = 0u; k < taps; ++k) {
      results[k] = own;
      dirs[k] = csm_disk_tap(k, taps, r.rotation);
    }
    uint live = taps >= 32u ? 0xffffffffu : ((1u << taps) - 1u);
    // The dilated min/max bounds the march: past t_max every ray sample is nearer the sun than
    // every occluder in reach, so a ray's result can no longer change (gow_ragnarok.md).
    uint last = min(steps, uint(ceil(r.t_max * float(steps))) + 1u);
    for (uint i = 1u; i <= last && live != 0u; ++i) {
      float t = float(i) / float(steps);
      float size = max(1.0, r.radius_tex * t) / res;
      float ray_z = r.z - t * r.march;
      uint pending = live;
      while (pending != 0u) {
        int k = findLSB(pending);
        pending &= pending - 1u;
        vec2 d = dirs[k] * size;
        float disk_z = r.z + dot(r.slope, d);
        // The ray's and the disk's samples share their texels: one read, two comparisons.
        vec2 vis2 = csm_shadow_tap2(r.cascade, r.uv + d, vec2(min(ray_z, disk_z), disk_z), res);
        if (abs(vis2.x - vis2.y) > 0.99) live &= ~(1u << uint(k));
        else results[k] = vis2.y;
      }
    }
    float sum = 0.0;
    for (uint k = 0u; k < taps; ++k) sum += results[k];
    vis = sum / float(taps);
  }
  return vis;
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(out_visibility)))) return;
  ShadowReceiver r = csm_receiver(p, push);
  float vis = contact_hardening(r);
  if (r.blend > 0.0) vis = mix(vis, contact_hardening(csm_receiver_in(p, push, r.cascade + 1u)), r.blend);
  imageStore(out_visibility, p, vec4(vis, 0.0, 0.0, 0.0));
}
