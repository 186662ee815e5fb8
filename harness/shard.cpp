#include "harness/shard.h"

#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <stdexcept>

#include "harness/report.h"

namespace fs = std::filesystem;

namespace gib {

Shard parse_shard(const std::string& text) {
  Shard s;
  unsigned k = 0, n = 0;
  char slash = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%u%c%u%c", &k, &slash, &n, &extra) != 3 || slash != '/' || n == 0 || k >= n ||
      text.find_first_not_of("0123456789/") != std::string::npos)
    throw std::invalid_argument(
        fmt::format("--shard: expected K/N with 0 <= K < N (0-based, as GTEST_SHARD_INDEX; e.g. 0/2), got '{}'", text));
  s.index = k;
  s.count = n;
  return s;
}

Shard shard_from(const std::string& flag) {
  if (!flag.empty()) return parse_shard(flag);
  const char* index = std::getenv("GTEST_SHARD_INDEX");
  const char* total = std::getenv("GTEST_TOTAL_SHARDS");
  if (!index || !total || !*index || !*total) return {};
  Shard s;
  try {
    s = parse_shard(std::string(index) + "/" + total);
  } catch (const std::invalid_argument&) {
    throw std::invalid_argument(fmt::format(
        "GTEST_SHARD_INDEX / GTEST_TOTAL_SHARDS: expected 0 <= index < total, got '{}' and '{}'", index, total));
  }
  if (const char* status = std::getenv("GTEST_SHARD_STATUS_FILE"); status && *status) std::ofstream(status).flush();
  return s;
}

namespace {

nlohmann::json read_results(const fs::path& dir) {
  fs::path p = dir / "results.json";
  std::ifstream in(p);
  if (!in) throw std::runtime_error(fmt::format("{}: expected a shard's results.json, got no readable file", p.string()));
  try {
    return nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    throw std::runtime_error(fmt::format("{}: expected JSON, got a parse error: {}", p.string(), e.what()));
  }
}


}  // namespace

int cmd_merge(const MergeOptions& o) {
  if (o.shard_dirs.empty()) throw std::invalid_argument("merge: expected at least one shard folder");
  std::vector<nlohmann::json> shards;
  std::map<uint32_t, std::string> by_index;
  nlohmann::json plan;
  uint32_t count = 0;
  std::string device_class, tier;
  for (const std::string& dir : o.shard_dirs) {
    nlohmann::json j = read_results(dir);
    std::string where = (fs::path(dir) / "results.json").string();
    if (!j.contains("shard") || !j["shard"].is_object())
      throw std::runtime_error(fmt::format("{}: shard: expected the record of a `gibench run --shard K/N`, got none", where));
    const nlohmann::json& s = j["shard"];
    uint32_t k = s.value("index", 0u), n = s.value("count", 0u);
    if (shards.empty()) {
      count = n;
      plan = s.value("plan", nlohmann::json::array());
      device_class = j["device"].value("class", "");
    } else if (n != count || s.value("plan", nlohmann::json::array()) != plan) {
      throw std::runtime_error(fmt::format("{}: shard: expected {}/{} of the same plan as {}, got {}/{} of {}", where, k,
                                           count, o.shard_dirs.front(), k, n,
                                           n != count ? "another shard count" : "another plan (other cases or --case)"));
    }
    if (j["device"].value("class", "") != device_class)
      throw std::runtime_error(fmt::format(
          "{}: device.class: expected {} as in {} (goldens and verdicts are per device class), got {}", where,
          device_class, o.shard_dirs.front(), j["device"].value("class", "")));
    if (shards.empty()) tier = j["device"].value("tier", "");
    if (j["device"].value("tier", "") != tier)
      throw std::runtime_error(fmt::format(
          "{}: device.tier: expected {} as in {} (sizes, references and goldens are per tier), got {}", where, tier,
          o.shard_dirs.front(), j["device"].value("tier", "")));
    if (auto [it, fresh] = by_index.emplace(k, dir); !fresh)
      throw std::runtime_error(fmt::format("{}: shard {}/{} given twice (also {})", where, k, n, it->second));
    shards.push_back(std::move(j));
  }
  for (uint32_t k = 0; k < count; ++k)
    if (!by_index.count(k))
      throw std::runtime_error(fmt::format("merge: shard {}/{} missing (got {} of {} shards)", k, count, by_index.size(), count));

  // Rows in plan order; each planned row exactly once, unless its case recorded an error.
  std::map<std::string, nlohmann::json> rows;
  std::set<std::string> case_errors_seen, cases_with_errors;
  nlohmann::json case_errors = nlohmann::json::array(), cases = nlohmann::json::array();
  std::set<std::string> case_names;
  nlohmann::json devices = nlohmann::json::array();
  for (size_t i = 0; i < shards.size(); ++i) {
    const nlohmann::json& j = shards[i];
    devices.push_back({{"shard", j["shard"]["index"]}, {"name", j["device"].value("name", "")}});
    for (auto& row : j["results"]) {
      std::string key = row_key_of(row);
      if (auto [it, fresh] = rows.emplace(key, row); !fresh)
        throw std::runtime_error(fmt::format("{}: row {} duplicated (also in another shard)", o.shard_dirs[i], key));
    }
    for (auto& e : j["case_errors"]) {
      std::string text = e.get<std::string>();
      if (case_errors_seen.insert(text).second) case_errors.push_back(text);
      cases_with_errors.insert(text.substr(0, text.find(':')));
    }
    for (auto& c : j["cases"])
      if (case_names.insert(c.value("name", "")).second) cases.push_back(c);
  }
  nlohmann::json merged_rows = nlohmann::json::array();
  for (size_t i = 0; i < plan.size(); ++i) {
    std::string key = plan[i].get<std::string>();
    auto it = rows.find(key);
    if (it == rows.end()) {
      if (cases_with_errors.count(key.substr(0, key.find('/')))) continue;
      uint32_t k = uint32_t(i % count);
      throw std::runtime_error(fmt::format("merge: row {} missing: planned in shard {}/{} ({}), not in its results", key,
                                           k, count, by_index[k]));
    }
    merged_rows.push_back(it->second);
    rows.erase(it);
  }
  if (!rows.empty())
    throw std::runtime_error(fmt::format("merge: row {} is in no shard's plan", rows.begin()->first));

  nlohmann::json out = shards.front();
  out.erase("shard");
  out["results"] = merged_rows;
  out["case_errors"] = case_errors;
  out["cases"] = cases;
  out["merged"] = {{"shards", count}, {"devices", devices}};
  fs::create_directories(fs::path(o.out) / "img");
  for (auto& dir : o.shard_dirs) {
    std::error_code ec;
    if (!fs::is_directory(fs::path(dir) / "img", ec)) continue;
    for (auto& f : fs::directory_iterator(fs::path(dir) / "img"))
      fs::copy_file(f.path(), fs::path(o.out) / "img" / f.path().filename(), fs::copy_options::overwrite_existing);
  }
  write_report_files(o.out, out);
  int failed = int(case_errors.size()), known = 0, passed = 0;
  for (auto& r : merged_rows) {
    std::string st = r.value("status", "error");
    if (st == "fail" || st == "error") ++failed;
    else if (st == "known_failure") ++known;
    else if (st == "pass") ++passed;
  }
  fmt::print("merged {} shards ({}): {} rows\n", count, device_class, merged_rows.size());
  fmt::print("{} passed, {} failed{}\n", passed, failed, known ? fmt::format(", {} known failures (not counted)", known) : "");
  fmt::print("report: {}\n", (fs::path(o.out) / "index.html").string());
  return failed ? 1 : 0;
}

}  // namespace gib
