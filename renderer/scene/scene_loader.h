// JSON scene files -> Scene. The format is documented field by field in cases/scenes/README.md.
// Every problem is reported as one line, `<file>: <json pointer>: expected <what>, got <what>`,
// so a harness can print it next to the case that failed and an editor can jump to it.
#pragma once
#include <nlohmann/json_fwd.hpp>
#include <stdexcept>
#include <string>

#include "renderer/scene/scene.h"

namespace gib {

class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Reads and parses a scene file; unreadable files and JSON syntax errors are SceneErrors too
// (syntax errors name the line and column instead of a JSON pointer).
Scene load_scene(const std::string& path);

// Validates and converts an already-parsed document (cases may embed a scene inline).
// `source_name` is what messages and Scene::source call the document.
Scene parse_scene(const nlohmann::json& doc, const std::string& source_name);

}  // namespace gib
