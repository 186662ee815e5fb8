#include "renderer/scene/json_messages.h"

#include <fmt/format.h>

#include <cmath>

namespace gib::json_messages {

using json = nlohmann::json;

std::string pointer_token(std::string_view key) {
  std::string out;
  for (char c : key) {
    if (c == '~') out += "~0";
    else if (c == '/') out += "~1";
    else out += c;
  }
  return out;
}

std::string dump_safe(const json& v) { return v.dump(-1, ' ', false, json::error_handler_t::replace); }

std::string describe(const json& v) {
  switch (v.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return v.get<bool>() ? "true" : "false";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned: return dump_safe(v);
    case json::value_t::number_float: {
      double d = v.get<double>();
      if (std::isnan(d)) return "NaN";
      if (std::isinf(d)) return d > 0 ? "inf" : "-inf";
      return dump_safe(v);
    }
    case json::value_t::string: {
      std::string s = dump_safe(v);  // quoted and escaped, so never multi-line
      return s.size() > 48 ? s.substr(0, 44) + "...\"" : s;
    }
    case json::value_t::array:
      return v.empty() ? "empty array" : fmt::format("array of {} element{}", v.size(), v.size() == 1 ? "" : "s");
    case json::value_t::object: return v.empty() ? "empty object" : "object";
    default: return "non-JSON value";
  }
}

std::string ascii_line(std::string s) {
  for (char& c : s)
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
  return s;
}

}  // namespace gib::json_messages
