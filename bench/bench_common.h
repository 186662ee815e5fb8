// What every benchmark file shares: one Gpu for the whole bench binary (device from
// GIB_DEVICE: index or name substring; else the default), recorded in the benchmark context.
#pragma once
#include "renderer/vk/gpu.h"

namespace gib {
Gpu& bench_gpu();
}
