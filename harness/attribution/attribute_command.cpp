#include "harness/attribution/attribute_command.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "harness/attribution/attribution.h"
#include "harness/attribution/attribution_report.h"
#include "harness/case_render.h"
#include "harness/goldens.h"
#include "harness/measure.h"
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

bool has_reference(const GoldenStore& store, const Case& c, const std::string& aov) {
  return !store.find(GoldenStore::reference_stem(aov, c.output), "").empty();
}

// Why stage `s` cannot play in this row ("" when it can): the pass its oracle follows is culled,
// a resource it reads is not made, or a reference AOV it needs is not committed (in an analytic
// case, only indirect_diffuse of a radiance comparison can be derived).
std::string why_not_playable(const TechniqueStage& s, const Plan& plan, const GoldenStore& store, const Case& c,
                             bool analytic, const std::string& aov, const Technique& t) {
  bool runs = false;
  for (const PlannedPass* p : plan.running()) runs |= p->name == s.after_pass;
  if (!runs) return fmt::format("{} does not run in this row", s.after_pass);
  for (const std::string& r : s.seed_reads)
    if (!plan.find(r)) return fmt::format("no resource '{}' in this row", r);
  for (const std::string& a : s.reference_aovs) {
    if (a == aov) continue;
    if (analytic && !(a == "indirect_diffuse" && aov == "radiance" && t.contract_aovs.count("direct")))
      return fmt::format("the case is analytic and '{}' cannot be derived from it", a);
    if (!analytic && !has_reference(store, c, a))
      return fmt::format("no reference '{}' committed for the case", GoldenStore::reference_stem(a, c.output));
  }
  return "";
}

}  // namespace

int cmd_attribute(const AttributeOptions& o) {
  const AttributionSettings& st = o.settings;
  if (st.seeds == 0 || st.oracle_seeds == 0 || st.oracle_frames == 0 || st.noise_spp == 0)
    throw std::invalid_argument("attribute: expected --seeds, --oracle-seeds, --oracle-frames and --noise-spp >= 1");
  std::vector<Case> cases = select_cases(o.suite);
  if (cases.size() != 1)
    throw CaseError(fmt::format("attribute: expected --case naming exactly one case, got {}", cases.size()));
  auto gpu = Gpu::create({o.suite.device, o.suite.validate});
  const DeviceInfo& dev = gpu->info();
  const Tier tier = resolve_tier(o.suite.tier, device_class(dev.driver_name, dev.name));
  const Case c = at_tier(cases.front(), tier);
  const TechniqueRun& run = find_run(c, o.technique, o.label);
  attribute_row(*gpu, c, tier, run, o.preset.empty() ? run.presets.front() : o.preset, st, o.suite, true);
  return 0;
}

