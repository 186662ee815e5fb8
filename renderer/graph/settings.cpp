#include "renderer/graph/settings.h"

#include <cxxabi.h>
#include <fmt/format.h>

#include <cstdlib>

#include "renderer/graph/graph.h"

namespace gib {
namespace {
std::string type_name(const std::type_info& t) {
  int status = 0;
  char* d = abi::__cxa_demangle(t.name(), nullptr, nullptr, &status);
  std::string out = status == 0 && d ? d : t.name();
  std::free(d);
  if (out.rfind("gib::", 0) == 0) out = out.substr(5);
  return out;
}
}  // namespace

void throw_settings_type_error(const std::type_info& wanted, const TechniqueSettings* held) {
  throw GraphError(fmt::format("settings: a pass expected {}, but the technique settings are {}",
                               type_name(wanted), held ? type_name(typeid(*held)) : std::string("not set (no technique)")));
}

}  // namespace gib
