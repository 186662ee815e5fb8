// A Cmd that forwards everything to another and logs every compute dispatch it records: its
// thread count (groups x the bound pipeline's workgroup size; an indirect dispatch's groups are
// read back after the submission) and, where asked, a timestamp written right after it. The
// executor wraps a pass's commands in one when its dispatch profile is on (Executor::
// enable_dispatch_profile), so bench can tell how a pass's time splits over its dispatches and
// how many threads each ran (perf/occupancy.h), and with which pipeline (its statistics). Knows
// no pass and no technique.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "renderer/vk/gpu.h"

namespace gib {

struct LoggedDispatch {
  uint64_t local_threads = 0;      // workgroup size of the bound pipeline
  uint64_t groups = 0;             // direct dispatch: x * y * z
  const Buffer* args = nullptr;    // indirect dispatch: where its (x, y, z) lie
  uint64_t args_offset = 0;
  int64_t query = -1;              // timestamp written after it (-1: none)
  const Pipeline* pipeline = nullptr;  // the bound pipeline (the Gpu's pipeline cache owns it)
};

class DispatchLogCmd final : public Cmd {
 public:
  // Timestamps go to queries next_query, next_query + 1, ... up to query_limit (exclusive);
  // past it (or with timestamps off) dispatches are logged without one.
  DispatchLogCmd(Cmd& inner, uint32_t& next_query, uint32_t query_limit, bool timestamps)
      : inner_(inner), next_query_(next_query), query_limit_(query_limit), timestamps_(timestamps) {}
  const std::vector<LoggedDispatch>& dispatches() const { return log_; }

  void bind(const Pipeline& pipeline, std::span<const Bind> binds, const void* push, uint32_t push_bytes) override;
  void dispatch(uint32_t x, uint32_t y, uint32_t z) override;
  void dispatch_indirect(const Buffer& args, uint64_t offset) override;
  void begin_rendering(std::span<const Image* const> colors, const Image* depth, const float clear_color[4]) override {
    inner_.begin_rendering(colors, depth, clear_color);
  }
  void set_viewport(uint32_t x, uint32_t y, uint32_t width, uint32_t height) override {
    inner_.set_viewport(x, y, width, height);
  }
  void draw(uint32_t vertex_count) override { inner_.draw(vertex_count); }
  void end_rendering() override { inner_.end_rendering(); }
  void barrier(uint32_t src_stages, uint32_t dst_stages) override { inner_.barrier(src_stages, dst_stages); }
  void fill(const Buffer& buffer, uint32_t value) override { inner_.fill(buffer, value); }
  void update(const Buffer& buffer, const void* data, uint32_t bytes) override { inner_.update(buffer, data, bytes); }
  void clear(const Image& image, const float value[4]) override { inner_.clear(image, value); }
  void copy(const Image& src, const Image& dst) override { inner_.copy(src, dst); }
  void copy(const Buffer& src, const Buffer& dst) override { inner_.copy(src, dst); }
  void timestamp(uint32_t query) override { inner_.timestamp(query); }
  void begin_label(const std::string& name) override { inner_.begin_label(name); }
  void end_label() override { inner_.end_label(); }

 private:
  void log(LoggedDispatch d);
  Cmd& inner_;
  uint32_t& next_query_;
  uint32_t query_limit_;
  bool timestamps_;
  uint64_t local_threads_ = 0;
  const Pipeline* pipeline_ = nullptr;
  std::vector<LoggedDispatch> log_;
};

}  // namespace gib
