// Rows in parallel: `gibench run -j N` starts N worker processes (`gibench run --worker`, the
// same binary) and hands each a row key on stdin whenever it is idle, the longest expected rows
// first. A worker renders the row on its own device (Vulkan instance, queue, memory) and writes
// one JSON event per line to stdout: row started, frames, row finished (with the row's full
// result), case errors. The parent prints progress and collects the rows; each worker's images
// land in DIR/.jobs/K/img and are moved to DIR/img at the end. Rows are independent and every
// technique is deterministic on a device, so a parallel run gives the rows a serial run gives.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "harness/plan.h"
#include "harness/progress.h"
#include "harness/suite.h"

namespace gib {

// Workers when -j is not given on a GPU device. The suite's small rows wait on the host and the
// driver between frames, so several processes keep a GPU busy; the driver's host time (system
// CPU) is what limits them. CI tier, 191 rows, one H200 (driver 580.159.04): serial 288 s,
// -j4 122 s, -j8 98 s; -j8 over two H200s 137 s and -j16 157 s (system CPU 3.6 -> 4.8 -> 5.9
// min), so the default stays at 8 whatever the number of devices.
inline constexpr unsigned kGpuJobs = 8;

// lavapipe threads per worker when the workers fill the cores (one per core): 0 runs each
// dispatch on the submitting thread, as Mesa's CI does with one test process per core.
inline constexpr unsigned kCpuWorkerThreads = 0;

// -j N (0: by device: one worker per core on a CPU device, kGpuJobs otherwise).
unsigned resolve_jobs(unsigned requested, bool cpu_device);
// --device "0,1": one device per entry, workers alternate between them; "" or one entry: one.
std::vector<std::string> split_devices(const std::string& device);

struct JobsResult {
  std::vector<nlohmann::json> rows;  // row JSON (report.h row_to_json), in the order they finished
  std::vector<std::string> case_errors;
  nlohmann::json references = nlohmann::json::object();
};
// Runs `rows` on `jobs` workers. `o`: the parent's options (cases, tier, devices, scan, ...);
// `tier` and `golden_class` are the parent's resolved ones, so every worker judges alike.
// `cpu_device`: the workers get LP_NUM_THREADS (lavapipe's threads per process; see
// kCpuWorkerThreads) unless it is set already.
JobsResult run_jobs(const SuiteOptions& o, const std::string& tier, const std::string& golden_class, bool cpu_device,
                    const std::vector<PlannedRow>& rows, unsigned jobs, SuiteProgress& progress);

// `gibench run --worker`: rows named on stdin, events on stdout (see above). Returns the exit code.
int run_worker(const SuiteOptions& o);

}  // namespace gib
