// gi_resolve kernel, included by gi_resolve_<format>.comp with GI_HISTORY_FORMAT defined.
// See gi_resolve.h.
#include "renderer/techniques/radiance_cache/gi_resolve/gi_resolve_shared.h"
#include "renderer/techniques/radiance_cache/include/gi_history.glsl"

layout(local_size_x = kGiResolveGroup, local_size_y = kGiResolveGroup) in;
GI_HISTORY_READER(gi_history, kGiResolveBindHistory, load_history)
GI_HISTORY_READER(gi_history_direct, kGiResolveBindHistoryDirect, load_history_direct)
layout(set = 0, binding = kGiResolveBindExposure, std430) readonly buffer Exposure { float exposure[4]; };
layout(set = 0, binding = kGiResolveBindIrradiance, rgba32f) uniform writeonly image2D out_irradiance;
layout(set = 0, binding = kGiResolveBindDirectIrradiance, rgba32f) uniform writeonly image2D out_direct_irradiance;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(out_irradiance)))) return;
  float p_now = exposure[kGiResolveExposureNow];
  imageStore(out_irradiance, p, vec4(load_history(p) / p_now, 1.0));
  imageStore(out_direct_irradiance, p, vec4(load_history_direct(p) / p_now, 1.0));
}
