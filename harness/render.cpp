#include "harness/render.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "harness/image_io.h"
#include "renderer/image/format.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/techniques/reference/reference.h"
#include "renderer/techniques/technique.h"

namespace gib {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The process's peak resident set in bytes (VmHWM), or 0 when /proc/self/status has none.
uint64_t peak_rss_bytes() {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::strtoull(line.c_str() + 6, nullptr, 10) * 1024;  // kB
  return 0;
}

Settings make_settings(const RenderOptions& o, const Technique& t) {
  Settings s;
  s.width = o.width;
  s.height = o.height;
  s.seed = o.seed;
  s = apply_preset(t, o.preset, s);
  return apply_options(t, s, parse_render_options(t, o.options));
}

// Non-finite values among the colour channels of an image.
struct NonFinite {
  size_t nan = 0, inf = 0, pixels = 0;  // pixels: with any non-finite channel
};
NonFinite count_non_finite(const FloatImage& img) {
  NonFinite n;
  const uint32_t channels = std::min(img.channels, 3u);
  for (size_t i = 0; i < img.pixel_count(); ++i) {
    bool bad = false;
    for (uint32_t c = 0; c < channels; ++c) {
      float v = img.pixels[i * img.channels + c];
      n.nan += std::isnan(v);
      n.inf += std::isinf(v);
      bad = bad || !std::isfinite(v);
    }
    n.pixels += bad;
  }
  return n;
}

// Samples per frame: the largest of 16, 8, 4, 2, 1 that divides the total.
// Samples per pixel each frame adds: the reference's setting; 1 for every other technique.
uint32_t spp_per_frame(const Settings& s) {
  return s.has_params<ReferenceSettings>() ? s.params<ReferenceSettings>().spp_per_frame : 1;
}

uint32_t samples_per_frame(uint32_t spp) {
  for (uint32_t c : {16u, 8u, 4u, 2u})
    if (spp % c == 0) return c;
  return 1;
}

// The output, the contract AOVs the scene supports (so passes that feed only an AOV such as
// `reflection` run and are timed, as in `gibench bench`), then the --dump resources.
std::vector<std::string> requested_outputs(const RenderOptions& o, const Technique& t, SceneFeatures features) {
  std::vector<std::string> out{t.output};
  for (auto& a : contract_aov_names(t, features))
    if (std::string r = contract_resource(t, a); std::find(out.begin(), out.end(), r) == out.end()) out.push_back(r);
  for (auto& d : o.dumps)
    if (std::find(out.begin(), out.end(), d) == out.end()) out.push_back(d);
  return out;
}

std::string stem_path(const std::string& out, const std::string& suffix) {
  std::filesystem::path p(out);
  return (p.parent_path() / (p.stem().string() + suffix)).string();
}

}  // namespace

std::map<std::string, double> parse_render_options(const Technique& t, const std::vector<std::string>& options) {
  std::map<std::string, double> out;
  for (const std::string& o : options) {
    size_t eq = o.find('=');
    if (eq == std::string::npos || eq == 0)
      throw std::invalid_argument(fmt::format("--option: expected NAME=VALUE, got '{}'", o));
    std::string name = o.substr(0, eq), text = o.substr(eq + 1);
    char* end = nullptr;
    double value = text.empty() ? 0.0 : std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0')
      throw std::invalid_argument(fmt::format("--option {}: expected a number, got '{}'", name, text));
    if (std::string err = check_option(t, name, value); !err.empty())
      throw std::invalid_argument(fmt::format("--option {}: {}", name, err));
    if (!out.emplace(name, value).second)
      throw std::invalid_argument(fmt::format("--option {}: expected each option once, got it twice", name));
  }
  return out;
}

std::vector<PassStats> summarize(const std::vector<FrameResult>& frames) {
  std::vector<PassStats> out;
  if (frames.empty()) return out;
  for (size_t i = 0; i < frames[0].passes.size(); ++i) {
    std::vector<double> ms;
    for (auto& f : frames) ms.push_back(f.passes[i].ms);
    out.push_back({frames[0].passes[i].name, median(ms), *std::min_element(ms.begin(), ms.end()),
                   *std::max_element(ms.begin(), ms.end())});
  }
  return out;
}

Scene load_scene_measured(const std::string& path, SceneLoad& load) {
  const uint64_t rss0 = peak_rss_bytes();
  const auto t0 = std::chrono::steady_clock::now();
  Scene scene = load_scene(path);
  load.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const uint64_t rss1 = peak_rss_bytes();
  load.peak_rss_known = rss0 > 0 && rss1 > 0;
  load.peak_rss_growth = load.peak_rss_known ? rss1 - rss0 : 0;
  load.mesh_bytes = 0;
  for (const Mesh& m : scene.meshes)
    load.mesh_bytes += m.positions.size() * sizeof(Vec3) + m.normals.size() * sizeof(Vec3) +
                       m.uvs.size() * sizeof(Vec2) + m.indices.size() * sizeof(uint32_t);
  load.texture_bytes = textures_bytes(scene.textures);
  load.imports = scene.imports;
  return scene;
}

