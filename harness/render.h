// `gibench render`: one scene, one technique, N frames; prints the device, the plan and the GPU
// time of every pass; writes the output EXR (+ PNG preview), dumps, and a JSON record.
#pragma once
#include <string>
#include <vector>

#include <map>

#include "renderer/graph/executor.h"
#include "renderer/techniques/technique.h"

namespace gib {

struct RenderOptions {
  std::string scene;
  std::string technique = "direct";
  std::string preset = "medium";
  uint32_t spp = 0;     // reference: total samples per pixel (0: technique default)
  uint32_t frames = 0;  // 0: 1, or what spp needs
  uint32_t width = 256, height = 144;
  uint32_t seed = 1;
  std::string device;
  bool validate = false;
  bool plan_only = false;
  std::string dot;                  // write the graph as graphviz here
  std::vector<std::string> dumps;   // resources to write as EXR
  std::vector<std::string> options; // technique options, "NAME=VALUE" each (validated by check_option)
  std::string out;                  // output EXR
  std::string json;                 // machine-readable record
};

struct PassStats {
  std::string name;
  double median_ms = 0, min_ms = 0, max_ms = 0;
};

// Loading a scene file (its glTF objects' import included), measured: wall time, the bytes the
// loaded scene holds (mesh arrays, texture mips), and how far the process's peak resident set
// (VmHWM, /proc/self/status) rose during the load: the import's transient memory, decoders'
// buffers included (0 where the peak was already higher, or /proc is unreadable).
struct SceneLoad {
  double ms = 0;
  uint64_t mesh_bytes = 0, texture_bytes = 0;
  uint64_t peak_rss_growth = 0;
  bool peak_rss_known = false;
  std::vector<SceneImport> imports;  // the glTF objects': what each read and ignored
};
Scene load_scene_measured(const std::string& path, SceneLoad& load);
// For the console: one line, then two per glTF import (read, ignored).
std::string to_string(const SceneLoad& load);

struct RenderRun {
  DeviceInfo device;
  SceneLoad scene_load;
  Plan plan;
  Settings settings;
  uint32_t frames = 0;
  std::vector<PassStats> passes;  // running passes, execution order
  double frame_median_ms = 0;
  uint64_t texture_bytes = 0;  // the scene's packed image textures on the GPU (0 without any)
  FloatImage output;
  // The technique's GPU counters (Technique::stats) whose buffer the plan kept, after the last
  // frame: e.g. gow-ragnarok's reflection sample shares, with --dump reflection.
  std::map<std::string, double> stats;
  std::vector<std::string> validation_messages;
};

// Renders and returns the result; the CLI wrapper prints and writes files.
RenderRun render(const RenderOptions& options);
int cmd_render(const RenderOptions& options);  // returns the process exit code
// Lists the Vulkan devices. With `ctest_resource_spec`, also writes a CTest resource spec file
// there: one "gpus" resource per hardware device (every device when there is none, e.g.
// lavapipe alone), id = the device index `--device` takes (CMakeLists.txt, GIB_SUITE_SHARDS).
int cmd_devices(const std::string& ctest_resource_spec = "");

std::vector<PassStats> summarize(const std::vector<FrameResult>& frames);
// "NAME=VALUE" strings to technique options; throws std::invalid_argument naming the bad one.
std::map<std::string, double> parse_render_options(const Technique& t, const std::vector<std::string>& options);

}  // namespace gib
