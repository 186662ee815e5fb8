#include "harness/progress.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "harness/plan.h"

namespace gib {

std::string format_duration(double seconds) {
  long s = std::lround(std::max(0.0, seconds));
  if (s >= 3600) return fmt::format("{}:{:02}:{:02}", s / 3600, (s / 60) % 60, s % 60);
  return fmt::format("{}:{:02}", s / 60, s % 60);
}

std::map<std::string, double> recorded_row_seconds(const std::string& out_dir) {
  std::map<std::string, double> out;
  std::ifstream in(std::filesystem::path(out_dir) / "results.json");
  if (!in) return out;
  try {
    nlohmann::json j = nlohmann::json::parse(in);
    for (auto& r : j.at("results"))
      if (r.contains("wall_s") && r["wall_s"].is_number())
        out[row_key_of(r)] = r["wall_s"].get<double>();
  } catch (const std::exception&) {
    return {};  // an unreadable old results.json only costs the ETA
  }
  return out;
}

SuiteProgress::SuiteProgress(std::vector<std::pair<std::string, double>> expected, unsigned jobs, bool live,
                             bool quiet)
    : total_(expected.size()), jobs_(std::max(1u, jobs)), live_(live && !quiet), quiet_(quiet),
      start_(std::chrono::steady_clock::now()) {
  for (auto& [k, s] : expected) expected_[k] = s;
}

double SuiteProgress::elapsed_s() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void SuiteProgress::started(const std::string& key) {
  running_[key] = Running{"", 0, 0, std::chrono::steady_clock::now()};
  draw(true);
}

void SuiteProgress::frame(const std::string& key, const std::string& what, uint32_t done, uint32_t total) {
  Running& r = running_[key];
  r.what = what;
  r.done = done;
  r.total = total;
  draw(false);
}

double SuiteProgress::eta_s() const {
  // Expected seconds of what is left, scaled by how the finished rows compared with their
  // expectation, spread over the workers.
  double left = 0;
  const auto now = std::chrono::steady_clock::now();
  for (auto& [k, s] : expected_) {
    auto it = running_.find(k);
    double ran = it == running_.end() ? 0 : std::chrono::duration<double>(now - it->second.since).count();
    left += std::max(0.0, s - ran);
  }
  const double scale = done_expected_ > 0 ? std::clamp(done_actual_ / done_expected_, 0.25, 4.0) : 1.0;
  return left * scale / double(jobs_);
}

void SuiteProgress::clear_line() {
  if (!line_shown_) return;
  std::fputs("\r\033[K", stderr);
  std::fflush(stderr);
  line_shown_ = false;
}

void SuiteProgress::draw(bool force) {
  if (!live_) return;
  const auto now = std::chrono::steady_clock::now();
  if (!force && now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  std::string running;
  for (auto& [k, r] : running_) {
    if (!running.empty()) running += ", ";
    running += k;
    if (r.total) running += fmt::format(" {}{}/{}", r.what.empty() ? "frame " : r.what + " ", r.done, r.total);
  }
  std::string line = fmt::format("[{}/{}] {} elapsed, ETA {} | {}", done_.size(), total_, format_duration(elapsed_s()),
                                 format_duration(eta_s()), running);
  if (line.size() > 160) line = line.substr(0, 157) + "...";
  std::fprintf(stderr, "\r\033[K%s", line.c_str());
  std::fflush(stderr);
  line_shown_ = true;
}

void SuiteProgress::finished(const RowLine& row) {
  running_.erase(row.key);
  done_.push_back({row.key, row.wall_s});
  if (auto it = expected_.find(row.key); it != expected_.end()) {
    done_expected_ += it->second;
    done_actual_ += row.wall_s;
    expected_.erase(it);
  }
  if (quiet_) return;
  clear_line();
  const size_t width = std::to_string(total_).size();
  fmt::print("[{:>{}}/{}] {:<13} {:>6.1f} s  {}{}{}\n", done_.size(), width, total_, row.status, row.wall_s, row.key,
             row.figures.empty() ? "" : "  ", row.figures);
  if (row.status != "pass")
    for (auto& m : row.messages) fmt::print("      {}\n", m);
  std::fflush(stdout);
  draw(true);
}

void SuiteProgress::print_slowest(size_t n) {
  if (quiet_ || done_.empty()) return;
  clear_line();  // the run is over: the live line gives way to the summary
  std::vector<std::pair<std::string, double>> rows = done_;
  std::sort(rows.begin(), rows.end(), [](auto& a, auto& b) { return a.second > b.second; });
  double sum = 0;
  for (auto& r : rows) sum += r.second;
  fmt::print("slowest rows (of {}, {:.0f} s of row time in {} wall):\n", rows.size(), sum, format_duration(elapsed_s()));
  for (size_t i = 0; i < std::min(n, rows.size()); ++i) fmt::print("  {:>7.1f} s  {}\n", rows[i].second, rows[i].first);
  std::fflush(stdout);
}

}  // namespace gib
