// `gibench update-goldens`: renders what was asked, prints old-vs-new FLIP for every golden it
// replaces, writes atomically and keeps the old file in history/. golden.json records device,
// driver, revision, settings hash, date and reason; with --reference also spp (the case's
// reference_spp, or --spp), seed, AOV and, with --noise-floor, the noise floor (FLIP between
// two renders with different seeds; goldens.h measure_noise_floor).
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "harness/case_render.h"
#include "harness/goldens.h"
#include "harness/image_io.h"
#include "metrics/flip.h"
#include "harness/suite.h"
#include "harness/tier.h"

namespace gib {
namespace fs = std::filesystem;
namespace {

FlipOptions flip_opts(const Case& c) {
  FlipOptions f;
  f.ppd = c.ppd;
  f.mode = c.flip_mode == "ldr" ? FlipOptions::Mode::ldr : FlipOptions::Mode::hdr;
  return f;
}

nlohmann::json file_record(const Gpu& gpu, const CaseRender& r, const std::string& reason) {
  return {{"device", gpu.info().name}, {"driver", gpu.info().driver_name + " " + gpu.info().driver_info},
          {"revision", renderer_revision()}, {"settings_hash", r.settings_hash}, {"date", utc_now_iso()},
          {"reason", reason}, {"technique", r.technique}, {"preset", r.preset}, {"frames", r.frames},
          {"spp", r.spp}};
}

void replace(GoldenStore& store, nlohmann::json& meta, const std::string& stem, const std::string& cls,
             const FloatImage& image, nlohmann::json record, const Case& c) {
  std::string old_path = store.find(stem, cls);
  std::string name = store.file_name(stem, cls);
  if (!old_path.empty() && std::filesystem::path(old_path).filename() == name) {
    FloatImage old = store.read_without_record(old_path);  // its record may be what is being restored
    if (old.width == image.width && old.height == image.height) {
      double f = flip(old, image, flip_opts(c)).mean;
      fmt::print("  {}: old vs new FLIP {:.6f}\n", name, f);
      record["flip_vs_previous"] = f;
    } else {
      fmt::print("  {}: old {}x{} vs new {}x{} (size changed)\n", name, old.width, old.height, image.width,
                 image.height);
    }
  } else {
    fmt::print("  {}: new golden\n", name);
  }
  std::string hist = store.write(stem, cls, image);
  if (!hist.empty()) {
    fmt::print("  previous kept as {} (move it back to undo)\n", hist);
    record["previous"] = std::filesystem::path(hist).filename().string();
  }
  meta["files"][name] = record;
}

}  // namespace

// --from-run DIR: every technique row of DIR/results.json whose case and technique are selected
// becomes the approved golden of the run's device class and tier, from DIR/img/<row>.exr.
static int update_from_run(const UpdateOptions& o) {
  const fs::path dir(o.from_run);
  nlohmann::json results;
  {
    std::ifstream in(dir / "results.json");
    if (!in) throw std::runtime_error(fmt::format("{}: expected the results.json of a gibench run, got no such file",
                                                  (dir / "results.json").string()));
    try {
      results = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
      throw std::runtime_error(fmt::format("{}: expected valid JSON, got: {}", (dir / "results.json").string(), e.what()));
    }
  }
  const nlohmann::json dev = results.value("device", nlohmann::json::object());
  const std::string cls = dev.value("class", ""), tier_text = dev.value("tier", "ci");
  if (cls.empty()) throw std::runtime_error(fmt::format("{}: device.class: expected the run's device class, got none",
                                                        (dir / "results.json").string()));
  const Tier tier = resolve_tier(tier_text, cls);
  std::map<std::string, Case> cases;
  for (Case& c : select_cases(o.suite)) cases.emplace(c.name, at_tier(c, tier));
  std::map<std::string, nlohmann::json> metas;
  std::map<std::string, GoldenStore> stores;
  // The rows to approve, every output checked before any golden is replaced. Rows a quick
  // profile listed as not run have no output: they are left as they are, and counted.
  const nlohmann::json all_rows = results.value("results", nlohmann::json::array());
  std::vector<const nlohmann::json*> rows;
  size_t not_run = 0;
  for (const auto& row : all_rows) {
    const std::string case_name = row.value("case", ""), technique = row.value("technique", "");
    if (row.value("kind", "") != "technique" || !cases.count(case_name)) continue;
    if (!technique_selected(o.techniques, technique.substr(0, technique.find('+')))) continue;
    if (row.value("status", "") == "not_run") {
      ++not_run;
      continue;
    }
    const fs::path exr = dir / "img" / (row.value("image", "") + ".exr");
    if (!fs::exists(exr))
      throw std::runtime_error(fmt::format("{}: expected the output of row {}/{}.{}, got no such file", exr.string(),
                                           case_name, technique, row.value("preset", "")));
    rows.push_back(&row);
  }
  size_t approved = 0;
  for (const nlohmann::json* r : rows) {
    const nlohmann::json& row = *r;
    const std::string case_name = row.value("case", ""), technique = row.value("technique", "");
    const fs::path exr = dir / "img" / (row.value("image", "") + ".exr");
    auto [it, fresh] = stores.try_emplace(case_name, technique_store(o.suite.goldens_dir, case_name, tier));
    if (fresh) {
      metas[case_name] = it->second.metadata();
      fmt::print("{}:\n", case_name);
    }
    FloatImage img = read_image(exr.string());
    nlohmann::json rec = {{"device", dev.value("name", "")}, {"driver", dev.value("driver", "") + " " + dev.value("driver_info", "")},
                          {"revision", renderer_revision()}, {"date", utc_now_iso()}, {"reason", o.reason},
                          {"technique", technique}, {"preset", row.value("preset", "")}, {"tier", tier_name(tier)},
                          {"size", {img.width, img.height}}, {"from_run", fs::absolute(dir).string()},
                          {"run_status", row.value("status", "")}};
    if (tier == Tier::gpu) rec["storage"] = fits_half(img) ? "half" : "float (a value exceeds half's range)";
    const Case& c = cases.at(case_name);
    if (img.width != c.width || img.height != c.height)
      throw std::runtime_error(fmt::format("{}: expected {}x{} ({} at the {} tier), got {}x{}", exr.string(), c.width,
                                           c.height, case_name, tier_name(tier), img.width, img.height));
    replace(it->second, metas[case_name], GoldenStore::technique_stem(technique, row.value("preset", "")), cls, img, rec, c);
    ++approved;
  }
  for (auto& [name, store] : stores) store.write_metadata(metas[name]);
  fmt::print("approved {} technique goldens from {} (device class {}, tier {})\n", approved, dir.string(), cls,
             tier_name(tier));
  if (not_run)
    fmt::print("{} selected rows were not run there (quick profile): their goldens are left as they are\n", not_run);
  return 0;
}

int cmd_update_goldens(const UpdateOptions& o) {
  if (!o.from_run.empty()) {
    if (o.reason.empty()) throw std::invalid_argument("--reason: expected why the goldens change (recorded in golden.json)");
    if (o.reference) throw std::invalid_argument("--from-run: expected without --reference (a run's outputs are technique goldens)");
    return update_from_run(o);
  }
  if (o.reason.empty()) throw std::invalid_argument("--reason: expected why the goldens change (recorded in golden.json)");
  if ((o.spp || o.noise_floor || o.only_reference) && !o.reference)
    throw std::invalid_argument(
        "--spp, --noise-floor, --only-reference: expected with --reference (they describe the reference render)");
  std::vector<Case> cases = select_cases(o.suite);
  auto gpu = Gpu::create({o.suite.device, o.suite.validate});
  std::string cls = device_class(gpu->info().driver_name, gpu->info().name);
  const Tier tier = resolve_tier(o.suite.tier, cls);
  if (tier == Tier::gpu && o.reference)
    throw std::invalid_argument("--reference: expected at the CI tier (--tier ci); GPU-tier references are not committed: "
                                "gibench references renders them into the local cache");
  fmt::print("tier {}\n", tier_name(tier));
  for (const Case& c0 : cases) {
    const Case c = at_tier(c0, tier);
    GoldenStore store = technique_store(o.suite.goldens_dir, c.name, tier);
    nlohmann::json meta = store.metadata();
    fmt::print("{}:\n", c.name);
    if (o.reference && c.reference_spp == 0) fmt::print("  no reference (reference_spp 0)\n");
    if (o.reference && c.reference_spp > 0) {
      // The reference's configuration: the case's, at --spp when given. golden.json records the
      // spp used; that, not reference_spp, describes the committed file.
      Case rc = c;
      if (o.spp) rc.reference_spp = o.spp;
      if (uint32_t was = recorded_reference_spp(c, meta); was > rc.reference_spp)
        fmt::print("  the committed reference has {} spp; this render has {} (--spp N keeps more)\n", was,
                   rc.reference_spp);
      // A moving scene evaluated at several frames has one reference per frame (scene frozen
      // at that frame's time); otherwise one reference of the scene at time 0.
      std::vector<uint32_t> at = per_frame_references(c) ? evaluation_frames(c) : std::vector<uint32_t>{0};
      for (uint32_t f : at) {
        CaseRender r = render_reference(*gpu, rc, 0, f);
        for (auto& [aov, img] : r.aovs) {
          nlohmann::json rec = file_record(*gpu, r, o.reason);
          rec["aov"] = aov;
          rec["seed"] = c.reference_seed;
          if (f) rec["at_frame"] = f;
          // "" class: one reference file for every device (goldens.h).
          replace(store, meta, GoldenStore::reference_stem(aov, c.output, f), "", img, rec, c);
        }
        if (f != at.back() || !o.noise_floor) continue;
        // Noise floor: the same reference with another seed; flip bounds vs the reference must
        // sit at 3x or more (check_noise_floor_bounds).
        nlohmann::json floor = measure_noise_floor(*gpu, rc, &r);
        record_noise_floor(meta, floor);
        // Every committed AOV is a reference some run compares with, so the floor that decides
        // whether the render has converged is the worst one (ci/gpu_references.sh reads the
        // last line).
        std::string worst_aov = c.output;
        double worst = floor["flip"].get<double>();
        for (auto& [aov, f] : floor["aovs"].items()) {
          fmt::print("  noise floor of {}: {:.6f}\n", aov, f.get<double>());
          if (f.get<double>() > worst) worst = f.get<double>(), worst_aov = aov;
        }
        fmt::print("  noise floor (FLIP between seeds {} and {} at {} spp, worst AOV {}): {:.6f}\n", c.reference_seed,
                   c.reference_seed + 1000, r.spp, worst_aov, worst);
      }
      if (!o.noise_floor && meta.contains("noise_floor")) {
        fmt::print("  noise floor not measured (--noise-floor); the previous record ({:.6f} at {} spp) described the "
                   "replaced reference and is removed\n",
                   meta["noise_floor"].value("flip", 0.0), meta["noise_floor"].value("spp", 0u));
        meta.erase("noise_floor");
      }
    }
    for (auto& run : c.techniques) {
      if (o.only_reference) break;
      if (!technique_selected(o.techniques, run.technique)) continue;
      for (auto& preset : run.presets) {
        CaseRender r = render_case(*gpu, c, run, preset);
        nlohmann::json rec = file_record(*gpu, r, o.reason);
        rec["tier"] = tier_name(tier);
        rec["size"] = {c.width, c.height};
        if (tier == Tier::gpu) rec["storage"] = fits_half(r.image) ? "half" : "float (a value exceeds half's range)";
        replace(store, meta, GoldenStore::technique_stem(run.name(), preset), cls, r.image, rec, c);
      }
    }
    store.write_metadata(meta);
  }
  return 0;
}

}  // namespace gib
