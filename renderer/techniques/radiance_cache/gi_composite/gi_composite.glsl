// gi_composite kernel, included by gi_composite_<format>.comp with GI_HISTORY_FORMAT defined.
// See gi_composite.h.
#include "renderer/techniques/radiance_cache/gi_composite/gi_composite_shared.h"
#include "renderer/techniques/radiance_cache/include/gi_history.glsl"

layout(local_size_x = kGiCompositeGroup, local_size_y = kGiCompositeGroup) in;
layout(set = 0, binding = kGiCompositeBindDirect, rgba32f) uniform readonly image2D direct_light;
layout(set = 0, binding = kGiCompositeBindAlbedo, rgba16f) uniform readonly image2D gb_albedo;
GI_HISTORY_READER(gi_history, kGiCompositeBindHistory, load_history)
GI_HISTORY_READER(gi_history_direct, kGiCompositeBindHistoryDirect, load_history_direct)
layout(set = 0, binding = kGiCompositeBindExposure, std430) readonly buffer Exposure { float exposure[4]; };
layout(set = 0, binding = kGiCompositeBindColor, rgba32f) uniform writeonly image2D out_color;
layout(set = 0, binding = kGiCompositeBindIndirect, rgba32f) uniform writeonly image2D out_indirect;
layout(set = 0, binding = kGiCompositeBindDirectOut, rgba32f) uniform writeonly image2D out_direct;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(out_color)))) return;
  // The history holds irradiance / pi x P_now; dividing P_now out gives gi_irradiance and
  // gi_direct_irradiance as gi_resolve writes them. Sky pixels: albedo and the history are 0,
  // so final_color is direct_light's sky radiance.
  float p_now = exposure[kGiCompositeExposureNow];
  vec3 albedo = imageLoad(gb_albedo, p).rgb;
  vec3 indirect = albedo * (load_history(p) / p_now);
  vec3 direct = imageLoad(direct_light, p).rgb + albedo * (load_history_direct(p) / p_now);
  imageStore(out_indirect, p, vec4(indirect, 1.0));
  imageStore(out_direct, p, vec4(direct, 1.0));
  imageStore(out_color, p, vec4(direct + indirect, 1.0));
}