std::string to_string(const SceneLoad& l) {
  std::string out =
      fmt::format("scene load: {:.1f} ms; holds {:.1f} KiB of meshes, {:.1f} KiB of textures with mips; peak RSS {}",
                  l.ms, l.mesh_bytes / 1024.0, l.texture_bytes / 1024.0,
                  l.peak_rss_known ? fmt::format("+{:.1f} MiB while loading", l.peak_rss_growth / 1048576.0)
                                   : std::string("unknown (no /proc/self/status)"));
  for (const SceneImport& i : l.imports)
    out += fmt::format("\n  glTF {}: read {}\n  glTF {}: ignored: {}", i.file, i.read, i.file,
                       i.ignored.empty() ? std::string("nothing") : fmt::format("{}", fmt::join(i.ignored, "; ")));
  return out;
}

RenderRun render(const RenderOptions& o) {
  const Technique& t = find_technique(o.technique);
  SceneLoad load;
  Scene scene = load_scene_measured(o.scene, load);
  Settings settings = make_settings(o, t);
  uint32_t frames = o.frames ? o.frames : 1;
  if (t.name == "reference") {
    uint32_t spp = o.spp ? o.spp : 64;
    uint32_t& per_frame = settings.params<ReferenceSettings>().spp_per_frame;
    per_frame = samples_per_frame(spp);
    if (!o.frames) frames = spp / per_frame;
  }
  auto gpu = Gpu::create({o.device, o.validate});
  Executor ex(*gpu, scene, settings, make_passes(t), requested_outputs(o, t, scene.features()));
  RenderRun run;
  run.scene_load = load;
  run.device = gpu->info();
  run.plan = ex.plan();
  run.settings = settings;
  run.frames = frames;
  std::vector<FrameResult> results;
  for (uint32_t f = 0; f < frames; ++f) results.push_back(ex.run_frame());
  run.texture_bytes = ex.texture_bytes();  // uploaded with the scene, at the first frame
  run.passes = summarize(results);
  std::vector<double> totals;
  for (auto& r : results) totals.push_back(r.total_ms);
  run.frame_median_ms = median(totals);
  run.output = ex.read(t.output);
  for (const TechniqueStat& st : t.stats) {
    if (!ex.plan().find(st.resource)) continue;
    const std::vector<uint8_t> raw = ex.read_buffer(st.resource);
    const double v = buffer_word(raw, st.word), of = st.of_word == UINT32_MAX ? 0.0 : buffer_word(raw, st.of_word);
    run.stats[st.name] = st.of_word == UINT32_MAX ? v : (of > 0 ? v / of : 0.0);
  }
  for (auto& d : o.dumps) write_exr(stem_path(o.out, "." + d + ".exr"), ex.read(d));
  run.validation_messages = gpu->validation_messages();
  return run;
}

int cmd_devices(const std::string& ctest_resource_spec) {
  std::vector<DeviceInfo> devices = Gpu::list_devices();
  for (auto& d : devices)
    fmt::print("{} {}: {} ({}, driver {} {}, Vulkan {}, subgroup {}){}\n", d.is_default ? "*" : " ", d.index, d.name,
               d.type, d.driver_name, d.driver_info, d.api_version, d.subgroup_size,
               d.is_default ? "  [default]" : "");
  if (ctest_resource_spec.empty()) return 0;
  bool hardware = std::any_of(devices.begin(), devices.end(), [](auto& d) { return !d.is_software(); });
  nlohmann::json gpus = nlohmann::json::array();
  for (auto& d : devices)
    if (!hardware || !d.is_software()) gpus.push_back({{"id", std::to_string(d.index)}, {"slots", 1}});
  nlohmann::json spec = {{"version", {{"major", 1}, {"minor", 0}}}, {"local", {{{"gpus", gpus}}}}};
  std::string tmp = ctest_resource_spec + ".tmp";
  {
    std::ofstream out(tmp);
    out << spec.dump(2) << "\n";
    if (!out) throw std::runtime_error(fmt::format("{}: expected a writable path for the resource spec", ctest_resource_spec));
  }
  std::filesystem::rename(tmp, ctest_resource_spec);
  fmt::print("wrote {}: {} GPU resource{} for ctest --resource-spec-file\n", ctest_resource_spec, gpus.size(),
             gpus.size() == 1 ? "" : "s");
  return 0;
}

