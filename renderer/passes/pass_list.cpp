#include "renderer/passes/pass_list.h"

#include <fmt/format.h>

#include <functional>
#include <utility>

#include "renderer/passes/composite/composite.h"
#include "renderer/passes/direct_lighting/direct_lighting.h"
#include "renderer/passes/exposure/exposure.h"
#include "renderer/passes/final_gather/final_gather.h"
#include "renderer/passes/gbuffer/gbuffer.h"
#include "renderer/passes/gi_denoise/gi_denoise.h"
#include "renderer/passes/gi_upscale/gi_upscale.h"
#include "renderer/passes/irradiance_volume_update/irradiance_volume_update.h"
#include "renderer/passes/light_grid/light_grid.h"
#include "renderer/passes/path_trace/path_trace.h"
#include "renderer/passes/path_trace_resolve/path_trace_resolve.h"
#include "renderer/passes/probe_trace/probe_trace.h"
#include "renderer/passes/radiance_cache_shade/radiance_cache_shade.h"
#include "renderer/passes/radiance_cache_update/radiance_cache_update.h"
#include "renderer/passes/visibility/visibility.h"

namespace gib {
namespace {
const std::vector<std::pair<std::string, std::function<std::unique_ptr<Pass>()>>>& registry() {
  static const std::vector<std::pair<std::string, std::function<std::unique_ptr<Pass>()>>> r = {
      {"visibility", make_visibility_pass},
      {"gbuffer", make_gbuffer_pass},
      {"direct_lighting", make_direct_lighting_pass},
      {"path_trace", make_path_trace_pass},
      {"path_trace_resolve", make_path_trace_resolve_pass},
      {"light_grid", [] { return make_light_grid_pass(); }},
      {"probe_trace", make_probe_trace_pass},
      {"radiance_cache_update", make_radiance_cache_update_pass},
      {"radiance_cache_shade", make_radiance_cache_shade_pass},
      {"irradiance_volume_update", make_irradiance_volume_update_pass},
      {"exposure", make_exposure_pass},
      {"final_gather", make_final_gather_pass},
      {"gi_denoise", make_gi_denoise_pass},
      {"gi_upscale", make_gi_upscale_pass},
      {"composite", make_composite_pass},
  };
  return r;
}
}  // namespace

std::vector<std::string> pass_names() {
  std::vector<std::string> out;
  for (auto& [n, f] : registry()) out.push_back(n);
  return out;
}

std::unique_ptr<Pass> make_pass(const std::string& name) {
  for (auto& [n, f] : registry())
    if (n == name) return f();
  throw GraphError(fmt::format("unknown pass '{}': expected one of [{}]", name, fmt::join(pass_names(), ", ")));
}

}  // namespace gib
