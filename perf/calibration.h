// Calibration micro-kernels (perf/calibrate_fma.comp, calibrate_fma_scalar.comp, calibrate_copy.comp,
// calibrate_dispatch.comp, calibrate_raster.vert/.frag): the measuring device's achieved FP32 FMA
// rate, copy bandwidth, dispatch latency and raster fill rate (pixels written through depth test), median of repeats. Every
// `gibench bench` run records them, since the console-scaling model divides by them.
#pragma once
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "perf/profiles.h"
#include "renderer/vk/gpu.h"

namespace gib::perf {

struct Calibration {
  DeviceThroughput throughput;
  std::string timing;           // "timestamps" (GPU) or "host clock" (CPU device)
  uint32_t repeats = 0;
  uint64_t fma_threads = 0, fma_iterations = 0;
  double fma_flops = 0;         // per dispatch
  std::vector<double> fma_ms;   // every repeat (calibrate_fma.comp: vec4 chains)
  std::vector<double> fma_scalar_ms;  // every repeat, interleaved (calibrate_fma_scalar.comp: scalar chains)
  double fma_gflops = 0, fma_scalar_gflops = 0;  // each kernel's median rate; fp32_gflops is the larger
  // Dispatch latency (calibrate_dispatch.comp): a chain of kCalibDispatchChain one-group
  // dispatches that do nothing, each behind a compute -> compute barrier; chain_ms per repeat,
  // dispatch_latency_ms = median / chain length. What every dispatch of a pass costs before its
  // work (launch, the barrier's drain, the ramp). GPU only (0: not measured).
  std::vector<double> dispatch_chain_ms;
  double dispatch_latency_ms = 0;
  uint64_t copy_bytes = 0;      // per dispatch (read + write)
  std::vector<double> copy_ms;
  // Raster fill rate (calibrate_raster.vert/.frag): `raster_layers` full-screen triangles over a
  // raster_width x raster_height rg32_uint + D32 target per draw, every fragment written.
  uint32_t raster_width = 0, raster_height = 0, raster_layers = 0;
  std::vector<double> raster_ms;
  double fill_gpix_of(const std::vector<double>& ms) const;  // Gpixel/s at the median of ms
  nlohmann::json to_json() const;
  static Calibration from_json(const nlohmann::json& j);
};

// Times one dispatch of each kernel `repeats` times after tuning its size to ~20 ms (GPU, after
// ~0.5 s of warm-up so the clocks have ramped) or ~100 ms (CPU device); the rates come from the
// median time. FP32 is measured by two differently written kernels, interleaved; the device's
// rate is the larger median and both are recorded (they should agree within a few percent).
Calibration calibrate(Gpu& gpu, uint32_t repeats = 7);

// One dispatch of `groups` workgroups, in ms: timestamps on a GPU, the host clock around
// submit-and-wait on a CPU device (llvmpipe's timestamps misattribute its lazily-run work).
double time_dispatch(Gpu& gpu, const Pipeline& pipeline, const std::vector<Bind>& binds, const void* push,
                     uint32_t push_bytes, uint32_t groups);

// The raster calibration's pipeline (calibrate_raster.vert/.frag: rg32_uint colour, D32 depth)
// and one draw of `layers` full-screen triangles, front to back, into color + depth (cleared
// first), in ms as time_dispatch. Every fragment of every layer passes the depth test, so a
// draw writes layers x width x height pixels; the last layer's id is what the target holds.
std::shared_ptr<Pipeline> raster_calibration_pipeline(Gpu& gpu);
double time_raster(Gpu& gpu, const Pipeline& pipeline, const Image& color, const Image& depth, uint32_t layers);

}  // namespace gib::perf
