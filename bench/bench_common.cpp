#include "bench/bench_common.h"

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <memory>

namespace gib {

Gpu& bench_gpu() {
  static std::unique_ptr<Gpu> gpu = [] {
    const char* d = std::getenv("GIB_DEVICE");
    auto g = Gpu::create({d ? d : "", false});
    benchmark::AddCustomContext("gpu_device", g->info().name);
    benchmark::AddCustomContext("gpu_driver", g->info().driver_name + " " + g->info().driver_info);
    return g;
  }();
  return *gpu;
}

}  // namespace gib
