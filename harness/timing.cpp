#include "harness/timing.h"

#include "harness/tier.h"

#include <fmt/format.h>

#include <cmath>
#include <fstream>

#include "harness/case_render.h"
#include "renderer/techniques/technique.h"

namespace gib {

std::vector<double> TimingPath::frame_ms() const {
  std::vector<double> v;
  for (auto& r : repeats)
    for (double ms : r.frame_ms()) v.push_back(ms);
  return v;
}

std::vector<double> TimingPath::repeat_medians() const {
  std::vector<double> v;
  for (auto& r : repeats) v.push_back(r.frame().median);
  return v;
}

std::vector<std::pair<std::string, perf::Summary>> TimingPath::passes() const {
  std::vector<std::pair<std::string, perf::Summary>> out;
  if (repeats.empty() || repeats.front().frames.empty()) return out;
  for (auto& p : repeats.front().frames.front().passes) {
    std::vector<double> ms;
    for (auto& r : repeats)
      for (auto& f : r.frames)
        for (auto& q : f.passes)
          if (q.name == p.name) ms.push_back(q.ms);
    out.emplace_back(p.name, perf::summarize_samples(std::move(ms)));
  }
  return out;
}

uint32_t TimingPath::scan_dispatches() const {
  uint32_t n = 0;
  for (auto& r : repeats) n += r.scan_dispatches;
  return n;
}

std::string timed_work(const Plan& plan) {
  std::string s;
  for (auto* p : plan.running()) {
    s += fmt::format("pass {} writes {} B", p->name, p->bytes_written);
    for (auto& w : p->work) s += fmt::format(", {} {}", w.name, w.per_frame);
    s += "\n";
  }
  for (auto& r : plan.resources) s += fmt::format("resource {} {}x{} {} B\n", r.name, r.width, r.height, r.bytes);
  return s;
}

std::vector<TimingPath> measure_timing(Gpu& gpu, const Case& c, const TechniqueRun& run, const std::string& preset,
                                       uint32_t repeats, int bench_warmup) {
  if (c.timing_frames == 0)
    throw CaseError(fmt::format("{}: timing needs timing_frames > 0 (the case times its own frames)", c.file));
  const Technique& t = find_technique(run.technique);
  std::vector<TimingPath> paths{{"run"}, {"sweep"}, {"bench"}};
  const uint32_t warmup = bench_warmup >= 0 ? uint32_t(bench_warmup) : c.frames;
  for (uint32_t rep = 0; rep < std::max(1u, repeats); ++rep) {
    CaseRender a = render_case(gpu, c, run, preset, 0, 0, /*scan=*/true);  // gibench run
    paths[0].scanned_dispatches += uint64_t(a.stability.frames) * a.stability.dispatches_per_frame;
    paths[0].plan = a.plan;
    paths[0].repeats.push_back(std::move(a.timing));
    CaseRender b = render_case(gpu, c, run, preset);  // gibench sweep
    paths[1].plan = b.plan;
    paths[1].repeats.push_back(std::move(b.timing));
    // gibench bench: a fresh executor, warm-up and timed frames by the same function it calls.
    Executor ex(gpu, c.scene, a.settings, make_passes(t), a.outputs);
    paths[2].plan = ex.plan();
    paths[2].repeats.push_back(perf::time_frames(ex, warmup, c.timing_frames));
  }
  return paths;
}

namespace {

std::string ms3(double v) { return fmt::format("{:.4g}", v); }

}  // namespace

int cmd_timing(const TimingOptions& o) {
  std::vector<Case> cases = select_cases(o.suite);
  if (cases.size() != 1)
    throw CaseError(fmt::format("timing: expected --case naming exactly one case, got {}", cases.size()));
  Case c = cases.front();
  if (o.frames) c.timing_frames = o.frames;
  const TechniqueRun* run = &c.techniques.front();
  if (!o.technique.empty()) {
    run = nullptr;
    for (auto& r : c.techniques)
      if (r.technique == o.technique) run = &r;
    if (!run) throw CaseError(fmt::format("timing: case {} has no run of technique '{}'", c.name, o.technique));
  }
  const std::string preset = o.preset.empty() ? run->presets.front() : o.preset;
  auto gpu = Gpu::create({o.suite.device, o.suite.validate});
  const DeviceInfo& dev = gpu->info();
  const Tier tier = resolve_tier(o.suite.tier, device_class(dev.driver_name, dev.name));
  c = at_tier(c, tier);
  fmt::print("tier {}: {}x{}\n", tier_name(tier), c.width, c.height);
  fmt::print("device: {} ({} {})\n", dev.name, dev.driver_name, dev.driver_info);
  fmt::print("case {} {} {} at {}x{}: {} case frames, then {} timed frames; {} repeats (run, sweep, bench "
             "interleaved)\n",
             c.name, run->technique, preset, c.width, c.height, c.frames, c.timing_frames, o.repeats);
  std::fflush(stdout);
  std::vector<TimingPath> paths = measure_timing(*gpu, c, *run, preset, o.repeats, o.bench_warmup);

  fmt::print("\n{:<6} {:>6} {:>8} {:>11} {:>21} {:>21}  {}\n", "path", "frames", "after", "median ms", "IQR [q1, q3]",
             "[min, max]", "per-repeat medians");
  for (auto& p : paths) {
    perf::Summary s = perf::summarize_samples(p.frame_ms());
    std::string reps;
    for (double m : p.repeat_medians()) reps += (reps.empty() ? "" : " ") + ms3(m);
    fmt::print("{:<6} {:>6} {:>8} {:>11} {:>21} {:>21}  {}  ({})\n", p.name, s.n,
               p.repeats.front().warmup, ms3(s.median), fmt::format("[{}, {}]", ms3(s.q1), ms3(s.q3)),
               fmt::format("[{}, {}]", ms3(s.min), ms3(s.max)), reps, p.repeats.front().source);
  }
  auto med = [&](size_t i) { return perf::median_of(paths[i].frame_ms()); };
  fmt::print("ratios of medians: run/sweep {:.3f}, run/bench {:.3f}, sweep/bench {:.3f}\n", med(0) / med(1),
             med(0) / med(2), med(1) / med(2));
  if (paths[0].repeats.front().clock.measured()) {
    fmt::print("GPU clock: a fixed probe around the timed frames / its fastest on this device (1 = peak clock), per "
               "repeat:\n");
    for (auto& p : paths) {
      std::string r;
      for (auto& t : p.repeats) r += fmt::format(" {:.3f}", t.clock.ratio());
      fmt::print("  {:<6}{}\n", p.name, r);
    }
  }

  fmt::print("\n{:<26} {:>10} {:>10} {:>10} {:>9} {:>9}\n", "pass (median ms)", "run", "sweep", "bench", "run/sweep",
             "run/bench");
  auto pr = paths[0].passes(), ps = paths[1].passes(), pb = paths[2].passes();
  for (size_t i = 0; i < pr.size() && i < ps.size() && i < pb.size(); ++i)
    fmt::print("{:<26} {:>10} {:>10} {:>10} {:>9.3f} {:>9.3f}\n", pr[i].first, ms3(pr[i].second.median),
               ms3(ps[i].second.median), ms3(pb[i].second.median), pr[i].second.median / ps[i].second.median,
               pr[i].second.median / pb[i].second.median);

  int rc = 0;
  const std::string work = timed_work(paths[0].plan);
  for (auto& p : paths) {
    if (timed_work(p.plan) != work) {
      fmt::print("timed work DIFFERS: {} vs run:\n{}\n--- run:\n{}", p.name, timed_work(p.plan), work);
      rc = 1;
    }
    if (p.scan_dispatches()) {
      fmt::print("{}: {} stability-scan dispatches in timed frames (expected none)\n", p.name, p.scan_dispatches());
      rc = 1;
    }
  }
  if (!rc)
    fmt::print("\ntimed work identical in all three ({} running passes, same work counters and resource sizes); "
               "0 scan dispatches in timed frames (run's case frames had {})\n",
               paths[0].plan.running().size(), paths[0].scanned_dispatches);

  if (!o.json.empty()) {
    nlohmann::json j{{"case", c.name}, {"technique", run->technique}, {"preset", preset},
                     {"size", {c.width, c.height}}, {"device", {{"name", dev.name}, {"driver", dev.driver_name},
                                                                {"driver_info", dev.driver_info}}}};
    for (auto& p : paths) {
      nlohmann::json jp{{"name", p.name}, {"scanned_dispatches_before_timing", p.scanned_dispatches}};
      for (auto& r : p.repeats) {
        nlohmann::json passes = nlohmann::json::object();
        for (auto& f : r.frames)
          for (auto& q : f.passes) passes[q.name].push_back(q.ms);
        jp["repeats"].push_back({{"source", r.source}, {"warmup", r.warmup}, {"scan_dispatches", r.scan_dispatches},
                                 {"frame_ms", r.frame_ms()}, {"pass_ms", passes}});
        if (r.clock.measured()) jp["repeats"].back()["clock"] = r.clock.to_json();
      }
      j["paths"].push_back(jp);
    }
    j["ratios"] = {{"run_over_sweep", med(0) / med(1)}, {"run_over_bench", med(0) / med(2)},
                   {"sweep_over_bench", med(1) / med(2)}};
    std::ofstream(o.json) << j.dump(2) << "\n";
    fmt::print("wrote {}\n", o.json);
  }
  return rc;
}

}  // namespace gib
