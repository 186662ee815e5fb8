#version 460
#extension GL_GOOGLE_include_directive : require
// exposure: the radiance-cache technique's pre-exposure P (see exposure.h). Two stages (push.stage):
// partial sums of log2 luminance per workgroup, then one workgroup adds them and its thread 0
// writes {P_now, P_prev, average, lit}.
#include "renderer/techniques/radiance_cache/exposure/exposure_shared.h"
#include "finite.glsl"
#include "sampling.glsl"

layout(local_size_x = kExposureGroup) in;
layout(set = 0, binding = kExposureBindDirect, rgba32f) uniform readonly image2D direct_light;
layout(set = 0, binding = kExposureBindPrevColor, rgba32f) uniform readonly image2D prev_color;
layout(set = 0, binding = kExposureBindOut, std430) buffer Exposure { float exposure[kExposureWords]; };
layout(push_constant) uniform Push { ExposurePush push; };

shared float s_sum[kExposureGroup];
shared uint s_count[kExposureGroup];

// Rec.709 luminance (gib_luminance); a non-finite or negative one counts as unlit (0), whatever
// nan_guards says: P feeds every gather sample, so it must stay finite.
float luminance(vec3 c) {
  float y = gib_luminance(c);
  return gib_finite(y) && y > 0.0 ? y : 0.0;
}

void main() {
  uint t = gl_LocalInvocationID.x;
  float sum = 0.0;
  uint count = 0u;
  if (push.stage == 0u) {
    ivec2 size = imageSize(direct_light);
    uvec2 grid = (uvec2(size) + kExposureStride - 1u) / kExposureStride;  // sampled pixels per axis
    uint n = grid.x * grid.y;
    uint stride = push.partials * kExposureGroup;
    if (push.enabled != 0u) {
      for (uint i = gl_WorkGroupID.x * kExposureGroup + t; i < n; i += stride) {
        ivec2 p = ivec2(int(i % grid.x), int(i / grid.x)) * int(kExposureStride);
        float y = luminance(imageLoad(direct_light, p).rgb);
        if (push.prev_valid != 0u) y = max(y, luminance(imageLoad(prev_color, p).rgb));
        if (y > kExposureMinLuminance) {
          sum += log2(y);
          ++count;
        }
      }
    }
  } else if (t < push.partials) {
    sum = exposure[kExposurePartialFirst + 2u * t];
    count = uint(exposure[kExposurePartialFirst + 2u * t + 1u]);
  }
  s_sum[t] = sum;
  s_count[t] = count;
  barrier();
  for (uint s = kExposureGroup / 2u; s > 0u; s >>= 1u) {
    if (t < s) {
      s_sum[t] += s_sum[t + s];
      s_count[t] += s_count[t + s];
    }
    barrier();
  }
  if (t != 0u) return;
  if (push.stage == 0u) {
    exposure[kExposurePartialFirst + 2u * gl_WorkGroupID.x] = s_sum[0];
    exposure[kExposurePartialFirst + 2u * gl_WorkGroupID.x + 1u] = float(s_count[0]);
    return;
  }
  float p_now = 1.0, average = 0.0;
  if (s_count[0] > 0u) {
    float mean = s_sum[0] / float(s_count[0]);
    average = exp2(mean);
    p_now = exp2(clamp(-mean, -kExposureMaxLog2, kExposureMaxLog2));
  }
  // Last frame's P: what this buffer holds (persistent), except on the first frame.
  float p_prev = push.prev_valid != 0u ? exposure[kExposureNow] : p_now;
  exposure[kExposureNow] = p_now;
  exposure[kExposurePrev] = p_prev;
  exposure[kExposureAverage] = average;
  exposure[kExposureLitPixels] = float(s_count[0]);
}
