// `gibench bench` and `gibench perf-diff` (also built into gibench-perf, which links no
// image libraries so it can be carried to a GPU machine; see bench/README.md).
//
// bench: runs every technique's passes at each console profile's workload, times them
// (median of frames after warm-up, repeated), splits each pass into memory and compute time
// with the calibrated device throughput, scales both to every profile, compares with the seed
// timings, measures its own noise floor, writes JSON (all samples) and appends a history line.
// perf-diff: per pass, a Mann-Whitney rank test between two such files (or Google Benchmark
// JSON with repetitions); flags changes outside noise; exit 1 on any regression.
#pragma once
#include <cstdint>
#include <map>
#include <optional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "renderer/graph/graph.h"

namespace gib {
struct Technique;
}

namespace gib::perf {

struct BenchOptions {
  std::string profiles = "all";
  std::vector<std::string> techniques;  // empty: every technique
  // "LABEL:NAME=VALUE[,NAME=VALUE...]": every technique is also timed with these technique
  // options, interleaved with the plain run in each repeat, and compared with it per pass.
  std::vector<std::string> variants;
  // Contract AOVs to plan (--aov, repeatable): empty plans every contract AOV of each technique
  // that the scene supports (bench_outputs), so passes that only feed an AOV other than
  // radiance are timed too.
  std::vector<std::string> aovs;
  std::string case_name = "cornell";    // a case (cases/<name>.json), a scene, or a path (resolve_case_scene)
  std::string preset = "medium";
  uint32_t frames = 0;        // timed frames per repeat (0: 5 on a CPU device, 30 on a GPU)
  uint32_t repeats = 2;       // fresh executor each; >= 2 gives the noise floor
  uint32_t warmup = 0;        // frames before timing (0: 1 on a CPU device, 5 on a GPU)
  std::string scale_resolution;  // "1/8" or "0.125"; "" auto: 1 on a GPU, 1/8 on a CPU device
  std::string json;              // write the run here
  std::string budget_html;       // write the budget trees (data/budgets.json) as an HTML page here
  std::string history;           // "": bench/history.jsonl (default_history_path)
  bool no_history = false;
  std::string device;
  std::string data_dir;
  uint32_t calibration_repeats = 7;
  double min_change = 0.02;
};
int cmd_bench(const BenchOptions& o);

// One --variant: "LABEL:NAME=VALUE[,NAME=VALUE...]"; PerfError names the flag and what was
// expected (option names are checked against each technique when the runs are built).
struct BenchVariant {
  std::string label;
  std::map<std::string, double> options;
};
BenchVariant parse_variant(const std::string& text);

// What bench plans for technique `t` in a scene with `features`: the contract AOVs
// (renderer/techniques/aov.h) the scene supports (contract_aov_names(t, features)), narrowed to
// `only` when it is not empty (--aov; a name outside the contract is a PerfError naming the
// flag; one the technique lacks or the scene cannot produce is left out and listed).
struct BenchOutputs {
  std::vector<std::string> aovs;       // planned, radiance first (empty: nothing to time)
  std::vector<std::string> resources;  // the executor's outputs: the AOVs' resources, once each
  std::vector<std::string> left_out;   // "NAME (why)" for asked or contract AOVs not planned
};
BenchOutputs bench_outputs(const Technique& t, SceneFeatures features, const std::vector<std::string>& only = {});

struct DiffOptions {
  std::string base, next;
  double confidence = 0.95;
  double min_change = 0.02;
};
// 0: no regression; 1: at least one; errors throw.
int cmd_perf_diff(const DiffOptions& o);

// Bytes a running pass touches per frame: resources it reads (read, read_write, read_prev; one
// copy each) and the plan's bytes_written. A slot that declares a sparse access (Slot::touched)
// counts the bytes it moves instead of the resource's size, once `counters` (the run's
// GPU-counted work by name: PassDecl::measured, read back by bench) are known; without them, or
// when its counter was not measured, the resource's size (and `unresolved` names the slot).
struct PassBytes {
  uint64_t read = 0, written = 0;
  uint64_t total() const { return read + written; }
  std::vector<std::string> sparse;      // "slot: N bytes (E elements)" for each touched slot counted
  std::vector<std::string> unresolved;  // touched slots counted at full size: their counter is unknown
};
PassBytes pass_bytes(const Plan& plan, const PlannedPass& pass,
                     const std::map<std::string, double>* counters = nullptr);
// The elements a sparse access moves (Slot::touched) given the measured counters; nullopt when
// one of its counters is not among them.
std::optional<double> touched_elements(const Touched& t, const std::map<std::string, double>& counters);
// The bytes those elements move: elements x element_bytes (rounded up to a 32-byte sector
// unless contiguous), at most `resource_bytes`.
uint64_t touched_bytes(const Touched& t, double elements, uint64_t resource_bytes);

// Samples per benchmark key from a `gibench bench --json` file ("<technique>/<pass>/<WxH>",
// ms per frame) or a Google Benchmark JSON file (run_name, one sample per repetition, ms).
// Throws PerfError naming the file and field on malformed input.
struct SampleFile {
  std::string format;  // "gibench-perf-1" or "google-benchmark"
  std::string device;
  std::map<std::string, std::vector<double>> samples;
  std::map<std::string, double> detectable;  // noise floor per key, when the file has one
};
SampleFile parse_sample_file(const std::string& text, const std::string& file);
SampleFile load_sample_file(const std::string& path);

// "1/8", "0.125", "1" -> fraction in (0, 1]; PerfError otherwise.
double parse_scale(const std::string& text);

}  // namespace gib::perf
