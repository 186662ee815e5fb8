// What a suite run shows while it runs: one line per finished row on stdout (as soon as it
// ends, so a CI log follows the run), and on a terminal a live line on stderr (rows done of all,
// the running rows with their frame, elapsed time, ETA from the last run's recorded row times),
// redrawn at most 10 times a second. At the end, the slowest rows with their wall times.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace gib {

// A finished row as the progress output shows it.
struct RowLine {
  std::string key;
  std::string status;
  double wall_s = 0;
  std::string figures;                // "FLIP ref 0.0123  GPU 1.23 ms"
  std::vector<std::string> messages;  // printed under the row unless it passed
};

class SuiteProgress {
 public:
  // `expected`: seconds per row key (the last run's wall times, else the plan's estimate), in the
  // order rows will be listed; `jobs`: rows running at once (for the ETA). `live`: draw the
  // live line (stderr is a terminal). `quiet`: print nothing (a worker process: its parent prints).
  SuiteProgress(std::vector<std::pair<std::string, double>> expected, unsigned jobs, bool live, bool quiet = false);
  void started(const std::string& key);
  void frame(const std::string& key, const std::string& what, uint32_t done, uint32_t total);
  void finished(const RowLine& row);
  // The slowest rows (up to n) with their wall times, and the run's total.
  void print_slowest(size_t n = 10);
  double elapsed_s() const;

 private:
  struct Running {
    std::string what;
    uint32_t done = 0, total = 0;
    std::chrono::steady_clock::time_point since;
  };
  void draw(bool force);
  void clear_line();
  double eta_s() const;

  std::map<std::string, double> expected_;  // rows not finished yet
  size_t total_;
  unsigned jobs_;
  bool live_, quiet_;
  std::chrono::steady_clock::time_point start_, last_draw_{};
  std::map<std::string, Running> running_;
  std::vector<std::pair<std::string, double>> done_;  // key, wall s
  double done_expected_ = 0, done_actual_ = 0;
  bool line_shown_ = false;
};

// "1:05" / "12:03" / "1:02:03".
std::string format_duration(double seconds);

// Each row's wall time recorded by the run whose results.json lies in `out_dir` ({} when there is
// none or it records none): the ETA of the next run.
std::map<std::string, double> recorded_row_seconds(const std::string& out_dir);

}  // namespace gib
