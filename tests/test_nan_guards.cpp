// NaN injection and NaN guards (docs/architecture.md "Determinism and numerical stability"), on lavapipe at small sizes:
// a NaN written into one resource on one frame (Settings::debug, options inject_*) must never
// reach an output while Settings::nan_guards is on (measured: 0 frames, 0 pixels, for every
// technique and target), and must persist with the guards off (so the injection is known to
// work); plus the radiance-cache multi_bounce switch against a closed furnace box.
// GIB_NAN_SIZE=WxH (e.g. 128x72) and GIB_NAN_FRAMES=n change the size and frame count of the
// injection runs, which print their per-frame NaN counts (how the numbers in the report of
// this change were measured); the bounds asserted hold at the defaults.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <nlohmann/json.hpp>

#include "renderer/graph/executor.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/techniques/technique.h"
#include "renderer/techniques/radiance_cache/include/radiance_cache_shared.h"
#include "tests/gpu_fixture.h"
#include "tests/technique_settings.h"

namespace gib {
namespace {

using test::GpuTest;

constexpr uint32_t kInjectFrame = 5;

struct Size {
  uint32_t w = 64, h = 36;
};
Size run_size() {
  Size s;
  if (const char* e = std::getenv("GIB_NAN_SIZE")) std::sscanf(e, "%ux%u", &s.w, &s.h);
  return s;
}
uint32_t run_frames(uint32_t fallback) {
  if (const char* e = std::getenv("GIB_NAN_FRAMES")) return uint32_t(std::atoi(e));
  return fallback;
}

std::string fmt_double(double v) {
  char b[32];
  std::snprintf(b, sizeof(b), " %.3f", v);
  return b;
}

size_t nan_pixels(const FloatImage& img) {
  size_t n = 0;
  for (size_t i = 0; i < img.pixel_count(); ++i) {
    bool bad = false;
    for (uint32_t c = 0; c < std::min(img.channels, 3u); ++c) bad |= !std::isfinite(img.pixels[i * img.channels + c]);
    n += bad;
  }
  return n;
}

// Per frame: non-finite pixels in each watched output image, and in each probed resource (the
// injection target, to show the NaN was written).
struct NanTrace {
  std::vector<std::string> images, probes;
  std::vector<std::vector<size_t>> counts;        // [frame][image]
  std::vector<std::vector<size_t>> probe_counts;  // [frame][probe]
  Settings settings;
  // Frames from the injection frame on that hold a non-finite pixel in any watched image
  // (last such frame - injection frame + 1; 0 when none ever did).
  uint32_t frames_with_nan() const {
    uint32_t last = 0;
    bool any = false;
    for (uint32_t f = 0; f < counts.size(); ++f)
      if (nan_on(f)) {
        last = f;
        any = true;
      }
    return any ? last - kInjectFrame + 1 : 0;
  }
  size_t max_area() const {
    size_t m = 0;
    for (auto& f : counts)
      for (size_t c : f) m = std::max(m, c);
    return m;
  }
  size_t area(uint32_t frame) const { return *std::max_element(counts[frame].begin(), counts[frame].end()); }
  bool nan_on(uint32_t frame) const { return area(frame) > 0; }
  bool nan_before_injection() const {
    for (uint32_t f = 0; f < kInjectFrame && f < counts.size(); ++f)
      if (nan_on(f)) return true;
    return false;
  }
};

Scene cornell() { return load_scene(std::string(GIB_SOURCE_DIR) + "/cases/scenes/cornell.json"); }

// Renders `frames` frames of `technique` (medium) on `scene` with a NaN injected into `target`
// on frame kInjectFrame near the image centre, counting non-finite pixels after every frame.
NanTrace run_injection(Gpu& gpu, const Scene& scene, const std::string& technique, uint32_t target, bool guards,
                       uint32_t frames, std::map<std::string, double> extra = {},
                       std::vector<std::string> probes = {}) {
  const Technique& t = find_technique(technique);
  Size size = run_size();
  Settings s;
  s.width = size.w;
  s.height = size.h;
  s = apply_preset(t, "medium", s);
  std::map<std::string, double> options = {
      {"nan_guards", guards ? 1 : 0}, {"inject_nan", target}, {"inject_frame", kInjectFrame}};
  options.insert(extra.begin(), extra.end());
  s = apply_options(t, s, options);
  // Near the centre, on the representative pixel of a gather pixel (g * divisor + divisor / 2),
  // so that the radiance-cache gather, denoise and upscale all read an injected normal.
  const uint32_t div = s.has_params<RadianceCacheSettings>() ? gather_divisor(rc(s)) : 2u;
  s.debug.inject_x = s.width / 2 / div * div + div / 2;
  s.debug.inject_y = s.height / 2 / div * div + div / 2;
  NanTrace trace;
  trace.settings = s;
  trace.images = {t.output};
  if (technique != "direct") trace.images.push_back("indirect_diffuse");
  trace.probes = probes;
  Executor ex(gpu, scene, s, make_passes(t), trace.images);
  const bool verbose = std::getenv("GIB_NAN_VERBOSE") != nullptr;
  for (uint32_t f = 0; f < frames; ++f) {
    ex.run_frame();
    std::vector<size_t> c, pc;
    for (auto& name : trace.images) c.push_back(nan_pixels(ex.read(name)));
    for (auto& name : trace.probes) pc.push_back(nan_pixels(ex.read(name)));
    trace.counts.push_back(c);
    trace.probe_counts.push_back(pc);
    if (verbose && f >= kInjectFrame && f <= kInjectFrame + 3) {
      std::string all;  // every image of the plan holding a NaN: where it went
      for (auto& name : ex.image_names())
        if (size_t n = nan_pixels(ex.read(name))) all += " " + name + "=" + std::to_string(n);
      std::printf("  frame %u:%s\n", f, all.c_str());
    }
  }
  std::string line, opts;
  for (auto& f : trace.counts) {
    line += " ";
    for (size_t i = 0; i < f.size(); ++i) line += (i ? "/" : "") + std::to_string(f[i]);
  }
  for (auto& [k, v] : extra) opts += " " + k + "=" + std::to_string(int(v));
  std::printf("%s target %u guards %d%s %ux%u: NaN pixels per frame (%s%s):%s -> frames with NaN %u, max area %zu\n",
              technique.c_str(), target, guards ? 1 : 0, opts.c_str(), size.w, size.h, trace.images[0].c_str(),
              trace.images.size() > 1 ? "/indirect_diffuse" : "", line.c_str(), trace.frames_with_nan(),
              trace.max_area());
  return trace;
}

class NanGuards : public GpuTest {};

TEST(NanOptions, SharedDebugOptionsAndTargets) {
  const Technique& direct = find_technique("direct");
  const Technique& ref = find_technique("reference");
  const Technique& rc = find_technique("radiance-cache");
  for (const Technique* t : {&direct, &ref, &rc})
    for (const char* name : {"nan_guards", "inject_nan", "inject_frame", "inject_x", "inject_y"})
      EXPECT_EQ(check_option(*t, name, 0), "") << t->name << " " << name;
  // Each technique takes only the targets its passes write.
  EXPECT_EQ(check_option(direct, "inject_nan", 1), "");
  EXPECT_EQ(check_option(rc, "inject_nan", 1), "");
  EXPECT_EQ(check_option(rc, "inject_nan", 2), "");
  EXPECT_EQ(check_option(ref, "inject_nan", 3), "");
  EXPECT_NE(check_option(direct, "inject_nan", 2).find("expected one of [0, 1] for direct, got 2"), std::string::npos)
      << check_option(direct, "inject_nan", 2);
  EXPECT_NE(check_option(ref, "inject_nan", 1), "");
  EXPECT_NE(check_option(rc, "inject_nan", 3), "");
  EXPECT_NE(check_option(rc, "nan_guards", 2), "");
  EXPECT_EQ(check_option(rc, "multi_bounce", 0), "");
  EXPECT_NE(check_option(ref, "multi_bounce", 0), "");

  Settings s = apply_options(rc, Settings{}, {{"nan_guards", 0}, {"multi_bounce", 0}, {"inject_nan", 2},
                                              {"inject_frame", 7}, {"inject_x", 3}, {"inject_y", 4}});
  EXPECT_FALSE(s.nan_guards);
  EXPECT_FALSE(s.params<RadianceCacheSettings>().multi_bounce);
  EXPECT_TRUE(s.debug.injects(2, 7));
  EXPECT_FALSE(s.debug.injects(2, 6));
  EXPECT_FALSE(s.debug.injects(1, 7));
  EXPECT_EQ(s.debug.inject_x, 3u);
  EXPECT_EQ(s.debug.inject_y, 4u);
  Settings d = defaults_of("radiance-cache");
  EXPECT_TRUE(d.nan_guards);
  EXPECT_TRUE(d.params<RadianceCacheSettings>().multi_bounce);
  EXPECT_EQ(d.debug.inject_nan, 0u);
}

// reference: the injected sample is dropped by the guard (the pixel's count is one short) and
// the image never holds a NaN; without the guard the running sums hold it for good.
TEST_F(NanGuards, ReferenceSampleIsDroppedWithGuardsAndPersistsWithout) {
  Scene scene = cornell();
  const uint32_t frames = kInjectFrame + 5;
  NanTrace on = run_injection(gpu(), scene, "reference", 3, true, frames);
  EXPECT_EQ(on.frames_with_nan(), 0u);
  {
    // The sample count shows the guard at work: one sample short at the injected pixel only.
    const Technique& t = find_technique("reference");
    Executor ex(gpu(), scene, on.settings, make_passes(t), {"radiance"});
    for (uint32_t f = 0; f <= kInjectFrame; ++f) ex.run_frame();
    FloatImage sum = ex.read("pt_radiance_sum");
    const float all = float((kInjectFrame + 1) * ref(on.settings).spp_per_frame);
    const uint32_t x = on.settings.debug.inject_x, y = on.settings.debug.inject_y;
    EXPECT_EQ(sum.at(x, y, 3), all - 1.0f);
    EXPECT_EQ(sum.at(x + 1, y, 3), all);
    EXPECT_EQ(nan_pixels(sum), 0u);
  }
  NanTrace off = run_injection(gpu(), scene, "reference", 3, false, frames);
  EXPECT_FALSE(off.nan_before_injection());
  for (uint32_t f = kInjectFrame; f < frames; ++f) EXPECT_EQ(off.area(f), 1u) << "frame " << f;
}

// direct: no history, so the NaN normal can only touch its own pixel on its own frame; the
// guard lights it as if it faced the camera.
TEST_F(NanGuards, DirectNormalStaysOnePixelOneFrame) {
  Scene scene = cornell();
  const uint32_t frames = kInjectFrame + 3;
  NanTrace on = run_injection(gpu(), scene, "direct", 1, true, frames, {}, {"gbuffer_normal"});
  EXPECT_EQ(on.probe_counts[kInjectFrame][0], 1u) << "the injection must write one NaN normal";
  EXPECT_EQ(on.probe_counts[kInjectFrame + 1][0], 0u);
  EXPECT_EQ(on.frames_with_nan(), 0u);
  NanTrace off = run_injection(gpu(), scene, "direct", 1, false, frames);
  EXPECT_EQ(off.frames_with_nan(), 1u);
  EXPECT_EQ(off.max_area(), 1u);
}

// radiance-cache, NaN G-buffer normal. With the guards the outputs never hold a NaN, whatever
// the history format. Without them, with a float history (RGBA32F here) the NaN goes
// gather -> denoise -> upscale -> history -> final_color -> screen cache -> gather, and spreads
// over the surfaces frame after frame; it is still there frames later.
TEST_F(NanGuards, RadianceCacheNormal) {
  Scene scene = cornell();
  const uint32_t frames = kInjectFrame + 4;
  // One cascade of 16-ray probes: the world half is not what is tested here, and costs most.
  const std::map<std::string, double> cheap = {{"cascades", 1}, {"rays_per_probe", 16}};
  for (double format : {0.0, 3.0}) {
    std::map<std::string, double> o = cheap;
    o["history_format"] = format;
    NanTrace on = run_injection(gpu(), scene, "radiance-cache", 1, true, frames, o, {"gbuffer_normal"});
    EXPECT_EQ(on.probe_counts[kInjectFrame][0], 1u) << "the injection must write one NaN normal";
    EXPECT_EQ(on.frames_with_nan(), 0u) << "history_format " << format;
  }
  std::map<std::string, double> o = cheap;
  o["history_format"] = 3;
  NanTrace off = run_injection(gpu(), scene, "radiance-cache", 1, false, frames, o);
  EXPECT_FALSE(off.nan_before_injection());
  EXPECT_TRUE(off.nan_on(frames - 1)) << "without guards the NaN must persist in a float history";
  EXPECT_GT(off.area(frames - 1), off.area(kInjectFrame)) << "and spread";
}

// radiance-cache, NaN shading result of the cache cell of the centre pixel's surface. RGB9E5
// cannot hold a NaN (it packs to 0), so the outputs never see one, guards or not: with the
// guard the cell is left unshaded (readers miss it and fall back to the volumes; the next probe
// hit re-queues it), without it the cell holds 0 (black) for cache_reuse_frames frames.
TEST_F(NanGuards, RadianceCacheCell) {
  Scene scene = cornell();
  const Technique& t = find_technique("radiance-cache");
  auto cells_after_injection = [&](double target, bool guards, NanTrace* trace) {
    Settings s;
    s.width = run_size().w;
    s.height = run_size().h;
    s = apply_options(t, apply_preset(t, "medium", s),
                      {{"nan_guards", guards}, {"inject_nan", target}, {"inject_frame", kInjectFrame},
                       {"inject_x", s.width / 2 + 1}, {"inject_y", s.height / 2 + 1}, {"cascades", 1},
                       {"rays_per_probe", 16}});
    Executor ex(gpu(), scene, s, make_passes(t), {t.output, "indirect_diffuse"});
    for (uint32_t f = 0; f <= kInjectFrame; ++f) {
      ex.run_frame();
      if (trace) trace->counts.push_back({nan_pixels(ex.read(t.output)), nan_pixels(ex.read("indirect_diffuse"))});
    }
    std::vector<uint8_t> bytes = ex.read_buffer("rc_cells");
    std::vector<glsl::RcCell> cells(bytes.size() / sizeof(glsl::RcCell));
    std::memcpy(cells.data(), bytes.data(), cells.size() * sizeof(glsl::RcCell));
    return cells;
  };
  auto unshaded = [](const std::vector<glsl::RcCell>& cells) {
    return std::count_if(cells.begin(), cells.end(), [](auto& c) { return c.key != 0 && c.shaded_frame == 0; });
  };
  NanTrace on, off;
  auto clean = cells_after_injection(0, true, nullptr);
  auto guarded = cells_after_injection(2, true, &on);
  auto unguarded = cells_after_injection(2, false, &off);
  ASSERT_EQ(clean.size(), guarded.size());
  size_t used = std::count_if(clean.begin(), clean.end(), [](auto& c) { return c.key != 0; });
  size_t differ_on = 0, differ_off = 0, zeroed = 0;
  for (size_t i = 0; i < clean.size(); ++i) {
    differ_on += std::memcmp(&clean[i], &guarded[i], sizeof(glsl::RcCell)) != 0;
    differ_off += std::memcmp(&clean[i], &unguarded[i], sizeof(glsl::RcCell)) != 0;
    zeroed += clean[i].radiance != 0 && unguarded[i].radiance == 0 && unguarded[i].shaded_frame == kInjectFrame + 1;
  }
  std::printf("cells used %zu; unshaded: clean %zd, guarded %zd, unguarded %zd; differing from clean: guarded %zu, "
              "unguarded %zu (zeroed %zu)\n",
              used, unshaded(clean), unshaded(guarded), unshaded(unguarded), differ_on, differ_off, zeroed);
  EXPECT_GT(used, 0u);
  EXPECT_EQ(unshaded(clean), 0);
  EXPECT_EQ(unshaded(guarded), 1) << "the guard must leave exactly the injected cell unshaded";
  EXPECT_EQ(unshaded(unguarded), 0);
  // (Other cells may differ too: those that bounce into the injected one this frame.)
  EXPECT_GE(zeroed, 1u) << "without the guard the NaN packs to 0 in the injected cell";
  for (uint32_t f = 0; f <= kInjectFrame; ++f) {
    EXPECT_FALSE(on.nan_on(f));
    EXPECT_FALSE(off.nan_on(f));
  }
}

// A closed box, albedo 0.99 and emission 1 on every face, seen from inside: the converged
// radiance is E / (1 - rho) = 100. Single bounce (multi_bounce 0) stays near
// E + rho (E + rho E) = 2.97 (cells: emission plus one bounce; a gather ray answered by the
// volumes adds at most one more); with multi-bounce the caches feed back and it keeps rising.
Scene furnace_box() {
  return parse_scene(nlohmann::json::parse(R"({
    "materials": {"wall": {"albedo": [0.99, 0.99, 0.99], "emissive": [1, 1, 1]}},
    "objects": [{"primitive": {"type": "box", "size": [4, 4, 4]}, "material": "wall"}],
    "camera": {"position": [0, 0, 0.5], "target": [0.3, -0.2, -1], "fov_y_deg": 70, "near": 0.05, "far": 100}
  })"),
                     "inline");
}

double mean_rgb(const FloatImage& img) {
  double s = 0;
  for (size_t i = 0; i < img.pixel_count(); ++i)
    for (uint32_t c = 0; c < 3; ++c) s += img.pixels[i * img.channels + c];
  return s / (3.0 * img.pixel_count());
}

TEST_F(NanGuards, MultiBounceSwitchInClosedFurnaceBox) {
  Scene scene = furnace_box();
  const Technique& t = find_technique("radiance-cache");
  const uint32_t frames = run_frames(16);
  auto means = [&](bool multi) {
    Settings s;
    s.width = 32;
    s.height = 18;
    s = apply_options(t, apply_preset(t, "medium", s),
                      {{"multi_bounce", multi ? 1 : 0}, {"cascades", 1}, {"rays_per_probe", 16}});
    Executor ex(gpu(), scene, s, make_passes(t), {t.output});
    std::vector<double> m;
    for (uint32_t f = 0; f < frames; ++f) {
      ex.run_frame();
      m.push_back(mean_rgb(ex.read(t.output)));
    }
    std::string line;
    for (double v : m) line += fmt_double(v);
    std::printf("furnace box multi_bounce %d: mean radiance per frame:%s\n", multi ? 1 : 0, line.c_str());
    return m;
  };
  std::vector<double> single = means(false), multi = means(true);
  const double one_bounce = 1.0 + 0.99 + 0.99 * 0.99;  // E + rho (E + rho E), E = 1
  EXPECT_NEAR(single.back(), one_bounce, 0.03 * one_bounce) << "single bounce converges to E (1 + rho + rho^2)";
  EXPECT_NEAR(single.back(), single[single.size() / 2], 0.01) << "and stays there";
  EXPECT_GT(multi.back(), 1.4 * single.back()) << "multi-bounce must climb towards E / (1 - rho) = 100";
  EXPECT_GT(multi.back(), multi[multi.size() / 2] + 0.2) << "and still be climbing";
}

// The measurement behind the numbers in the change's report: every technique and target, guards
// on and off, with per-frame counts printed. Skipped unless GIB_NAN_MEASURE is set; e.g.
//   GIB_NAN_MEASURE=1 GIB_NAN_SIZE=128x72 GIB_NAN_FRAMES=20 gib_tests --gtest_filter=NanGuards.Measure
TEST_F(NanGuards, Measure) {
  if (!std::getenv("GIB_NAN_MEASURE")) GTEST_SKIP() << "set GIB_NAN_MEASURE=1 to measure";
  Scene scene = cornell();
  const uint32_t frames = run_frames(20);
  for (bool guards : {true, false}) {
    run_injection(gpu(), scene, "direct", 1, guards, frames);
    run_injection(gpu(), scene, "reference", 3, guards, frames);
    for (double format : {0.0, 1.0, 2.0, 3.0}) {
      run_injection(gpu(), scene, "radiance-cache", 1, guards, frames, {{"history_format", format}});
      run_injection(gpu(), scene, "radiance-cache", 2, guards, frames, {{"history_format", format}});
    }
  }
}

}  // namespace
}  // namespace gib
