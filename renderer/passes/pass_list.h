// Every pass the renderer knows, by name. Adding a pass: a folder under renderer/passes/ and
// one line in pass_list.cpp.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "renderer/graph/pass.h"

namespace gib {
std::vector<std::string> pass_names();
// Throws GraphError naming the known passes when `name` is unknown.
std::unique_ptr<Pass> make_pass(const std::string& name);
}  // namespace gib
