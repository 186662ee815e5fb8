#include "renderer/graph/dispatch_log.h"

namespace gib {

void DispatchLogCmd::bind(const Pipeline& pipeline, std::span<const Bind> binds, const void* push, uint32_t push_bytes) {
  const auto ls = pipeline.local_size();
  local_threads_ = uint64_t(ls[0]) * ls[1] * ls[2];
  pipeline_ = &pipeline;
  inner_.bind(pipeline, binds, push, push_bytes);
}

void DispatchLogCmd::log(LoggedDispatch d) {
  d.local_threads = local_threads_;
  d.pipeline = pipeline_;
  if (timestamps_ && next_query_ < query_limit_) {
    d.query = next_query_;
    inner_.timestamp(next_query_++);
  }
  log_.push_back(d);
}

void DispatchLogCmd::dispatch(uint32_t x, uint32_t y, uint32_t z) {
  inner_.dispatch(x, y, z);
  LoggedDispatch d;
  d.groups = uint64_t(x) * y * z;
  log(d);
}

void DispatchLogCmd::dispatch_indirect(const Buffer& args, uint64_t offset) {
  inner_.dispatch_indirect(args, offset);
  LoggedDispatch d;
  d.args = &args;
  d.args_offset = offset;
  log(d);
}

}  // namespace gib
