#include "harness/row_runner.h"

#include <fmt/format.h>

#include <chrono>

#include "harness/verdict.h"
#include "renderer/vk/gpu.h"

namespace gib {

RowRunner::RowRunner(Gpu& gpu, const SuiteOptions& o, const std::vector<Case>& cases, Tier tier,
                     std::string cache_root, SuiteResult& suite)
    : gpu_(gpu), o_(o), cases_(cases), tier_(tier), cache_root_(std::move(cache_root)), suite_(suite) {}

CaseContext* RowRunner::context(size_t ci) {
  if (failed_cases_.count(ci)) return nullptr;
  if (auto it = contexts_.find(ci); it != contexts_.end()) return it->second.get();
  const Case& c = cases_[ci];
  try {
    // GPU tier: references come from the cache; any missing are rendered first.
    bool rendered = false;
    ReferenceSource src = prepare_references(gpu_, o_.goldens_dir, cache_root_, c, tier_, &rendered);
    if (tier_ == Tier::gpu && c.reference_spp) {
      nlohmann::json meta = src.store.metadata();
      suite_.references[c.name] = {{"key", src.key}, {"dir", src.store.dir()}, {"rendered", rendered},
                                   {"spp", recorded_reference_spp(c, meta)},
                                   {"noise_floor", reference_floor(c, src)},
                                   {"target", src.request.target_floor},
                                   {"converged", references_converged(c, src)}};
    }
    auto ctx = std::make_unique<CaseContext>(CaseContext{c, technique_store(o_.goldens_dir, c.name, tier_),
                                                         src.store, suite_.tier, suite_.device_class,
                                                         suite_.golden_class, {}, {}, o_});
    if (c.analytic_value) ctx->analytic = FloatImage(c.width, c.height, 4, float(*c.analytic_value));
    check_noise_floor(*ctx, gpu_);
    return (contexts_[ci] = std::move(ctx)).get();
  } catch (const std::exception& e) {
    suite_.case_errors.push_back(fmt::format("{}: {}", c.name, e.what()));
    failed_cases_.insert(ci);
    return nullptr;
  }
}

const ResultRow* RowRunner::run(const PlannedRow& p, const RowProgress& progress) {
  const auto start = std::chrono::steady_clock::now();
  CaseContext* ctx = context(p.case_index);
  if (!ctx) return nullptr;
  const Case& c = cases_[p.case_index];
  const TechniqueRun& run = planned_run(cases_, p);
  try {
    Evaluation e = evaluate_row(*ctx, gpu_, run, p.preset, p.kind, p.control, progress);
    if (p.kind == "negative_control")
      control_verdict(e.row, c.negative_controls.at(p.run_index), suite_.device_class, suite_.tier);
    else
      technique_verdict(e.row, e.failed, run, suite_.device_class, suite_.tier);
    // A reference short of its floor (a budgeted `gibench references --max-spp`) is said on every
    // row compared with it, never silently.
    if (suite_.references.contains(c.name) && !suite_.references[c.name]["converged"].get<bool>()) {
      const auto& r = suite_.references[c.name];
      e.row.messages.push_back(fmt::format(
          "reference not converged: noise floor {:.4f} > {:.4f} at {} spp (refine it: gibench references --case {})",
          r["noise_floor"].get<double>(), r["target"].get<double>(), r["spp"].get<uint32_t>(), c.name));
    }
    e.row.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    suite_.rows.push_back(std::move(e.row));
    return &suite_.rows.back();
  } catch (const std::exception& e) {
    suite_.case_errors.push_back(fmt::format("{}: {}", c.name, e.what()));
    failed_cases_.insert(p.case_index);
    return nullptr;
  }
}

void RowRunner::finish() {
  for (auto& [ci, ctx] : contexts_) write_reference_previews(*ctx);
  for (auto& m : gpu_.validation_messages()) suite_.case_errors.push_back("validation: " + m);
}

RowLine row_line(const std::string& key, const ResultRow& row) {
  RowLine l{key, row.status, row.wall_s, "", row.messages};
  auto add = [&](const char* metric, const char* label, const char* f) {
    auto it = row.metrics.find(metric);
    if (it == row.metrics.end()) return;
    if (!l.figures.empty()) l.figures += "  ";
    l.figures += fmt::format(fmt::runtime(f), label, it->second);
  };
  add("flip_vs_reference", "FLIP ref", "{} {:.4f}");
  add("psnr_vs_reference", "PSNR ref", "{} {:.2f}");
  add("flip_vs_golden", "FLIP golden", "{} {:.4f}");
  if (row.gpu_ms > 0) l.figures += fmt::format("{}GPU {:.3f} ms", l.figures.empty() ? "" : "  ", row.gpu_ms);
  return l;
}

}  // namespace gib
