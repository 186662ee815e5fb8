#include "harness/attribution/attribute_command.h"

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "harness/attribution/attribution.h"
#include "harness/attribution/attribution_report.h"
#include "harness/case_render.h"
#include "harness/goldens.h"
#include "harness/references.h"
#include "renderer/techniques/technique.h"

namespace gib {

namespace fs = std::filesystem;
using attribution::NamedRoi;

namespace {

const TechniqueRun& find_run(const Case& c, const std::string& technique, const std::string& label) {
  for (const TechniqueRun& r : c.techniques)
    if (r.technique == technique && r.label == label) return r;
  throw CaseError(fmt::format("attribute: case {} has no run of '{}'{}", c.name, technique,
                              label.empty() ? "" : " with label '" + label + "'"));
}

FloatImage read_reference(const GoldenStore& store, const Case& c, const std::string& aov) {
  const std::string stem = GoldenStore::reference_stem(aov, c.output);
  const std::string path = store.find(stem, "");
  if (path.empty())
    throw std::runtime_error(fmt::format("attribute: {}: no reference '{}' in {} (gibench update-goldens --case {} "
                                         "--reference creates it)", c.name, stem, store.dir(), c.name));
  return store.read(path);
}

// The reference's per-pixel variance (MSE units) per ROI: two renders at `spp` with other
// seeds give 2 x the variance at that spp; the committed reference's is that x spp / its spp.
std::vector<double> reference_noise(Gpu& gpu, const Case& c, const std::string& aov, uint32_t spp,
                                    uint32_t committed_spp, const std::vector<NamedRoi>& rois) {
  TechniqueRun ref;
  ref.technique = "reference";
  ref.presets = {"ultra"};
  ref.spp = spp;
  ref.compare_aov = aov;
  const FloatImage a = render_case(gpu, c, ref, "ultra", 7001).image;
  const FloatImage b = render_case(gpu, c, ref, "ultra", 7002).image;
  std::vector<double> out;
  for (const NamedRoi& r : rois) {
    const attribution::RoiError e = attribution::roi_error({a}, b, metrics::roi_pixels(r.box, a.width, a.height));
    out.push_back(e.mse / 2.0 * double(spp) / double(std::max<uint32_t>(committed_spp, 1)));
  }
  return out;
}

}  // namespace

int cmd_attribute(const AttributeOptions& o) {
  if (o.technique.empty()) throw std::invalid_argument("attribute: expected --technique NAME");
  if (o.seeds == 0 || o.oracle_seeds == 0 || o.noise_spp == 0)
    throw std::invalid_argument("attribute: expected --seeds, --oracle-seeds and --noise-spp >= 1");
  const Technique& t = find_technique(o.technique);
  std::vector<size_t> game;  // indices into t.stages of the stages with an oracle
  for (size_t i = 0; i < t.stages.size(); ++i)
    if (t.stages[i].make) game.push_back(i);
  if (game.empty())
    throw std::invalid_argument(fmt::format("attribute: technique '{}' declares no stage with an oracle "
                                            "(Technique::stages)", t.name));
  std::vector<Case> cases = select_cases(o.suite);
  if (cases.size() != 1)
    throw CaseError(fmt::format("attribute: expected --case naming exactly one case, got {}", cases.size()));
  auto gpu = Gpu::create({o.suite.device, o.suite.validate});
  const DeviceInfo& dev = gpu->info();
  const Tier tier = resolve_tier(o.suite.tier, device_class(dev.driver_name, dev.name));
  const Case c = at_tier(cases.front(), tier);
  const TechniqueRun& run = find_run(c, o.technique, o.label);
  const std::string preset = o.preset.empty() ? run.presets.front() : o.preset;
  const std::string aov = run.compare_aov.empty() ? c.output : run.compare_aov;
  const std::string cache_root = tier == Tier::gpu ? reference_cache_root(o.suite.reference_cache) : "";
  const GoldenStore store = prepare_references(*gpu, o.suite.goldens_dir, cache_root, c, tier).store;
  fmt::print("attribute {} {} {} ({}x{}, {} frames, compared: {}) on {} ({}), tier {}\n", c.name, run.name(), preset,
             c.width, c.height, run.frames ? run.frames : c.frames, aov, dev.name, dev.driver_info, tier_name(tier));

  OracleInputs in;
  in.width = c.width;
  in.height = c.height;
  in.reference[aov] = read_reference(store, c, aov);
  RunHooks reads;
  for (size_t i : game) {
    for (const std::string& a : t.stages[i].reference_aovs)
      if (!in.reference.count(a)) in.reference[a] = read_reference(store, c, a);
    for (const std::string& r : t.stages[i].seed_reads) reads.read.push_back(r);
  }
  const auto t0 = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  for (uint32_t s = 0; s < o.oracle_seeds; ++s) {
    CaseRender r = render_case_hooked(*gpu, c, run, preset, 1000 + s, reads);
    for (const std::string& name : reads.read) {
      const ResolvedResource* res = r.plan.find(name);
      in.formats[name] = res->desc.format;
      in.extents[name] = {res->width, res->height};
    }
    in.seeds.push_back(std::move(r.read));
    fmt::print("  oracle seed render {}/{} ({:.0f} s)\n", s + 1, o.oracle_seeds, elapsed());
    std::fflush(stdout);
  }
  std::vector<std::vector<ResourceOverride>> oracles;
  std::vector<std::string> names;
  for (size_t i : game) {
    std::vector<ResourceOverride> ov;
    for (auto& [resource, bytes] : t.stages[i].make(in)) ov.push_back({t.stages[i].after_pass, resource, bytes});
    oracles.push_back(std::move(ov));
    names.push_back(t.stages[i].name);
  }

  std::vector<NamedRoi> rois{{"image", {}}};
  for (const Roi& r : c.rois) rois.push_back({r.name, {r.x0, r.y0, r.x1, r.y1}});
  attribution::Options opts;
  opts.seeds = o.seeds;
  const nlohmann::json record = store.record_of(GoldenStore::reference_stem(aov, c.output) + ".exr");
  const uint32_t committed_spp = record.value("spp", 0u);
  opts.noise_floor = reference_noise(*gpu, c, aov, o.noise_spp, committed_spp, rois);
  fmt::print("  reference noise floor from two {}-spp renders, scaled to the reference's {} spp ({:.0f} s)\n",
             o.noise_spp, committed_spp, elapsed());
  const uint32_t total = (1u << game.size()) * o.seeds;
  uint32_t done = 0;
  auto render = [&](uint32_t mask, uint32_t seed) {
    RunHooks hooks;
    for (size_t i = 0; i < oracles.size(); ++i)
      if (mask & (1u << i)) hooks.overrides.insert(hooks.overrides.end(), oracles[i].begin(), oracles[i].end());
    FloatImage img = render_case_hooked(*gpu, c, run, preset, seed, hooks).image;
    fmt::print("  render {}/{}: oracles {{{}}} seed {} ({:.0f} s)\n", ++done, total,
               attribution::mask_names(names, mask), seed, elapsed());
    std::fflush(stdout);
    return img;
  };
  const attribution::Attribution a = attribution::attribute(names, render, in.reference.at(aov), rois, opts);

  attribution::ReportContext ctx;
  ctx.case_name = c.name;
  ctx.row = run.name();
  ctx.preset = preset;
  ctx.aov = aov;
  ctx.device = dev.name;
  for (const TechniqueStage& s : t.stages) ctx.stages.push_back({s.name, s.passes, s.oracle});
  fmt::print("{}", attribution::format_table(a, ctx));
  const fs::path dir = fs::path(o.suite.out) / "attribution";
  fs::create_directories(dir);
  const std::string stem = fmt::format("{}.{}.{}", c.name, run.name(), preset);
  std::ofstream(dir / (stem + ".json")) << attribution::to_json(a, ctx).dump(2) << "\n";
  std::ofstream(dir / (stem + ".html")) << attribution::waterfall_html(a, ctx);
  fmt::print("wrote {} and {}\n", (dir / (stem + ".json")).string(), (dir / (stem + ".html")).string());
  return 0;
}

}  // namespace gib
