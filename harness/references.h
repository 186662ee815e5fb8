// A case's path-traced references at each tier: where they are read from (the committed
// goldens at the CI tier, a local cache keyed by everything that changes them at the GPU tier),
// how a GPU-tier reference is rendered to the noise-floor rule, and `gibench references`.
#pragma once
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "harness/tier.h"

namespace gib {

class Gpu;

// The reference cache's root: `requested` (--reference-cache), else $GIBENCH_REFERENCE_CACHE,
// else $XDG_CACHE_HOME/gibench/references, else $HOME/.cache/gibench/references.
std::string reference_cache_root(const std::string& requested);
// Changes whenever what the path tracer renders for a given scene and seed may change: the
// SPIR-V of the reference technique's passes, its ultra preset and kPathTracerCpuRevision.
std::string path_tracer_revision();

// How a GPU-tier reference is rendered: the noise floor it must reach (the case's limit,
// kReferenceNoiseFloorMax, and a third of its tightest whole-image flip bound against the
// reference: kNoiseFloorFactor) and the spp predicted from the committed CI-tier reference's
// recorded spp and floor (noise per pixel does not depend on the image size; FLIP of noise
// falls about as 1/sqrt(spp)). The prediction overshoots at 640x360 (measured on an H100: the
// same spp gives a floor about 2x lower than at 128x72), so rendering starts with a pilot at
// 1/64 of it (pilot_spp) and, while the measured floor is above the target, renders again at the
// spp the pilot's floor predicts (next_spp), up to the budget.
inline constexpr uint32_t kReferenceSppMax = 1048576;
struct ReferenceRequest {
  double target_floor = kReferenceNoiseFloorMax;
  uint32_t start_spp = 0;
  // The most spp this request renders (`gibench references --max-spp`, a budget): a reference
  // that stops short of its target is kept, recorded as not converged and reported so by every
  // run that uses it. Not part of the key: a later request with a larger budget refines it.
  uint32_t max_spp = kReferenceSppMax;
  // The first render's spp (0: pilot_spp(start_spp)); refining an entry short of its target
  // starts where its measured floor points (next_spp). Not part of the key.
  uint32_t first_spp = 0;
};
ReferenceRequest reference_request(const Case& c_at_tier, const nlohmann::json& committed_meta);
inline constexpr uint32_t kReferencePilotMin = 1024;
// The first render: start_spp / 64 (kReferencePilotMin at least); start_spp itself when small.
uint32_t pilot_spp(uint32_t start_spp);
// After a render at `spp` measured `floor` above the target: the spp that puts it at 0.9 x the
// target (1/sqrt law), a multiple of 4096, at least 2 x spp, at most req.max_spp.
uint32_t next_spp(uint32_t spp, double floor, const ReferenceRequest& req);

// Everything that changes a GPU-tier reference (scene contents, size, seed, frames rendered,
// AOVs, the request above, the path tracer revision), and its hash: the cache entry's name.
nlohmann::json reference_key_inputs(const Case& c_at_tier, const ReferenceRequest& req);
std::string reference_key(const nlohmann::json& inputs);

// The store a case's references are read from at the tier: the committed goldens/<case> (ci),
// or the cache entry <cache root>/<case>/<key> (gpu).
struct ReferenceSource {
  GoldenStore store;
  std::string key;  // gpu: the cache key ("" at ci)
  nlohmann::json inputs;
  ReferenceRequest request;
};
ReferenceSource reference_source(const std::string& goldens_dir, const std::string& cache_root, const Case& c_at_tier,
                                 Tier t);

// True when the entry holds every reference file the case compares with, each with its record in
// golden.json (GoldenStore::record_of), and a noise floor.
bool references_present(const Case& c_at_tier, const ReferenceSource& src);
// The entry's noise floor: the worst over the AOVs the case compares with (infinity when none
// is recorded); converged when it is at most the request's target.
double reference_floor(const Case& c_at_tier, const ReferenceSource& src);
bool references_converged(const Case& c_at_tier, const ReferenceSource& src);

// Renders the case's GPU-tier references into its cache entry: at the request's start spp,
// measures the floor (FLIP between seeds reference_seed and +1000, the worst AOV), and while it
// is above the target renders again at 4x the spp (kReferenceSppMax at most; above it the entry
// is written with the floor it reached and a warning is returned). Writes golden.json with the
// key inputs, spp, floor, device and driver. `progress` (may be empty) sees each render's frames.
// Returns a one-line summary.
using RenderProgress = std::function<void(const std::string& what, uint32_t done, uint32_t total)>;
std::string render_references(Gpu& gpu, const Case& c_at_tier, ReferenceSource& src, const RenderProgress& progress);

// The case's references at the tier, ready to read: at the GPU tier, those the cache lacks are
// rendered first (render_references, its line printed). *rendered (if given): whether they were.
ReferenceSource prepare_references(Gpu& gpu, const std::string& goldens_dir, const std::string& cache_root,
                                   const Case& c_at_tier, Tier t, bool* rendered = nullptr);

// `gibench references`: for each selected case, the GPU-tier references' cache entry: present
// (key, spp, floor) or rendered now; `refresh` re-renders present ones. Exit 1 when a reference
// did not reach its target floor. `dry_run`: print each case's size, target floor, start spp,
// key and whether it is cached; render nothing.
struct SuiteOptions;
// `max_spp`: the budget (ReferenceRequest::max_spp); an entry short of its target is refined
// when the budget allows more than it holds.
int cmd_references(const SuiteOptions& o, bool refresh, bool dry_run, uint32_t max_spp = kReferenceSppMax);

// A progress bar on stderr when it is a terminal (one line redrawn), else nothing.
RenderProgress terminal_progress(const std::string& label);

}  // namespace gib
