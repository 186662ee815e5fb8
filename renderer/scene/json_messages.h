// Pieces of the one-line error messages every JSON loader writes ("<file>: <pointer>:
// expected <what>, got <what>"): shared by the scene loader and the case loader.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace gib::json_messages {

// RFC 6901: '~' and '/' inside a key are escaped so the pointer stays unambiguous.
std::string pointer_token(std::string_view key);
// A document built in C++ (not parsed) may hold invalid UTF-8; replace it rather than throw.
std::string dump_safe(const nlohmann::json& v);
// A short, single-line description of a JSON value for the "got ..." half of a message.
std::string describe(const nlohmann::json& v);
// Messages end up in JSON reports and JUnit XML, and parser messages quote raw bytes that may
// be invalid UTF-8: keep them one line of printable ASCII.
std::string ascii_line(std::string s);

}  // namespace gib::json_messages