nlohmann::json attribute_row(Gpu& gpu, const Case& c, Tier tier, const TechniqueRun& run, const std::string& preset,
                             const AttributionSettings& st, const SuiteOptions& suite, bool verbose) {
  const DeviceInfo& dev = gpu.info();
  const Technique& t = find_technique(run.technique);
  if (std::none_of(t.stages.begin(), t.stages.end(), [](const TechniqueStage& x) { return bool(x.make); }))
    throw std::invalid_argument(fmt::format("attribute: technique '{}' declares no stage with an oracle "
                                            "(Technique::stages)", t.name));
  const std::string aov = run.compare_aov.empty() ? c.output : run.compare_aov;
  // An analytic case (reference_spp 0) has no path-traced reference: the compared image is the
  // constant analytic value (exact, no noise floor), and a stage's indirect_diffuse reference is
  // that value less the technique's own direct AOV (the oracle seeds' mean): what makes the image
  // exact given the direct light the stage received.
  const bool analytic = c.reference_spp == 0 && c.analytic_value.has_value();
  const std::string cache_root = tier == Tier::gpu ? reference_cache_root(suite.reference_cache) : "";
  const GoldenStore store =
      analytic ? GoldenStore(suite.goldens_dir, c.name) : prepare_references(gpu, suite.goldens_dir, cache_root, c, tier).store;
  if (verbose)
    fmt::print("attribute {} {} {} ({}x{}, {} frames, compared: {}) on {} ({}), tier {}\n", c.name, run.name(), preset,
             c.width, c.height, run.frames ? run.frames : c.frames, aov, dev.name, dev.driver_info, tier_name(tier));

  // The row's plan (one frame) says which oracles can be written here.
  Case one = c;
  one.frames = 1;
  TechniqueRun one_run = run;
  one_run.frames = 1;
  const Plan plan = render_case_hooked(gpu, one, one_run, preset, 1000, {}).plan;
  std::vector<size_t> game;  // indices into t.stages of the stages whose oracle plays
  std::map<size_t, std::string> excluded;  // stages with an oracle that cannot play here, and why
  for (size_t i = 0; i < t.stages.size(); ++i) {
    if (!t.stages[i].make) continue;
    const std::string why = why_not_playable(t.stages[i], plan, store, c, analytic, aov, t);
    if (why.empty())
      game.push_back(i);
    else
      excluded[i] = "no oracle in this row: " + why;
  }
  if (verbose)
    for (const auto& [i, why] : excluded) fmt::print("  stage {}: {}\n", t.stages[i].name, why);
  if (game.empty()) throw CaseError(fmt::format("attribute: {}: no stage of {} can take its oracle in this row", c.name, run.name()));

  OracleInputs in;
  in.width = c.width;
  in.height = c.height;
  const FloatImage constant(c.width, c.height, 4, float(c.analytic_value.value_or(0.0)));
  in.reference[aov] = analytic ? constant : read_reference(store, c, aov);
  RunHooks reads;
  reads.read_frames = st.oracle_frames;
  bool derive_indirect = false;  // analytic: indirect_diffuse = the value - the technique's direct
  for (size_t i : game) {
    for (const std::string& a : t.stages[i].reference_aovs) {
      if (in.reference.count(a)) continue;
      if (!analytic) {
        in.reference[a] = read_reference(store, c, a);
      } else if (!derive_indirect) {
        derive_indirect = true;
        reads.read.push_back(t.contract_aovs.at("direct"));
      }
    }
    for (const std::string& r : t.stages[i].seed_reads) reads.read.push_back(r);
  }
  const auto t0 = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  for (uint32_t s = 0; s < st.oracle_seeds; ++s) {
    CaseRender r = render_case_hooked(gpu, c, run, preset, 1000 + s, reads);
    for (const std::string& name : reads.read) {
      const ResolvedResource* res = r.plan.find(name);
      in.formats[name] = res->desc.format;
      in.extents[name] = {res->width, res->height};
    }
    for (auto& before : r.read_before) in.seeds.push_back(std::move(before));
    in.seeds.push_back(std::move(r.read));
    if (verbose)
      fmt::print("  oracle seed render {}/{}, reads of its last {} frames ({:.0f} s)\n", s + 1, st.oracle_seeds,
               r.read_before.size() + 1, elapsed());
    std::fflush(stdout);
  }
  if (derive_indirect) {
    const std::string direct = t.contract_aovs.at("direct");
    FloatImage indirect = constant;
    for (const auto& seed : in.seeds) {
      const FloatImage d = decode_texels(in.formats.at(direct), c.width, c.height, seed.at(direct));
      for (size_t i = 0; i < indirect.pixels.size(); ++i) indirect.pixels[i] -= d.pixels[i] / float(in.seeds.size());
    }
    in.reference["indirect_diffuse"] = indirect;
    if (verbose) fmt::print("  analytic: indirect_diffuse reference = {} - the seeds' mean {}\n", *c.analytic_value, direct);
  }
  std::vector<std::vector<ResourceOverride>> oracles;
  std::vector<std::string> names;
  for (size_t i : game) {
    std::vector<ResourceOverride> ov;
    const TechniqueStage& st_i = t.stages[i];
    for (auto& [resource, bytes] : st_i.make(in))
      ov.push_back({st_i.after_pass_of.count(resource) ? st_i.after_pass_of.at(resource) : st_i.after_pass, resource, bytes});
    oracles.push_back(std::move(ov));
    names.push_back(t.stages[i].name);
  }

  std::vector<NamedRoi> rois{{"image", {}}};
  for (const Roi& r : c.rois) rois.push_back({r.name, {r.x0, r.y0, r.x1, r.y1}});
  attribution::Options opts;
  opts.seeds = st.seeds;
  const FloatImage& compared_reference = in.reference.at(aov);
  const FlipOptions flip_opts = flip_options(c);
  opts.flip_map = [&](const FloatImage& img) { return flip(compared_reference, img, flip_opts).error_map; };
  const uint32_t committed_spp =
      analytic ? 0u : store.record_of(GoldenStore::reference_stem(aov, c.output) + ".exr").value("spp", 0u);
  if (analytic) {
    opts.noise_floor.assign(rois.size(), 0.0);
    if (verbose) fmt::print("  reference: the analytic value {} (no noise floor)\n", *c.analytic_value);
  } else {
    opts.noise_floor = reference_noise(gpu, c, aov, st.noise_spp, committed_spp, rois);
    if (verbose)
      fmt::print("  reference noise floor from two {}-spp renders, scaled to the reference's {} spp ({:.0f} s)\n",
               st.noise_spp, committed_spp, elapsed());
  }
  const uint32_t total = (1u << game.size()) * st.seeds;
  uint32_t done = 0;
  auto render = [&](uint32_t mask, uint32_t seed) {
    RunHooks hooks;
    for (size_t i = 0; i < oracles.size(); ++i)
      if (mask & (1u << i)) hooks.overrides.insert(hooks.overrides.end(), oracles[i].begin(), oracles[i].end());
    FloatImage img = render_case_hooked(gpu, c, run, preset, seed, hooks).image;
    ++done;
    if (verbose)
      fmt::print("  render {}/{}: oracles {{{}}} seed {} ({:.0f} s)\n", done, total, attribution::mask_names(names, mask),
                 seed, elapsed());
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
  for (size_t i = 0; i < t.stages.size(); ++i)
    ctx.stages.push_back({t.stages[i].name, t.stages[i].passes,
                          excluded.count(i) ? excluded.at(i) : t.stages[i].oracle});
  if (verbose) fmt::print("{}", attribution::format_table(a, ctx));
  const fs::path dir = fs::path(suite.out) / "attribution";
  fs::create_directories(dir);
  const std::string stem = fmt::format("{}.{}.{}", c.name, run.name(), preset);
  const nlohmann::json full = attribution::to_json(a, ctx);
  std::ofstream(dir / (stem + ".json")) << full.dump(2) << "\n";
  std::ofstream(dir / (stem + ".html")) << attribution::waterfall_html(a, ctx);
  if (verbose) fmt::print("wrote {} and {}\n", (dir / (stem + ".json")).string(), (dir / (stem + ".html")).string());
  nlohmann::json summary = {{"page", "attribution/" + stem + ".html"},
                            {"json", "attribution/" + stem + ".json"},
                            {"stages_in_game", names},
                            {"renders", full.value("renders", 0)},
                            {"seconds", elapsed()},
                            {"rois", nlohmann::json::array()}};
  for (const auto& r : full["rois"])
    summary["rois"].push_back({{"roi", r["roi"]},
                               {"largest", r["largest"]},
                               {"mse", r["technique"]["mse"]},
                               {"signed_energy", r["technique"]["signed_energy"]},
                               {"oracle_floor", r["oracle_floor"]["mse"]}});
  return summary;
}

}  // namespace gib
