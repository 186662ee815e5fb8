#include "renderer/passes/pass_list.h"

#include <fmt/format.h>

#include <functional>
#include <utility>

#include "renderer/passes/direct_lighting/direct_lighting.h"
#include "renderer/passes/gbuffer/gbuffer.h"
#include "renderer/passes/path_trace/path_trace.h"
#include "renderer/passes/path_trace_resolve/path_trace_resolve.h"
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
