// Console profiles (data/console-profiles.json) and the seed per-pass timings
// (data/seed-timings.json), and the scaling model that maps a pass measured on this
// device to a profile (bench/README.md). Errors are PerfError naming the file and JSON field.
#pragma once
#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace gib::perf {

struct PerfError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct ConsoleProfile {
  std::string name, label;
  double fp32_tflops = 0, bandwidth_gbs = 0;
  // Raster fill rate in Gpixel/s: rops x clock_ghz (public figures), 0 where the file gives no
  // ROP count; a raster pass then scales by the FLOP / bandwidth split like a compute pass.
  double fill_gpix = 0;
  uint32_t width = 0, height = 0;               // targets.resolution
  std::optional<uint32_t> probes_per_frame;     // targets.probes_per_frame
  std::optional<double> gi_trace_scale;         // targets.gi_trace_scale
  std::vector<uint32_t> wave_size;
  // Threads resident at once: compute_units x resident_threads_per_cu, 0 where the file gives
  // neither (the occupancy term is then not applied for this profile).
  uint64_t resident_threads = 0;
};

// Profiles in file order. `file` only names the source in messages.
std::vector<ConsoleProfile> parse_profiles(const std::string& text, const std::string& file);
std::vector<ConsoleProfile> load_profiles(const std::string& path);
// "all" or a comma-separated list of names; PerfError listing the known names otherwise.
std::vector<ConsoleProfile> select_profiles(const std::vector<ConsoleProfile>& all, const std::string& names);

// The seed talks' per-pass tables (data/seed-timings.json) that `bench` compares with: each
// belongs to one of our techniques and maps its passes to the table's rows.
//   idtech8_gi_hotspot      radiance-cache; one row set per platform (its own resolution)
//   doom_visibility_buffer  deferred; the "Siege" table (Xbox Series X, 2560x1440) with a
//                           column per value of the technique's `vrcs` option
//   ac_shadows_probe_update probe-volume; per platform (its probes_per_frame budget), at 2560x1440
//   ac_shadows_diffuse_gi   probe-volume; per platform (its own resolution; quarter-res rays)
//   god_of_war_ragnarok     gow-ragnarok; PS5 at 3840x2160 (the table's own workload, not the
//                           ps5 profile's 2560x1440: bench runs it as an extra workload); columns
//                           shot_1 / shot_2 (the shadow captions' two views) and rt_cubemaps
//                           (the reflections' profiler capture), every column compared
struct SeedPlatform {
  std::string profile;  // console-profiles.json name
  std::string column;   // "" (one column) or the column's name ("no_vrcs", "vrcs")
  uint32_t width = 0, height = 0;
  std::map<std::string, double> ms;  // seed row -> ms
};
struct SeedTable {
  std::string name;       // key in seed-timings.json
  std::string source;     // where the seed talk printed it
  std::string technique;  // our technique whose passes it times
  // Our pass -> the seed row whose cost it is part of (several passes may share a row: their
  // costs are summed before comparing). Passes not listed have no counterpart in this table.
  std::map<std::string, std::string> pass_row;
  // The option of `technique` that picks the column, and the column for each of its values
  // ("" : the table has one column).
  std::string column_option;
  std::map<double, std::string> column_of_value;
  std::string total_row;  // the row holding the seed's own total ("" : none)
  // A table with no column option compares every column it holds for a profile (each is its own
  // capture: GoW Ragnarok's two shadow views and its reflection capture).
  // own_workload: the table's resolution is not the profile's target (GoW Ragnarok's PS5 at 4K):
  // bench runs that resolution as an extra workload for the table's technique and profiles,
  // and compares the table only there.
  bool own_workload = false;
  std::vector<SeedPlatform> platforms;
  const SeedPlatform* find(const std::string& profile, const std::string& column = "") const;
};
// Every table bench knows, in this order; PerfError naming the file and JSON field when one is
// missing or malformed (a table's other keys are left alone).
std::vector<SeedTable> parse_seed_tables(const std::string& text, const std::string& file);
std::vector<SeedTable> load_seed_tables(const std::string& path);

// AC Shadows' alpha-test cost table (ac_shadows_alpha_test_cost): each strategy's ray tracing
// cost relative to the full alpha test, on an NVIDIA GPU. Rows keyed by our option values
// (alpha_strategy, alpha_any_hit_limit): (0, 2) any_hit_limit_2, (0, 4) any_hit_limit_4,
// (1, 0) dither_average_opacity, (1, 2) dither_plus_any_hit_limit_2, (2, 0) opaque_approximation.
struct AlphaCostTable {
  std::string source;
  std::map<std::pair<uint32_t, uint32_t>, std::pair<std::string, double>> relative;  // (strategy, limit) -> row, cost
};
AlphaCostTable parse_alpha_cost_table(const std::string& text, const std::string& file);
AlphaCostTable load_alpha_cost_table(const std::string& path);

// ---- the scaling model
struct DeviceThroughput {
  double fp32_gflops = 0;    // achieved FP32 rate (calibrated)
  double bandwidth_gbs = 0;  // achieved copy bandwidth (calibrated)
  double fill_gpix = 0;      // achieved raster fill rate (calibrated; 0: not measured)
  uint64_t resident_threads = 0;  // DeviceInfo::resident_threads (0: the driver does not say)
};
struct PassSplit {
  double device_ms = 0;   // measured, at the profile's workload
  double bytes = 0;       // bytes the pass reads + writes (from the plan)
  double memory_ms = 0;   // min(device_ms, bytes / device bandwidth)
  double compute_ms = 0;  // device_ms - memory_ms
};
PassSplit split_pass(double device_ms, double bytes, const DeviceThroughput& dev);
// memory_ms x device_bw / console_bw + compute_ms x device_flops / console_flops x occupancy,
// where occupancy is the pass's occupancy term (perf/occupancy.h; 1: the plain FLOP split).
double scale_to_profile(const PassSplit& s, const DeviceThroughput& dev, const ConsoleProfile& p, double occupancy = 1);
// A rasterising pass (PassKind::graphics): its time is set by the fixed-function raster and ROP
// rate, which a FLOP split does not see (an H100 rasterises through a few graphics-capable
// units). device_ms x device fill rate / profile fill rate, when both are known; else nullopt
// (the caller falls back to scale_to_profile and says so).
std::optional<double> scale_raster_to_profile(double device_ms, const DeviceThroughput& dev, const ConsoleProfile& p);

// Where the profile and seed data live: --data-dir, else $GIB_DATA_DIR, else the first of
// ./data (the working folder's, as for cases: perf/project_files.h), <executable dir>/data or
// <executable dir>/../data (a pack from ci/pack_gpu.sh, a build folder) and <source>/data (the
// tree the binary was built from). PerfError listing every folder tried when none has
// console-profiles.json.
std::string find_data_dir(const std::string& override_dir);

}  // namespace gib::perf
