#include "harness/sweep.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "harness/case_render.h"
#include "harness/goldens.h"
#include "harness/references.h"
#include "metrics/flip.h"
#include "renderer/techniques/technique.h"

namespace fs = std::filesystem;

namespace gib {

void mark_pareto(std::vector<SweepPoint>& pts) {
  for (auto& p : pts) {
    p.pareto = std::none_of(pts.begin(), pts.end(), [&](const SweepPoint& q) {
      return &q != &p && q.gpu_ms <= p.gpu_ms && q.flip <= p.flip && (q.gpu_ms < p.gpu_ms || q.flip < p.flip);
    });
  }
}

std::string sweep_svg(const std::string& case_name, const std::vector<SweepPoint>& pts) {
  const double W = 640, H = 400, L = 70, R = 20, T = 40, B = 50;
  double tmax = 1e-9, emax = 1e-9;
  for (auto& p : pts) {
    tmax = std::max(tmax, p.gpu_ms);
    emax = std::max(emax, p.flip);
  }
  tmax *= 1.1;
  emax *= 1.1;
  auto X = [&](double t) { return L + t / tmax * (W - L - R); };
  auto Y = [&](double e) { return H - B - e / emax * (H - T - B); };
  static const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};
  std::vector<std::string> techs;
  for (auto& p : pts)
    if (std::find(techs.begin(), techs.end(), p.technique) == techs.end()) techs.push_back(p.technique);
  std::string s = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" font-family=\"sans-serif\" font-size=\"12\">\n"
      "<text x=\"{}\" y=\"20\" font-size=\"14\">{}: error vs GPU time (Pareto front dashed)</text>\n"
      "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#000\"/><line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#000\"/>\n"
      "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">GPU ms per frame (0 .. {:.3g})</text>\n"
      "<text x=\"15\" y=\"{}\" transform=\"rotate(-90 15 {})\" text-anchor=\"middle\">FLIP vs reference (0 .. {:.3g})</text>\n",
      W, H, L, case_name, L, H - B, W - R, H - B, L, T, L, H - B, (L + W - R) / 2, H - 12, tmax, (T + H - B) / 2,
      (T + H - B) / 2, emax);
  std::vector<SweepPoint> front;
  for (auto& p : pts)
    if (p.pareto) front.push_back(p);
  std::sort(front.begin(), front.end(), [](auto& a, auto& b) { return a.gpu_ms < b.gpu_ms; });
  std::string poly;
  for (auto& p : front) poly += fmt::format("{:.1f},{:.1f} ", X(p.gpu_ms), Y(p.flip));
  if (!poly.empty()) s += fmt::format("<polyline points=\"{}\" fill=\"none\" stroke=\"#555\" stroke-dasharray=\"4 3\"/>\n", poly);
  for (size_t ti = 0; ti < techs.size(); ++ti) {
    const char* col = kColours[ti % 6];
    s += fmt::format("<text x=\"{}\" y=\"{}\" fill=\"{}\">{}</text>\n", W - R - 120, T + 16 * ti, col, techs[ti]);
    for (auto& p : pts) {
      if (p.technique != techs[ti]) continue;
      s += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"{}\" fill=\"{}\" stroke=\"{}\"/>"
                       "<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"10\">{}</text>\n",
                       X(p.gpu_ms), Y(p.flip), p.pareto ? 6 : 4, col, p.pareto ? "#000" : col, X(p.gpu_ms) + 7,
                       Y(p.flip) - 5, p.preset);
    }
  }
  return s + "</svg>\n";
}

