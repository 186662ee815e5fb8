#include "tests/gpu_fixture.h"

namespace gib::test {
Gpu& shared_gpu() {
  static std::unique_ptr<Gpu> gpu = Gpu::create({"", true});
  return *gpu;
}
}  // namespace gib::test
