#include "perf/clock_probe.h"

#include <algorithm>
#include <map>
#include <mutex>

#include "perf/calibration_shared.h"
#include "perf/calibration.h"
#include "renderer/graph/pass.h"

namespace gib::perf {

namespace {
// Fastest probe per device (name + driver) in this process, in ms per loop iteration.
std::mutex g_mutex;
std::map<std::string, double> g_fastest;
}  // namespace

double ClockCheck::ratio() const {
  return measured() ? std::max(before_probe_ms, after_probe_ms) / fastest_probe_ms : 0.0;
}

nlohmann::json ClockCheck::to_json() const {
  return {{"fastest_probe_ms", fastest_probe_ms}, {"before_probe_ms", before_probe_ms},
          {"after_probe_ms", after_probe_ms}, {"ratio", ratio()}};
}

struct ClockProbe::State {
  std::shared_ptr<Buffer> out;
  std::shared_ptr<Pipeline> pipe;
  std::vector<Bind> binds;
  glsl::CalibFmaPush push{16, 0.999f, 1e-3f, 0};
  uint32_t groups = 1024;  // 256k threads: every SM of a large GPU, several waves each
  std::string device;
};

ClockProbe::ClockProbe(Gpu& gpu) : gpu_(gpu), s_(std::make_unique<State>()) {
  s_->device = gpu.info().name + " " + gpu.info().driver_name + " " + gpu.info().driver_info;
  s_->out = gpu.create_buffer(uint64_t(s_->groups) * glsl::kCalibGroup * 4, BufferUsage::storage, "clock_probe_out");
  s_->pipe = gpu.compute_pipeline(ComputePipelineDesc{
      "calibrate_fma.comp", {{glsl::kCalibBindOut, DescriptorKind::storage_buffer}}, sizeof(glsl::CalibFmaPush)});
  s_->binds = {{glsl::kCalibBindOut, s_->out.get(), nullptr}};
  // ~0.2 ms at the clock the device has now: long enough to dwarf the timestamp resolution.
  for (int i = 0; i < 12 && probe() < 0.2; ++i) s_->push.iterations *= 2;
}

ClockProbe::~ClockProbe() = default;

double ClockProbe::probe() {
  double ms = time_dispatch(gpu_, *s_->pipe, s_->binds, &s_->push, sizeof(s_->push), s_->groups);
  std::lock_guard lock(g_mutex);
  double per = ms / s_->push.iterations;
  auto [it, fresh] = g_fastest.emplace(s_->device, per);
  if (!fresh) it->second = std::min(it->second, per);
  return ms;
}

double ClockProbe::fastest() const {
  std::lock_guard lock(g_mutex);
  auto it = g_fastest.find(s_->device);
  return it == g_fastest.end() ? 0.0 : it->second * s_->push.iterations;
}

}  // namespace gib::perf