std::vector<SweepPoint> sweep_case(Gpu& gpu, const Case& c, const GoldenStore& store,
                                   const std::vector<std::string>& techniques, bool print) {
  std::vector<SweepPoint> pts;
  for (auto& run : c.techniques) {
    if (!technique_selected(techniques, run.technique)) continue;
    const std::string row = run.label.empty() ? run.technique : run.technique + "+" + run.label;
    std::string aov = run.compare_aov.empty() ? c.output : run.compare_aov;
    std::string ref_path = store.find(GoldenStore::reference_stem(aov, c.output), "");
    if (ref_path.empty())
      throw GoldenError(fmt::format("{}: reference golden missing; create it with: gibench update-goldens --case {} "
                                    "--reference --reason \"initial reference\"", store.dir(), c.name));
    FloatImage ref = store.read(ref_path);
    for (auto& preset : find_technique(run.technique).presets) {
      CaseRender r = render_case(gpu, c, run, preset);
      FlipOptions fo;
      fo.ppd = c.ppd;
      fo.mode = c.flip_mode == "ldr" ? FlipOptions::Mode::ldr : FlipOptions::Mode::hdr;
      // The reference converges over many frames: its cost is the whole convergence. Any other
      // technique: the median of its timed frames (scan-free, after the case's; render_case).
      const bool whole = run.technique == "reference";
      double ms = whole ? r.gpu_ms_total : r.frame_median_ms;
      SweepPoint pt{row, preset, ms, flip(ref, r.image, fo).mean};
      pt.timed_frames = uint32_t(whole ? r.frames : r.timing.frames.size());
      pt.scan_free = r.timing.scan_free();
      std::string rois;
      for (const Roi& roi : c.rois) {
        pt.roi_ratios.emplace_back(roi.name, compute_metric(c, "roi_ratio", r.image, &ref, &roi));  // as `run` reports it
        rois += fmt::format("  {} {:.3f}", roi.name, pt.roi_ratios.back().second);
      }
      pts.push_back(std::move(pt));
      if (print)
        fmt::print("{:<28} {:<8} {:>10.3f} ms  FLIP {:.4f}{}  ({} {} frames)\n", row, preset, ms, pts.back().flip, rois,
                   whole ? "sum of" : "median of", pts.back().timed_frames);
    }
  }
  return pts;
}

int cmd_sweep(const SuiteOptions& o) {
  for (const std::string& t : o.techniques) find_technique(t);  // an unknown name is an error, before any GPU work
  std::vector<Case> cases = select_cases(o);
  auto gpu = Gpu::create({o.device, o.validate});
  std::string cls = device_class(gpu->info().driver_name, gpu->info().name);
  const Tier tier = resolve_tier(o.tier, cls);
  const std::string cache_root = tier == Tier::gpu ? reference_cache_root(o.reference_cache) : "";
  fmt::print("tier {}\n", tier_name(tier));
  for (const Case& c0 : cases) {
    const Case c = at_tier(c0, tier);
    GoldenStore store = prepare_references(*gpu, o.goldens_dir, cache_root, c, tier).store;
    std::vector<SweepPoint> pts = sweep_case(*gpu, c, store, o.techniques);
    mark_pareto(pts);
    fs::path dir = fs::path(o.out) / c.name;
    fs::create_directories(dir);
    std::ofstream csv(dir / "sweep.csv");
    csv << "technique,preset,gpu_ms,flip_vs_reference,pareto\n";
    nlohmann::json j = nlohmann::json::array();
    for (auto& p : pts) {
      csv << fmt::format("{},{},{:.6f},{:.6f},{}\n", p.technique, p.preset, p.gpu_ms, p.flip, p.pareto ? 1 : 0);
      nlohmann::json rois = nlohmann::json::object();
      for (auto& [name, ratio] : p.roi_ratios) rois[name] = ratio;
      j.push_back({{"technique", p.technique}, {"preset", p.preset}, {"gpu_ms", p.gpu_ms}, {"flip", p.flip},
                   {"pareto", p.pareto}, {"timed_frames", p.timed_frames}, {"scan_free", p.scan_free},
                   {"roi_ratio", rois}});
    }
    std::ofstream(dir / "sweep.json") << j.dump(2) << "\n";
    std::ofstream(dir / "sweep.svg") << sweep_svg(c.name, pts);
    fmt::print("wrote {}/sweep.csv, sweep.json, sweep.svg\n", dir.string());
  }
  return 0;
}

}  // namespace gib