int cmd_render(const RenderOptions& o) {
  const Technique& t = find_technique(o.technique);
  if (o.plan_only || !o.dot.empty()) {
    SceneLoad load;
    Scene scene = load_scene_measured(o.scene, load);
    fmt::print("{}\n", to_string(load));
    Settings settings = make_settings(o, t);
    std::vector<PassDecl> decls;
    for (auto& p : make_passes(t)) decls.push_back(p->declare(scene, settings));
    CompileOptions co{scene.features(), requested_outputs(o, t, scene.features()), settings.width, settings.height};
    Plan plan = compile(decls, co);
    fmt::print("scene features: {}\nscene textures: {} ({:.1f} KiB with mips)\n{}", to_string(scene.features()),
               scene.textures.size(), load.texture_bytes / 1024.0, plan.to_text());
    if (!o.dot.empty()) {
      std::ofstream(o.dot) << plan.to_dot();
      fmt::print("wrote {}\n", o.dot);
    }
    if (o.plan_only) return 0;
  }
  if (o.out.empty()) throw std::invalid_argument("--out: expected an output path FILE.exr");
  RenderRun run = render(o);
  fmt::print("device: {} ({}, {} {})\n", run.device.name, run.device.type, run.device.driver_name,
             run.device.driver_info);
  fmt::print("{}\n", to_string(run.scene_load));
  fmt::print("technique: {} preset {}  size {}x{}  frames {}  spp/frame {}\n", t.name, run.settings.preset,
             run.settings.width, run.settings.height, run.frames, spp_per_frame(run.settings));
  fmt::print("{:<22} {:>7} {:>10} {:>10} {:>10}  {}\n", "pass", "status", "median ms", "min ms", "max ms", "reason");
  for (auto& p : run.passes)
    fmt::print("{:<22} {:>7} {:>10.3f} {:>10.3f} {:>10.3f}\n", p.name, "ran", p.median_ms, p.min_ms, p.max_ms);
  for (auto& p : run.plan.passes)
    if (!p.runs) fmt::print("{:<22} {:>7} {:>10} {:>10} {:>10}  {}\n", p.name, "culled", "-", "-", "-", p.reason);
  fmt::print("frame median {:.3f} ms; resources {:.2f} MiB; scene textures {:.2f} MiB\n", run.frame_median_ms,
             run.plan.total_bytes() / 1048576.0, run.texture_bytes / 1048576.0);
  const NonFinite bad = count_non_finite(run.output);
  fmt::print("output {}: {} NaN, {} Inf values ({} pixels)\n", t.output, bad.nan, bad.inf, bad.pixels);
  for (auto& [name, v] : run.stats) fmt::print("stat {}: {:.4f}\n", name, v);
  write_exr(o.out, run.output);
  write_png_preview(stem_path(o.out, ".png"), run.output);
  fmt::print("wrote {} and {}\n", o.out, stem_path(o.out, ".png"));
  for (auto& m : run.validation_messages) fmt::print(stderr, "validation: {}\n", m);

  if (!o.json.empty()) {
    nlohmann::json j;
    j["device"] = {{"name", run.device.name}, {"type", run.device.type}, {"driver", run.device.driver_name},
                   {"driver_info", run.device.driver_info}, {"api_version", run.device.api_version}};
    j["scene"] = o.scene;
    j["technique"] = t.name;
    j["preset"] = run.settings.preset;
    j["size"] = {run.settings.width, run.settings.height};
    j["frames"] = run.frames;
    j["spp"] = run.frames * spp_per_frame(run.settings);
    j["frame_median_ms"] = run.frame_median_ms;
    j["resource_bytes"] = run.plan.total_bytes();
    auto& resources = j["resources"] = nlohmann::json::array();  // memory by buffer / image
    for (const ResolvedResource& r : run.plan.resources) {
      const std::string producer = r.producer >= 0 ? run.plan.passes[size_t(r.producer)].name : "";
      resources.push_back({{"name", r.name}, {"format", format_name(r.desc.format)}, {"bytes", r.bytes},
                           {"copies", r.copies}, {"producer", producer}});
    }
    j["texture_bytes"] = run.texture_bytes;
    j["scene_load"] = {{"ms", run.scene_load.ms}, {"mesh_bytes", run.scene_load.mesh_bytes},
                       {"texture_bytes", run.scene_load.texture_bytes}};
    if (run.scene_load.peak_rss_known) j["scene_load"]["peak_rss_growth_bytes"] = run.scene_load.peak_rss_growth;
    for (const SceneImport& i : run.scene_load.imports)
      j["scene_load"]["imports"].push_back({{"file", i.file}, {"read", i.read}, {"ignored", i.ignored}});
    j["options"] = parse_render_options(t, o.options);
    j["output_non_finite"] = {{"nan", bad.nan}, {"inf", bad.inf}, {"pixels", bad.pixels}};
    auto& passes = j["passes"] = nlohmann::json::array();
    for (auto& p : run.plan.passes) {
      nlohmann::json pj{{"name", p.name}, {"status", p.runs ? "ran" : "culled"}, {"reason", p.reason}};
      for (auto& s : run.passes)
        if (s.name == p.name) pj.update({{"ms", s.median_ms}, {"min_ms", s.min_ms}, {"max_ms", s.max_ms}});
      passes.push_back(pj);
    }
    j["stats"] = run.stats;
    j["validation_messages"] = run.validation_messages;
    std::ofstream(o.json) << j.dump(2) << "\n";
  }
  return run.validation_messages.empty() || !o.validate ? 0 : 3;
}

}  // namespace gib
