#include "perf/calibration.h"

#include <chrono>

#include "bench/calibration_shared.h"
#include "perf/stats.h"
#include "renderer/graph/pass.h"

namespace gib::perf {
namespace {

// One dispatch, timed by timestamps on a GPU and by the host clock around submit-and-wait on
// a CPU device (llvmpipe's timestamps misattribute its lazily-run work; see Executor).
double time_dispatch(Gpu& gpu, const Pipeline& pipeline, const std::vector<Bind>& binds, const void* push,
                     uint32_t push_bytes, uint32_t groups) {
  auto cmd = gpu.begin(2);
  cmd->bind(pipeline, binds, push, push_bytes);
  cmd->timestamp(0);
  cmd->dispatch(groups);
  cmd->timestamp(1);
  auto t0 = std::chrono::steady_clock::now();
  auto ns = gpu.submit(std::move(cmd));
  if (gpu.info().is_software() || ns.size() < 2)
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return (ns[1] - ns[0]) * 1e-6;
}

}  // namespace

Calibration calibrate(Gpu& gpu, uint32_t repeats) {
  Calibration c;
  c.repeats = std::max(1u, repeats);
  const bool cpu = gpu.info().is_software();
  c.timing = cpu ? "host clock" : "timestamps";
  const double target_ms = cpu ? 100.0 : 5.0;

  {  // FP32 FMA rate
    const uint32_t groups = cpu ? 64 : 8192;
    c.fma_threads = uint64_t(groups) * glsl::kCalibGroup;
    auto out = gpu.create_buffer(c.fma_threads * 4, BufferUsage::storage, "calib_fma_out");
    ComputePipelineDesc desc{"calibrate_fma.comp", {{glsl::kCalibBindOut, DescriptorKind::storage_buffer}},
                             sizeof(glsl::CalibFmaPush)};
    auto pipe = gpu.compute_pipeline(desc);
    std::vector<Bind> binds{{glsl::kCalibBindOut, out.get(), nullptr}};
    glsl::CalibFmaPush push{16, 0.999f, 1e-3f, 0};
    time_dispatch(gpu, *pipe, binds, &push, sizeof(push), groups);  // warm-up (lazy compile)
    for (;;) {
      double ms = time_dispatch(gpu, *pipe, binds, &push, sizeof(push), groups);
      if (ms >= target_ms || push.iterations >= (1u << 22)) break;
      push.iterations *= ms < target_ms / 8 ? 8 : 2;
    }
    c.fma_iterations = push.iterations;
    c.fma_flops = double(c.fma_threads) * double(push.iterations) * glsl::kCalibFmaChains * 4 * 2;
    for (uint32_t r = 0; r < c.repeats; ++r)
      c.fma_ms.push_back(time_dispatch(gpu, *pipe, binds, &push, sizeof(push), groups));
    c.throughput.fp32_gflops = c.fma_flops / (median_of(c.fma_ms) * 1e-3) * 1e-9;
  }
  {  // copy bandwidth: buffers far larger than any last-level cache
    const uint64_t bytes = cpu ? (128ull << 20) : (1ull << 30);
    const uint32_t count = uint32_t(bytes / 16);
    auto src = gpu.create_buffer(bytes, BufferUsage::storage, "calib_copy_src");
    auto dst = gpu.create_buffer(bytes, BufferUsage::storage, "calib_copy_dst");
    {
      auto cmd = gpu.begin(0);
      cmd->fill(*src, 0x3f800000u);
      cmd->fill(*dst, 0);
      gpu.submit(std::move(cmd));
    }
    ComputePipelineDesc desc{"calibrate_copy.comp",
                             {{glsl::kCalibBindSrc, DescriptorKind::storage_buffer},
                              {glsl::kCalibBindDst, DescriptorKind::storage_buffer}},
                             sizeof(glsl::CalibCopyPush)};
    auto pipe = gpu.compute_pipeline(desc);
    std::vector<Bind> binds{{glsl::kCalibBindSrc, src.get(), nullptr}, {glsl::kCalibBindDst, dst.get(), nullptr}};
    glsl::CalibCopyPush push{count, 0, 0, 0};
    const uint32_t groups = std::min<uint32_t>(div_up(count, glsl::kCalibGroup), cpu ? 65535u : 32768u);
    time_dispatch(gpu, *pipe, binds, &push, sizeof(push), groups);  // warm-up
    c.copy_bytes = 2 * uint64_t(count) * 16;
    for (uint32_t r = 0; r < c.repeats; ++r)
      c.copy_ms.push_back(time_dispatch(gpu, *pipe, binds, &push, sizeof(push), groups));
    c.throughput.bandwidth_gbs = double(c.copy_bytes) / (median_of(c.copy_ms) * 1e-3) * 1e-9;
  }
  return c;
}

nlohmann::json Calibration::to_json() const {
  return {{"fp32_gflops", throughput.fp32_gflops},
          {"bandwidth_gbs", throughput.bandwidth_gbs},
          {"timing", timing},
          {"repeats", repeats},
          {"fma", {{"threads", fma_threads}, {"iterations", fma_iterations}, {"flops", fma_flops}, {"ms", fma_ms}}},
          {"copy", {{"bytes", copy_bytes}, {"ms", copy_ms}}}};
}

Calibration Calibration::from_json(const nlohmann::json& j) {
  Calibration c;
  c.throughput.fp32_gflops = j.value("fp32_gflops", 0.0);
  c.throughput.bandwidth_gbs = j.value("bandwidth_gbs", 0.0);
  c.timing = j.value("timing", "");
  c.repeats = j.value("repeats", 0u);
  if (j.contains("fma")) {
    c.fma_threads = j["fma"].value("threads", uint64_t(0));
    c.fma_iterations = j["fma"].value("iterations", uint64_t(0));
    c.fma_flops = j["fma"].value("flops", 0.0);
    c.fma_ms = j["fma"].value("ms", std::vector<double>{});
  }
  if (j.contains("copy")) {
    c.copy_bytes = j["copy"].value("bytes", uint64_t(0));
    c.copy_ms = j["copy"].value("ms", std::vector<double>{});
  }
  return c;
}

}  // namespace gib::perf
