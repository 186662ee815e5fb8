#include "harness/references.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <tuple>
#include <unistd.h>

#include "harness/case_render.h"
#include "harness/suite.h"
#include "renderer/techniques/reference/reference.h"
#include "renderer/techniques/technique.h"
#include "renderer/vk/gpu.h"

namespace fs = std::filesystem;

namespace gib {

std::string reference_cache_root(const std::string& requested) {
  if (!requested.empty()) return requested;
  if (const char* e = std::getenv("GIBENCH_REFERENCE_CACHE"); e && *e) return e;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return (fs::path(x) / "gibench" / "references").string();
  if (const char* h = std::getenv("HOME"); h && *h) return (fs::path(h) / ".cache" / "gibench" / "references").string();
  throw std::runtime_error(
      "reference cache: expected --reference-cache DIR, GIBENCH_REFERENCE_CACHE, XDG_CACHE_HOME or HOME, got none set");
}

std::string path_tracer_revision() {
  // The binary's shaders and presets: fixed for the process, so hashed once.
  static const std::string revision = [] {
    const Technique& t = find_technique("reference");
    std::string text = fmt::format("cpu {};", kPathTracerCpuRevision);
    for (const PassEntry& p : t.passes)
      for (auto& [name, words] : shader_registry())
        if (name.rfind(p.name + ".", 0) == 0)
          text += name + ":" +
                  std::string(reinterpret_cast<const char*>(words.data()), words.size() * sizeof(uint32_t)) + ";";
    Settings s = apply_preset(t, "ultra", Settings{});
    text += fmt::format("max_bounces {};", s.params<ReferenceSettings>().max_bounces);
    return fnv1a_hex(text);
  }();
  return revision;
}

namespace {

// The worst floor of a measured noise floor record ({"flip", "aovs": {...}}) over the AOVs the
// case compares with (an AOV nothing compares with does not decide convergence), and that AOV.
std::pair<double, std::string> worst_floor(const Case& c, const nlohmann::json& floor) {
  std::pair<double, std::string> w{floor.value("flip", 0.0), c.output};
  if (floor.contains("aovs"))
    for (auto& aov : compared_aovs(c))
      if (floor["aovs"].contains(aov) && floor["aovs"][aov].get<double>() > w.first) w = {floor["aovs"][aov].get<double>(), aov};
  return w;
}

// Every reference file the case's runs compare with at the tier's evaluation frames.
std::vector<std::string> needed_stems(const Case& c) {
  std::vector<uint32_t> frames = per_frame_references(c) ? evaluation_frames(c) : std::vector<uint32_t>{0};
  std::vector<std::string> stems;
  for (uint32_t f : frames)
    for (auto& aov : compared_aovs(c)) stems.push_back(GoldenStore::reference_stem(aov, c.output, f));
  return stems;
}

// What the renderer draws, beyond the scene file's text: the geometry, instances, materials,
// image textures and lights the loader produced, so content a scene file pulls in (glTF objects,
// their buffers and images) changes the key when it changes.
std::string scene_content_hash(const Scene& s) {
  std::string bytes;
  auto raw = [&](const void* p, size_t n) { bytes.append(static_cast<const char*>(p), n); };
  auto vec = [&](const auto& v) {
    uint64_t n = v.size();
    raw(&n, sizeof n);
    if (n) raw(v.data(), n * sizeof(v[0]));
  };
  for (const Mesh& m : s.meshes) {
    vec(m.positions);
    vec(m.normals);
    vec(m.uvs);
    vec(m.indices);
  }
  for (const Instance& i : s.instances) {
    raw(&i.mesh, sizeof i.mesh);
    raw(&i.material, sizeof i.material);
    raw(&i.transform, sizeof i.transform);
    vec(i.animation);
    raw(&i.removed_at, sizeof i.removed_at);
  }
  for (const Material& m : s.materials) {
    bytes += m.name;
    raw(&m.albedo, sizeof m.albedo);
    raw(&m.roughness, sizeof(float) * 2);  // roughness, metalness
    raw(&m.emissive, sizeof m.emissive);
    raw(&m.translucency, sizeof m.translucency);
    raw(&m.alpha, sizeof m.alpha);
    raw(&m.alpha_cutoff, sizeof(float) * 2);  // alpha_cutoff, opacity
    raw(&m.texture, sizeof m.texture);
    raw(&m.albedo2, sizeof m.albedo2);
    raw(&m.texture_scale, sizeof m.texture_scale);
    raw(&m.brdf, sizeof m.brdf);
    raw(&m.sheen, sizeof m.sheen);
    raw(&m.base_color_texture, sizeof m.base_color_texture);
    raw(&m.emissive_texture, sizeof m.emissive_texture);
    if (m.normal_texture >= 0) {  // only then, so keys made before normal maps stay valid
      raw(&m.normal_texture, sizeof m.normal_texture);
      raw(&m.normal_scale, sizeof m.normal_scale);
    }
  }
  for (const Texture& t : s.textures) {
    raw(&t.srgb, sizeof t.srgb);
    raw(&t.width, sizeof t.width);
    raw(&t.height, sizeof t.height);
    if (!t.mips.empty()) vec(t.mips[0]);  // the mips are made from level 0
  }
  vec(s.lights);
  return fnv1a_hex(bytes);
}

}  // namespace

uint32_t pilot_spp(uint32_t start_spp) {
  return start_spp <= kReferencePilotMin * 4 ? start_spp : std::max(kReferencePilotMin, start_spp / 64);
}

uint32_t next_spp(uint32_t spp, double floor, const ReferenceRequest& req) {
  // FLIP of the noise ~ 1/sqrt(spp): the spp that puts the floor at 0.9 x the target, rounded up
  // to a multiple of 4096; at least twice what was rendered, at most the budget.
  const double want = double(spp) * std::pow(floor / (0.9 * req.target_floor), 2.0);
  const uint64_t rounded = (uint64_t(std::ceil(want)) + 4095) / 4096 * 4096;
  return uint32_t(std::min<uint64_t>(std::max<uint64_t>(rounded, uint64_t(spp) * 2), req.max_spp));
}

ReferenceRequest reference_request(const Case& c, const nlohmann::json& committed_meta) {
  ReferenceRequest req;
  for (auto& run : c.techniques)
    for (auto& t : run.thresholds)
      if (t.metric == "flip" && t.against == "reference" && t.roi.empty() && t.max)
        req.target_floor = std::min(req.target_floor, *t.max / kNoiseFloorFactor);
  double floor = 0;
  uint32_t spp = 0, committed_spp = recorded_reference_spp(c, committed_meta);
  if (committed_meta.contains("noise_floor")) {
    floor = worst_floor(c, committed_meta["noise_floor"]).first;
    spp = committed_meta["noise_floor"].value("spp", committed_spp);
  }
  if (floor > 0 && spp > 0) {
    // FLIP of the noise ~ 1/sqrt(spp): the spp that reaches 0.8 x the target, to a power of 2.
    double want = double(spp) * std::pow(floor / (0.8 * req.target_floor), 2.0);
    uint32_t p = 256;
    while (p < want && p < kReferenceSppMax) p *= 2;
    req.start_spp = p;
  } else {
    req.start_spp = std::max<uint32_t>(committed_spp, 256);
  }
  return req;
}

nlohmann::json reference_key_inputs(const Case& c, const ReferenceRequest& req) {
  nlohmann::json frames = nlohmann::json::array();
  if (per_frame_references(c))
    for (uint32_t f : evaluation_frames(c)) frames.push_back(f);
  return {{"scene", fnv1a_hex(c.scene_text)},
          {"scene_content", scene_content_hash(c.scene)},
          {"scene_file", c.scene_file.empty() ? std::string("inline") : c.scene_file},
          {"size", {c.width, c.height}},
          {"seed", c.reference_seed},
          {"frames", frames},
          {"files", needed_stems(c)},
          {"target_floor", req.target_floor},
          {"start_spp", req.start_spp},
          {"path_tracer", path_tracer_revision()}};
}

std::string reference_key(const nlohmann::json& inputs) {
  nlohmann::json k = inputs;
  k.erase("scene_file");  // where the scene lives is not what it is
  return fnv1a_hex(k.dump());
}

ReferenceSource reference_source(const std::string& goldens_dir, const std::string& cache_root, const Case& c, Tier t) {
  if (t == Tier::ci) return {GoldenStore(goldens_dir, c.name), "", {}, {}};
  ReferenceRequest req = reference_request(c, GoldenStore(goldens_dir, c.name).metadata());
  nlohmann::json inputs = reference_key_inputs(c, req);
  std::string key = reference_key(inputs);
  return {GoldenStore(cache_root, c.name, key), key, inputs, req};
}

double reference_floor(const Case& c, const ReferenceSource& src) {
  nlohmann::json meta = src.store.metadata();
  return meta.contains("noise_floor") ? worst_floor(c, meta["noise_floor"]).first
                                      : std::numeric_limits<double>::infinity();
}

bool references_converged(const Case& c, const ReferenceSource& src) {
  return reference_floor(c, src) <= src.request.target_floor;
}

bool references_present(const Case& c, const ReferenceSource& src) {
  if (c.reference_spp == 0) return true;
  const nlohmann::json meta = src.store.metadata();
  for (auto& stem : needed_stems(c)) {
    if (!fs::exists(fs::path(src.store.dir()) / (stem + ".exr"))) return false;
    // A file without its record (spp, device) cannot be read: the entry is rendered again.
    try {
      src.store.record_of(stem + ".exr");
    } catch (const GoldenError&) {
      return false;
    }
  }
  return meta.contains("noise_floor");
}

std::string render_references(Gpu& gpu, const Case& c, ReferenceSource& src, const RenderProgress& progress) {
  if (c.reference_spp == 0) return fmt::format("{}: no reference (reference_spp 0)", c.name);
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<uint32_t> frames =
      per_frame_references(c) ? evaluation_frames(c) : std::vector<uint32_t>{0};
  const DeviceInfo& d = gpu.info();
  uint32_t spp = std::min(src.request.first_spp ? src.request.first_spp : pilot_spp(src.request.start_spp),
                          src.request.max_spp);
  const std::vector<std::string> aovs = compared_aovs(c);
  auto compared = [&](const std::string& aov) { return std::find(aovs.begin(), aovs.end(), aov) != aovs.end(); };
  nlohmann::json meta, floor;
  double worst = 0;
  std::string worst_aov;
  for (;;) {
    Case rc = c;
    rc.reference_spp = spp;
    meta = {{"reference_cache", src.inputs}, {"key", src.key}, {"files", nlohmann::json::object()}};
    std::map<std::string, FloatImage> images;
    std::optional<CaseRender> last;
    for (uint32_t f : frames) {
      std::string what = fmt::format("{} {}x{} {}{} spp", c.name, c.width, c.height, f ? fmt::format("f{} ", f) : "", spp);
      CaseRender r = render_reference(gpu, rc, 0, f, [&](uint32_t a, uint32_t b) { if (progress) progress(what, a, b); });
      for (auto& [aov, img] : r.aovs) {
        std::string stem = GoldenStore::reference_stem(aov, c.output, f);
        if (!compared(aov)) continue;  // nothing compares with it: not kept
        meta["files"][src.store.file_name(stem, "")] = {
            {"aov", aov}, {"spp", r.spp}, {"seed", c.reference_seed}, {"frames", r.frames},
            {"device", d.name}, {"driver", d.driver_name + " " + d.driver_info}, {"date", utc_now_iso()},
            {"gpu_ms", r.gpu_ms_total}};
        if (f) meta["files"][src.store.file_name(stem, "")]["at_frame"] = f;
        images[stem] = img;
      }
      if (f == frames.back()) last = std::move(r);
    }
    std::string what = fmt::format("{} {}x{} noise floor (seed {}) {} spp", c.name, c.width, c.height,
                                   c.reference_seed + 1000, spp);
    floor = measure_noise_floor(gpu, rc, &*last, [&](uint32_t a, uint32_t b) { if (progress) progress(what, a, b); });
    std::tie(worst, worst_aov) = worst_floor(c, floor);
    if (worst <= src.request.target_floor || spp >= src.request.max_spp) {
      for (auto& [stem, img] : images) src.store.write(stem, "", img);
      break;
    }
    spp = next_spp(spp, worst, src.request);
  }
  record_noise_floor(meta, floor);
  meta["noise_floor"]["worst"] = worst;
  meta["noise_floor"]["worst_aov"] = worst_aov;
  meta["noise_floor"]["target"] = src.request.target_floor;
  src.store.write_metadata(meta);
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::string line = fmt::format("{}: reference {}x{} at {} spp, noise floor {:.4f} ({}; target {:.4f}), {:.1f} s -> {}",
                                 c.name, c.width, c.height, spp, worst, worst_aov, src.request.target_floor, secs,
                                 src.store.dir());
  if (worst > src.request.target_floor)
    line += fmt::format(" (NOT CONVERGED: the budget stops at {} spp; runs report it)", src.request.max_spp);
  return line;
}

ReferenceSource prepare_references(Gpu& gpu, const std::string& goldens_dir, const std::string& cache_root,
                                   const Case& c, Tier t, bool* rendered) {
  ReferenceSource src = reference_source(goldens_dir, cache_root, c, t);
  const bool render = t == Tier::gpu && !references_present(c, src);
  if (render) {
    fmt::print("{}\n", render_references(gpu, c, src, terminal_progress("")));
    std::fflush(stdout);
  }
  if (rendered) *rendered = render;
  return src;
}

RenderProgress terminal_progress(const std::string& label) {
  if (!isatty(STDERR_FILENO)) return {};
  return [label](const std::string& what, uint32_t done, uint32_t total) {
    const int width = 30;
    int filled = total ? int(double(done) / total * width) : width;
    fmt::print(stderr, "\r{}{} [{}{}] {:3.0f}%\x1b[K", label, what, std::string(size_t(filled), '#'),
               std::string(size_t(width - filled), '-'), total ? 100.0 * done / total : 100.0);
    if (done == total) fmt::print(stderr, "\r\x1b[K");
  };
}

int cmd_references(const SuiteOptions& o, bool refresh, bool dry_run, uint32_t max_spp) {
  if (!o.tier.empty() && o.tier != "gpu")
    throw std::invalid_argument(fmt::format(
        "--tier: expected gpu (the CI tier's references are committed: gibench update-goldens --reference), got '{}'",
        o.tier));
  std::vector<Case> cases = select_cases(o);
  const std::string root = reference_cache_root(o.reference_cache);
  if (dry_run) {
    for (const Case& c0 : cases) {
      const Case c = at_tier(c0, Tier::gpu);
      if (c.reference_spp == 0) continue;
      ReferenceSource src = reference_source(o.goldens_dir, root, c, Tier::gpu);
      fmt::print("{:<28} {}x{}  target floor {:.4f}  start {:>7} spp  key {}  {}\n", c.name, c.width, c.height,
                 src.request.target_floor, src.request.start_spp, src.key,
                 references_present(c, src) ? "cached" : "to render");
    }
    return 0;
  }
  auto gpu = Gpu::create({o.device, o.validate});
  fmt::print("device: {}; GPU-tier references in {}\n", gpu->info().name, root);
  int status = 0;
  for (const Case& c0 : cases) {
    const Case c = at_tier(c0, Tier::gpu);
    if (c.reference_spp == 0) {
      fmt::print("{}: no reference (reference_spp 0)\n", c.name);
      continue;
    }
    ReferenceSource src = reference_source(o.goldens_dir, root, c, Tier::gpu);
    src.request.max_spp = max_spp;
    const bool present = references_present(c, src);
    const uint32_t held = present ? recorded_reference_spp(c, src.store.metadata()) : 0;
    const double floor = reference_floor(c, src);
    // An entry short of its target is refined (at the spp its floor predicts) when the budget allows more.
    const bool refine = present && floor > src.request.target_floor && held < max_spp;
    if (refine) src.request.first_spp = next_spp(held, floor, src.request);
    if (refresh || !present || refine)
      fmt::print("{}\n", render_references(*gpu, c, src, terminal_progress("")));
    else
      fmt::print("{}: cached ({} spp, noise floor {:.4f}{}, key {})\n", c.name, held, floor,
                 floor <= src.request.target_floor ? "" : ", NOT CONVERGED", src.key);
    std::fflush(stdout);
    if (!references_converged(c, src)) status = 1;
  }
  return status;
}

}  // namespace gib
