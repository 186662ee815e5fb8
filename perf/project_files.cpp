#include "perf/project_files.h"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "perf/profiles.h"

#ifndef GIB_SOURCE_DIR
#define GIB_SOURCE_DIR "."
#endif

namespace fs = std::filesystem;

namespace gib::perf {
namespace {

bool same_folder(const fs::path& a, const fs::path& b) {
  std::error_code ea, eb;
  const fs::path ca = fs::weakly_canonical(a, ea), cb = fs::weakly_canonical(b, eb);
  return !ea && !eb && ca == cb;
}

std::string joined(const std::vector<fs::path>& paths) {
  std::string out;
  for (const fs::path& p : paths) out += (out.empty() ? "" : ", ") + p.string();
  return out;
}

}  // namespace

std::vector<fs::path> project_roots() {
  std::vector<fs::path> roots{fs::current_path()};
  const fs::path source(GIB_SOURCE_DIR);
  if (!same_folder(roots[0], source)) roots.push_back(source);
  return roots;
}

std::string resolve_case_scene(const std::string& name, const std::string& flag) {
  const bool path = fs::path(name).extension() == ".json";
  std::vector<fs::path> tries;
  for (const fs::path& root : project_roots()) {
    std::vector<fs::path> here = path ? std::vector<fs::path>{root / name}
                                      : std::vector<fs::path>{root / "cases" / (name + ".json"),
                                                              root / "cases" / "scenes" / (name + ".json")};
    for (fs::path& p : here)
      if (std::find(tries.begin(), tries.end(), p) == tries.end()) tries.push_back(std::move(p));
  }
  for (const fs::path& p : tries) {
    if (!fs::is_regular_file(p)) continue;
    std::ifstream in(p, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(text.str());
    } catch (const nlohmann::json::parse_error& e) {
      throw PerfError(fmt::format("{}: expected valid JSON, got a parse error: {}", p.string(), e.what()));
    }
    if (j.is_object() && j.contains("scene")) {
      if (!j["scene"].is_string())
        throw PerfError(fmt::format("{}: /scene: expected a scene path string, got {}", p.string(), j["scene"].dump()));
      return (p.parent_path() / j["scene"].get<std::string>()).string();
    }
    return p.string();
  }
  throw PerfError(fmt::format("{}: expected a case or scene name (cases/<name>.json, cases/scenes/<name>.json) or a "
                              "JSON path, got '{}'; tried {}",
                              flag, name, joined(tries)));
}

std::string find_project_file(const std::string& relative, const std::string& what) {
  std::vector<fs::path> tried;
  for (const fs::path& root : project_roots()) {
    tried.push_back(root / relative);
    if (fs::is_regular_file(tried.back())) return tried.back().string();
  }
  throw PerfError(fmt::format("{}: expected {} in the working folder or the source tree, found none (tried {})", what,
                              relative, joined(tried)));
}

std::string default_history_path() {
  std::vector<fs::path> tried;
  for (const fs::path& root : project_roots()) {
    tried.push_back(root / "bench");
    if (fs::is_directory(tried.back())) return (tried.back() / "history.jsonl").string();
  }
  throw PerfError(fmt::format("--history: expected a bench/ folder for the default bench/history.jsonl, found none "
                              "(tried {}); pass --history FILE or --no-history",
                              joined(tried)));
}

}  // namespace gib::perf
