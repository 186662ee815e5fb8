#include "tests/gpu_fixture.h"

#include <cstdlib>
#include <string>

namespace gib::test {
// Validation on unless GIB_VALIDATE=0 (a GPU machine without the Khronos layer installed).
Gpu& shared_gpu() {
  const char* v = std::getenv("GIB_VALIDATE");
  static std::unique_ptr<Gpu> gpu = Gpu::create({"", !(v && std::string(v) == "0")});
  return *gpu;
}
}  // namespace gib::test
