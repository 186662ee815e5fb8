// Rendering one case x technique x preset (x options) on a Gpu: shared by run,
// update-goldens, the noise floor and sweep.
#pragma once
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "harness/case.h"
#include "harness/render.h"
#include "perf/frame_timing.h"
#include "renderer/graph/executor.h"
#include "renderer/graph/stability.h"

namespace gib {

struct CaseRender {
  std::string technique, preset;
  FloatImage image;                  // the compared output (technique output, or a reference AOV)
  std::map<std::string, FloatImage> aovs;  // reference: every AOV
  std::vector<PassStats> passes;     // over timing.frames
  Plan plan;
  Settings settings;                 // what the executor ran with, and the outputs it was asked for
  std::vector<std::string> outputs;
  double frame_median_ms = 0;        // over timing.frames
  double gpu_ms_total = 0;           // sum over the case's frames (reference: the whole convergence)
  perf::FrameTiming timing;          // the frames GPU times come from (render_case says which)
  uint32_t frames = 0, spp = 0;
  std::string settings_hash;
  uint64_t texture_bytes = 0;  // the scene's packed image textures on the GPU (Executor::texture_bytes)
  // Non-reference runs, from the case's tracking fields:
  std::map<uint32_t, FloatImage> frame_images;  // Case::eval_frames (1-based) -> output then
  std::vector<double> curve;                    // Case::convergence: ROI mean luminance per frame
  std::vector<FloatImage> last_frames;          // Case::flicker_frames: the last N outputs
  std::vector<double> nan_pixels;               // Case::track_nan: NaN pixels of the output per frame
  bool scanned = false;
  StabilityReport stability;                    // when rendered with scan = true
  std::map<std::string, double> stats;          // Technique::stats at the last frame (those in the plan)
  std::map<std::string, FloatImage> views;      // Technique::views at the last frame (those in the plan)
  std::map<std::string, std::string> printouts; // Technique::printouts at the last frame (those in the plan)
  std::map<std::string, std::vector<uint8_t>> read;  // RunHooks::read: raw bytes after the last frame
  std::vector<std::map<std::string, std::vector<uint8_t>>> read_before;  // the same after the frames before it
};

// Error attribution's access to a technique run (harness/attribution/): graph overrides in
// place from the first frame (Executor::add_override), and resources whose raw bytes are read
// after the last frame (Executor::read_bytes), and after the `read_frames` - 1 frames before it
// too (CaseRender::read_before). A hooked run renders no timing frames.
// `frozen_frame` (1-based, 0 = off) holds a moving scene as it is at that frame of the case, as
// its per-frame reference shows it: the technique's converged state there (a lag oracle's input).
struct RunHooks {
  std::vector<ResourceOverride> overrides;
  std::vector<std::string> read;
  uint32_t read_frames = 1;
  uint32_t frozen_frame = 0;
};

// Frames a row records into one GPU submission at most (Executor::run_frames), process-wide
// (`gibench run --frames-per-submission`; default 64). A frame whose output the host reads
// (an evaluated frame, a curve point, a hook) always ends a submission. At least 1.
void set_frames_per_submission(uint32_t n);

// `progress` (may be empty) is called after each frame with (frames done, frames in all).
using FrameProgress = std::function<void(uint32_t done, uint32_t total)>;

// A technique run of the case (`gibench run`, sweep, update-goldens of a technique golden):
// the case's frames at the preset; a reference (path tracer) row with TechniqueRun::spp renders
// that many samples per pixel instead (split over frames), seeded with the case's seed
// (seed_offset shifts it). `scan`: the stability scan during the case's frames.
CaseRender render_case(Gpu& gpu, const Case& c, const TechniqueRun& run, const std::string& preset,
                       uint32_t seed_offset = 0, uint32_t at_frame = 0, bool scan = false,
                       const FrameProgress& progress = {});
CaseRender render_case_hooked(Gpu& gpu, const Case& c, const TechniqueRun& run, const std::string& preset,
                              uint32_t seed_offset, const RunHooks& hooks);
// The committed path-traced reference: technique "reference", preset ultra, the case's
// reference_spp and reference_seed (seed_offset shifts it: the noise floor renders twice);
// at_frame (1-based) renders the scene as it is at that frame of a technique run (a per-frame
// reference of an animated scene; 0 = the scene's first frame, time 0). Every contract AOV is
// in CaseRender::aovs.
CaseRender render_reference(Gpu& gpu, const Case& c, uint32_t seed_offset = 0, uint32_t at_frame = 0,
                            const FrameProgress& progress = {});

// The 1-based frames a technique run is evaluated at: Case::eval_frames, or {frames}.
std::vector<uint32_t> evaluation_frames(const Case& c);
// The image a technique run produced at evaluation frame `f` (its final image at the case's last
// frame); a CaseError when the run did not capture it.
const FloatImage& image_at(const CaseRender& r, uint32_t f, const Case& c);
// True when the case's evaluation frames need references of their own (the scene moves).
bool per_frame_references(const Case& c);

}  // namespace gib
