#include "harness/attribution/attribute_command.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>

#include "harness/attribution/attribution.h"
#include "harness/attribution/attribution_report.h"
#include "harness/attribution/row_inputs.h"
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

bool has_reference(const GoldenStore& store, const Case& c, const std::string& aov) {
  for (uint32_t f : evaluation_frames(c))
    if (store.find(GoldenStore::reference_stem(aov, c.output, reference_frame(c, f)), "").empty()) return false;
  return true;
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
      return fmt::format("no reference '{}' committed for the case",
                         GoldenStore::reference_stem(a, c.output, reference_frame(c, evaluation_frames(c).back())));
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

  const std::vector<uint32_t> frames = evaluation_frames(c);
  const bool lag = per_frame_references(c);
  const auto t0 = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  const OracleRow orow{gpu, c, run, preset, st, store, analytic, aov, t, verbose};
  if (verbose && frames.size() > 1)
    fmt::print("  evaluated at frames {} of every run{}\n", fmt::join(frames, ", "),
               lag ? ", each against the reference of the scene frozen there (oracles: renders of those frozen scenes)"
                   : "");
  // The oracles: one set for a still scene. A scene that changes gets a set per evaluation frame,
  // made from seed renders of the scene frozen at that frame (the converged state there: a
  // temporal stage's oracle is its converged history, not the seed mean of a run that lags) and
  // that frame's reference; each set holds from the frame after the previous evaluation frame
  // through its own (executor frames are 0-based), the last to the end of the run.
  std::vector<std::vector<ResourceOverride>> oracles(game.size());
  for (size_t k = 0; k < (lag ? frames.size() : 1); ++k) {
    const OracleInputs in = oracle_inputs(orow, game, lag ? frames[k] : 0, elapsed);
    const uint32_t first = lag && k > 0 ? frames[k - 1] : 0;
    const uint32_t last = lag && k + 1 < frames.size() ? frames[k] - 1 : UINT32_MAX;
    for (size_t g = 0; g < game.size(); ++g) {
      const TechniqueStage& s = t.stages[game[g]];
      for (auto& [resource, bytes] : s.make(in))
        oracles[g].push_back({s.after_pass_of.count(resource) ? s.after_pass_of.at(resource) : s.after_pass, resource,
                              bytes, first, last});
    }
  }
  std::vector<std::string> names;
  for (size_t i : game) names.push_back(t.stages[i].name);

  std::vector<NamedRoi> rois{{"image", {}}};
  for (const Roi& r : c.rois) rois.push_back({r.name, {r.x0, r.y0, r.x1, r.y1}});
  // Per evaluation frame: its reference, noise floor and FLIP map against that reference.
  std::vector<FloatImage> references;
  for (uint32_t f : frames)
    references.push_back(analytic ? FloatImage(c.width, c.height, 4, float(c.analytic_value.value_or(0.0)))
                                  : read_reference(store, c, aov, reference_frame(c, f)));
  const FlipOptions flip_opts = flip_options(c);
  std::map<uint32_t, std::vector<double>> noise;  // by reference frame
  std::vector<attribution::Options> opts(frames.size());
  for (size_t k = 0; k < frames.size(); ++k) {
    const uint32_t rf = reference_frame(c, frames[k]);
    opts[k].seeds = st.seeds;
    const FloatImage& ref = references[k];
    // FLIP needs light in the reference to set its exposures; a dark frame plays no FLIP game.
    bool lit = false;
    for (uint32_t y = 0; y < ref.height && !lit; ++y)
      for (uint32_t x = 0; x < ref.width && !lit; ++x) lit = metrics::luminance(ref, x, y) > 0;
    if (lit) opts[k].flip_map = [&ref, &flip_opts](const FloatImage& img) { return flip(ref, img, flip_opts).error_map; };
    if (analytic) {
      opts[k].noise_floor.assign(rois.size(), 0.0);
      continue;
    }
    if (!noise.count(rf)) {
      const uint32_t committed_spp =
          store.record_of(GoldenStore::reference_stem(aov, c.output, rf) + ".exr").value("spp", 0u);
      noise[rf] = reference_noise(gpu, c, aov, st.noise_spp, committed_spp, rois, rf);
      if (verbose)
        fmt::print("  reference noise floor{} from two {}-spp renders, scaled to the reference's {} spp ({:.0f} s)\n",
                   rf ? fmt::format(" at frame {}", rf) : "", st.noise_spp, committed_spp, elapsed());
    }
    opts[k].noise_floor = noise.at(rf);
  }
  if (analytic && verbose) fmt::print("  reference: the analytic value {} (no noise floor)\n", *c.analytic_value);

  const uint32_t total = (1u << game.size()) * st.seeds;
  uint32_t done = 0;
  auto render = [&](uint32_t mask, uint32_t seed) {
    RunHooks hooks;
    for (size_t i = 0; i < oracles.size(); ++i)
      if (mask & (1u << i)) hooks.overrides.insert(hooks.overrides.end(), oracles[i].begin(), oracles[i].end());
    const CaseRender r = render_case_hooked(gpu, c, run, preset, seed, hooks);
    std::vector<FloatImage> images;  // every evaluation frame of this one run
    for (uint32_t f : frames) images.push_back(frames.size() == 1 ? r.image : image_at(r, f, c));
    ++done;
    if (verbose)
      fmt::print("  render {}/{}: oracles {{{}}} seed {} ({:.0f} s)\n", done, total, attribution::mask_names(names, mask),
                 seed, elapsed());
    std::fflush(stdout);
    return images;
  };

  attribution::ReportContext ctx;
  ctx.case_name = c.name;
  ctx.row = run.name();
  ctx.preset = preset;
  ctx.aov = aov;
  ctx.device = dev.name;
  for (size_t i = 0; i < t.stages.size(); ++i)
    ctx.stages.push_back({t.stages[i].name, t.stages[i].passes,
                          excluded.count(i) ? excluded.at(i) : t.stages[i].oracle});
  std::string table, html;
  nlohmann::json full;
  if (frames.size() == 1) {
    const attribution::Attribution a = attribution::attribute(
        names, [&](uint32_t mask, uint32_t seed) { return render(mask, seed).front(); }, references[0], rois, opts[0]);
    table = attribution::format_table(a, ctx);
    full = attribution::to_json(a, ctx);
    html = attribution::waterfall_html(a, ctx);
  } else {
    const attribution::LagAttribution a = attribution::attribute_frames(names, render, frames, references, rois, opts);
    table = attribution::format_table(a, ctx);
    full = attribution::to_json(a, ctx);
    html = attribution::waterfall_html(a, ctx);
  }
  if (verbose) fmt::print("{}", table);
  const fs::path dir = fs::path(suite.out) / "attribution";
  fs::create_directories(dir);
  const std::string stem = fmt::format("{}.{}.{}", c.name, run.name(), preset);
  std::ofstream(dir / (stem + ".json")) << full.dump(2) << "\n";
  std::ofstream(dir / (stem + ".html")) << html;
  if (verbose) fmt::print("wrote {} and {}\n", (dir / (stem + ".json")).string(), (dir / (stem + ".html")).string());
  nlohmann::json summary = {{"page", "attribution/" + stem + ".html"},
                            {"json", "attribution/" + stem + ".json"},
                            {"stages_in_game", names},
                            {"renders", full.value("renders", 0)},
                            {"seconds", elapsed()},
                            {"rois", nlohmann::json::array()}};
  if (frames.size() > 1) summary["frames"] = frames;  // the rois' figures: the integrated game's
  for (const auto& r : full["rois"])
    summary["rois"].push_back({{"roi", r["roi"]},
                               {"largest", r["largest"]},
                               {"mse", r["technique"]["mse"]},
                               {"signed_energy", r["technique"]["signed_energy"]},
                               {"oracle_floor", r["oracle_floor"]["mse"]}});
  return summary;
}

}  // namespace gib
