#include "perf/calibration.h"

#include <algorithm>
#include <chrono>

#include "perf/calibration_shared.h"
#include "perf/stats.h"
#include "renderer/graph/pass.h"

namespace gib::perf {

namespace {

// Runs cmd (timestamps 0 and 1 around its work) and returns the work's time in ms: timestamps
// on a GPU, the host clock around submit-and-wait on a CPU device.
double submit_timed(Gpu& gpu, std::unique_ptr<Cmd> cmd) {
  auto t0 = std::chrono::steady_clock::now();
  auto ns = gpu.submit(std::move(cmd));
  if (gpu.info().is_software() || ns.size() < 2)
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return (ns[1] - ns[0]) * 1e-6;
}

}  // namespace

double time_dispatch(Gpu& gpu, const Pipeline& pipeline, const std::vector<Bind>& binds, const void* push,
                     uint32_t push_bytes, uint32_t groups) {
  auto cmd = gpu.begin(2);
  cmd->bind(pipeline, binds, push, push_bytes);
  cmd->timestamp(0);
  cmd->dispatch(groups);
  cmd->timestamp(1);
  return submit_timed(gpu, std::move(cmd));
}

std::shared_ptr<Pipeline> raster_calibration_pipeline(Gpu& gpu) {
  GraphicsPipelineDesc desc;
  desc.vertex_shader = "calibrate_raster.vert";
  desc.fragment_shader = "calibrate_raster.frag";
  desc.push_constant_bytes = sizeof(glsl::CalibRasterPush);
  desc.color_formats = {Format::rg32_uint};
  desc.depth = true;
  return gpu.graphics_pipeline(desc);
}

double time_raster(Gpu& gpu, const Pipeline& pipeline, const Image& color, const Image& depth, uint32_t layers) {
  const glsl::CalibRasterPush push{layers, 0, 0, 0};
  const Image* colors[] = {&color};
  const float clear[4] = {0, 0, 0, 0};
  auto cmd = gpu.begin(2);
  cmd->timestamp(0);
  cmd->begin_rendering(colors, &depth, clear);
  cmd->bind(pipeline, {}, &push, sizeof(push));
  cmd->draw(3 * layers);
  cmd->end_rendering();
  cmd->timestamp(1);
  return submit_timed(gpu, std::move(cmd));
}

double Calibration::fill_gpix_of(const std::vector<double>& ms) const {
  if (ms.empty()) return 0;
  return double(raster_width) * raster_height * raster_layers / (median_of(ms) * 1e-3) * 1e-9;
}

Calibration calibrate(Gpu& gpu, uint32_t repeats) {
  Calibration c;
  c.repeats = std::max(1u, repeats);
  const bool cpu = gpu.info().is_software();
  c.timing = cpu ? "host clock" : "timestamps";
  const double target_ms = cpu ? 100.0 : 20.0;

  {  // FP32 FMA rate: two differently written kernels, interleaved; the faster median counts
    // On a GPU, first keep the ALUs busy for ~0.5 s so that the clocks have ramped up before
    // anything is timed (a 5 ms dispatch after idle measured an H100 at 2/3 of its FMA peak).
    const uint32_t groups = cpu ? 64 : 8192;
    c.fma_threads = uint64_t(groups) * glsl::kCalibGroup;
    auto out = gpu.create_buffer(c.fma_threads * 4, BufferUsage::storage, "calib_fma_out");
    std::vector<Bind> binds{{glsl::kCalibBindOut, out.get(), nullptr}};
    auto make = [&](const char* shader) {
      return gpu.compute_pipeline(ComputePipelineDesc{
          shader, {{glsl::kCalibBindOut, DescriptorKind::storage_buffer}}, sizeof(glsl::CalibFmaPush)});
    };
    auto vec4_pipe = make("calibrate_fma.comp");
    auto scalar_pipe = make("calibrate_fma_scalar.comp");
    const uint32_t scalar_groups = uint32_t(c.fma_threads / glsl::kCalibScalarGroup);
    glsl::CalibFmaPush push{16, 0.999f, 1e-3f, 0};
    time_dispatch(gpu, *vec4_pipe, binds, &push, sizeof(push), groups);  // lazy compile
    time_dispatch(gpu, *scalar_pipe, binds, &push, sizeof(push), scalar_groups);
    for (;;) {
      double ms = time_dispatch(gpu, *vec4_pipe, binds, &push, sizeof(push), groups);
      if (ms >= target_ms || push.iterations >= (1u << 22)) break;
      push.iterations *= ms < target_ms / 8 ? 8 : 2;
    }
    if (!cpu)
      for (double spent = 0; spent < 500.0;) spent += time_dispatch(gpu, *vec4_pipe, binds, &push, sizeof(push), groups);
    c.fma_iterations = push.iterations;
    c.fma_flops = double(c.fma_threads) * double(push.iterations) * glsl::kCalibFmaChains * 4 * 2;
    for (uint32_t r = 0; r < c.repeats; ++r) {
      c.fma_ms.push_back(time_dispatch(gpu, *vec4_pipe, binds, &push, sizeof(push), groups));
      c.fma_scalar_ms.push_back(time_dispatch(gpu, *scalar_pipe, binds, &push, sizeof(push), scalar_groups));
    }
    c.fma_gflops = c.fma_flops / (median_of(c.fma_ms) * 1e-3) * 1e-9;
    c.fma_scalar_gflops = c.fma_flops / (median_of(c.fma_scalar_ms) * 1e-3) * 1e-9;
    c.throughput.fp32_gflops = std::max(c.fma_gflops, c.fma_scalar_gflops);
  }
  if (!cpu) {  // dispatch latency: a chain of empty one-group dispatches, each behind a barrier
    auto out = gpu.create_buffer(4, BufferUsage::storage, "calib_dispatch_out");
    std::vector<Bind> binds{{glsl::kCalibBindOut, out.get(), nullptr}};
    auto pipe = gpu.compute_pipeline(ComputePipelineDesc{
        "calibrate_dispatch.comp", {{glsl::kCalibBindOut, DescriptorKind::storage_buffer}}, sizeof(glsl::CalibFmaPush)});
    const glsl::CalibFmaPush push{0xffffffffu, 1.0f, 0.0f, 0};
    auto chain = [&] {
      auto cmd = gpu.begin(2);
      cmd->bind(*pipe, binds, &push, sizeof(push));
      cmd->timestamp(0);
      for (uint32_t i = 0; i < glsl::kCalibDispatchChain; ++i) {
        cmd->barrier(kStageCompute, kStageCompute);
        cmd->dispatch(1);
      }
      cmd->timestamp(1);
      return submit_timed(gpu, std::move(cmd));
    };
    chain();  // lazy compile
    for (uint32_t r = 0; r < c.repeats; ++r) c.dispatch_chain_ms.push_back(chain());
    c.dispatch_latency_ms = median_of(c.dispatch_chain_ms) / glsl::kCalibDispatchChain;
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
  {  // raster fill rate: full-screen layers front to back through a D32 depth test
    c.raster_width = c.raster_height = cpu ? 256 : 4096;
    auto color = gpu.create_image(Format::rg32_uint, c.raster_width, c.raster_height, "calib_raster_color");
    auto depth = gpu.create_image(Format::d32_float, c.raster_width, c.raster_height, "calib_raster_depth");
    auto pipe = raster_calibration_pipeline(gpu);
    uint32_t layers = 4;
    time_raster(gpu, *pipe, *color, *depth, layers);  // lazy compile
    for (;;) {
      double ms = time_raster(gpu, *pipe, *color, *depth, layers);
      if (ms >= target_ms || layers >= (1u << 16)) break;
      layers *= ms < target_ms / 8 ? 8 : 2;
    }
    c.raster_layers = layers;
    for (uint32_t r = 0; r < c.repeats; ++r) c.raster_ms.push_back(time_raster(gpu, *pipe, *color, *depth, layers));
    c.throughput.fill_gpix = c.fill_gpix_of(c.raster_ms);
  }
  return c;
}

nlohmann::json Calibration::to_json() const {
  return {{"fp32_gflops", throughput.fp32_gflops},
          {"bandwidth_gbs", throughput.bandwidth_gbs},
          {"timing", timing},
          {"repeats", repeats},
          {"fma", {{"threads", fma_threads}, {"iterations", fma_iterations}, {"flops", fma_flops}, {"ms", fma_ms},
                   {"gflops", fma_gflops}}},
          {"fma_scalar", {{"ms", fma_scalar_ms}, {"gflops", fma_scalar_gflops}}},
          {"copy", {{"bytes", copy_bytes}, {"ms", copy_ms}}},
          {"dispatch_latency_ms", dispatch_latency_ms},
          {"dispatch_chain", {{"dispatches", glsl::kCalibDispatchChain}, {"ms", dispatch_chain_ms}}},
          {"fill_gpix", throughput.fill_gpix},
          {"raster", {{"width", raster_width}, {"height", raster_height}, {"layers", raster_layers}, {"ms", raster_ms}}}};
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
    c.fma_gflops = j["fma"].value("gflops", c.throughput.fp32_gflops);
  }
  if (j.contains("fma_scalar")) {
    c.fma_scalar_ms = j["fma_scalar"].value("ms", std::vector<double>{});
    c.fma_scalar_gflops = j["fma_scalar"].value("gflops", 0.0);
  }
  c.throughput.fill_gpix = j.value("fill_gpix", 0.0);  // absent in baselines before the raster calibration
  if (j.contains("raster")) {
    c.raster_width = j["raster"].value("width", 0u);
    c.raster_height = j["raster"].value("height", 0u);
    c.raster_layers = j["raster"].value("layers", 0u);
    c.raster_ms = j["raster"].value("ms", std::vector<double>{});
  }
  c.dispatch_latency_ms = j.value("dispatch_latency_ms", 0.0);  // absent in baselines before it was calibrated
  if (j.contains("dispatch_chain")) c.dispatch_chain_ms = j["dispatch_chain"].value("ms", std::vector<double>{});
  if (j.contains("copy")) {
    c.copy_bytes = j["copy"].value("bytes", uint64_t(0));
    c.copy_ms = j["copy"].value("ms", std::vector<double>{});
  }
  return c;
}

}  // namespace gib::perf
