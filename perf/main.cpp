// gibench-perf: `bench` and `perf-diff` alone, linked without the harness (no image files), so
// that the binary and its few shared libraries can be carried to a GPU machine (ci/pack_gpu.sh).
#include <fmt/format.h>

#include <exception>

#include "perf/cli.h"

int main(int argc, char** argv) {
  CLI::App app{"gibench-perf: pass-cost benchmarks scaled to console profiles, and perf-diff"};
  app.require_subcommand(1);
  gib::perf::PerfCli perf;
  gib::perf::add_perf_commands(app, perf);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    return gib::perf::run_perf_commands(perf);
  } catch (const std::exception& e) {
    fmt::print(stderr, "gibench-perf: error: {}\n", e.what());
    return 2;
  }
}
