// The numerical-stability scan: value domains in the graph, the CPU classification, the GPU
// scan against it on every scanned format (lavapipe), and the executor's first-offender report.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>

#include "renderer/codecs/half.h"
#include "renderer/codecs/r11g11b10.h"
#include "renderer/codecs/rgb9e5.h"
#include "renderer/graph/executor.h"
#include "renderer/graph/stability.h"
#include "renderer/scene/scene_loader.h"
#include "renderer/techniques/technique.h"
#include "tests/gpu_fixture.h"
#include "tests/stability_test_shared.h"

namespace gib {
namespace {

using test::GpuTest;
constexpr float kInf = std::numeric_limits<float>::infinity();
const float kNan = std::bit_cast<float>(0x7fc00001u);
constexpr uint32_t kNan_ = uint32_t(StabilityCategory::nan), kPosInf = uint32_t(StabilityCategory::pos_inf),
                   kNegInf = uint32_t(StabilityCategory::neg_inf), kNeg = uint32_t(StabilityCategory::negative),
                   kAbove = uint32_t(StabilityCategory::above_max), kSat = uint32_t(StabilityCategory::saturated);

std::string scene_path(const char* name) { return std::string(GIB_SOURCE_DIR) + "/cases/scenes/" + name; }

uint32_t classify(std::initializer_list<float> v, const ValueDomain& d) {
  std::vector<float> values(v);
  return stability_classify(values.data(), uint32_t(values.size()), d);
}

// ---------------------------------------------------------------- CPU classification
TEST(StabilityCpu, ClassifiesByCategoryDomainAndChannel) {
  const ValueDomain nn = non_negative_values();
  EXPECT_EQ(classify({0.0f, 1.0f, 1e30f}, nn), 0u);
  EXPECT_EQ(classify({kNan}, nn), 1u << kNan_);
  EXPECT_EQ(classify({-kNan}, finite_values()), 1u << kNan_);
  EXPECT_EQ(classify({kInf}, nn), 1u << kPosInf);
  EXPECT_EQ(classify({-kInf}, nn), 1u << kNegInf);
  EXPECT_EQ(classify({-1e-3f}, nn), 1u << kNeg);
  EXPECT_EQ(classify({-0.0f}, nn), 0u) << "-0 is not negative";
  EXPECT_EQ(classify({-1e-40f}, nn), 1u << kNeg) << "a negative denormal is negative";
  EXPECT_EQ(classify({-5.0f}, finite_values()), 0u);
  EXPECT_EQ(classify({-kInf}, finite_values()), 1u << kNegInf);
  // Bound: v > max for ordinary channels, |v| > max for signed ones.
  const ValueDomain b = nn.bounded(2.0f).allow_negative(kChannelG);
  EXPECT_EQ(classify({2.0f, 0.0f}, b), 0u);
  EXPECT_EQ(classify({2.5f, 0.0f}, b), 1u << kAbove);
  EXPECT_EQ(classify({0.0f, -1.5f}, b), 0u) << "signed channel may be negative";
  EXPECT_EQ(classify({0.0f, -2.5f}, b), 1u << kAbove) << "signed channel: |v| against the bound";
  EXPECT_EQ(classify({-2.5f, 0.0f}, b), 1u << kNeg);
  // Unit: the bound is 1 (or lower); several categories in one element.
  const ValueDomain u = effective_domain(Format::rgba16_float, unit_values());
  EXPECT_EQ(u.max_value, 1.0f);
  EXPECT_EQ(classify({1.0f, 0.5f, 0.0f, 0.25f}, u), 0u);
  EXPECT_EQ(classify({1.01f, -0.5f, kNan, 0.0f}, u), (1u << kAbove) | (1u << kNeg) | (1u << kNan_));
  // Unchecked channels are ignored; a format's missing channels are never checked.
  EXPECT_EQ(classify({1.0f, kNan}, nn.only(kChannelR)), 0u);
  EXPECT_EQ(effective_domain(Format::r32_float, nn).channels, kChannelR);
  EXPECT_EQ(effective_domain(Format::b10g11r11_float, nn).channels, kChannelsRgb);
  EXPECT_EQ(effective_domain(Format::r32_uint, nn.encoded(Encoding::rgb9e5)).channels, kChannelsRgb);
  EXPECT_EQ(effective_domain(Format::buffer, nn.encoded(Encoding::rgb9e5).layout(4, 1, 2)).channels, 0x3fu);
  float m = 0;
  std::vector<float> v{3.0f, -7.0f, kInf, kNan};
  stability_classify(v.data(), 4, finite_values(), &m);
  EXPECT_EQ(m, 7.0f) << "max |finite value|";
}

TEST(StabilityCpu, DecodesRgb9e5BeforeChecking) {
  // r32_uint RGB9E5 texels: (1, 2, 3) is within a bound of 4, (5, 0, 0) above it.
  std::vector<uint32_t> words{codecs::encode_rgb9e5(1, 2, 3), codecs::encode_rgb9e5(5, 0, 0),
                              codecs::encode_rgb9e5(0.5f, 0.5f, 0.5f), codecs::encode_rgb9e5(0, 0, 9)};
  std::vector<uint8_t> raw(words.size() * 4);
  std::memcpy(raw.data(), words.data(), raw.size());
  StabilityCounts c =
      stability_scan_texels(Format::r32_uint, 2, 2, raw, non_negative_values().bounded(4).encoded(Encoding::rgb9e5));
  EXPECT_EQ(c.count[kAbove], 2u);
  EXPECT_EQ(c.first[kAbove], 1u);
  EXPECT_EQ(c.max_abs, 9.0f);
  // Read as raw float bits instead (no encoding), the shared exponent lands in the sign and
  // exponent bits: different verdicts, so the decode matters.
  StabilityCounts raw_bits = stability_scan_texels(Format::r32_uint, 2, 2, raw, non_negative_values().bounded(4));
  EXPECT_GT(raw_bits.count[kNeg], 0u);
  EXPECT_NE(raw_bits.count, c.count);
}

// ---------------------------------------------------------------- graph: domains are metadata
ResourceDesc image(Format f) { return {f, SizeRule::render}; }

TEST(StabilityGraph, DomainIsMetadataDeclaredOnceOrConsistently) {
  const ResourceDesc a = image(Format::rgba16_float).with(non_negative_values());
  EXPECT_TRUE(same_desc(a, image(Format::rgba16_float)));
  EXPECT_EQ(describe(non_negative_values().only(kChannelsRgb).bounded(16).encoded(Encoding::rgb9e5)),
            "non_negative rgb <= 16 rgb9e5");
  EXPECT_EQ(describe(ValueDomain{}), "");
  // The writer declares no domain, a read_write slot with an otherwise unspecified desc does.
  std::vector<PassDecl> decls{
      {"writer", PassKind::compute, {}, {}, {{"x", Access::write, image(Format::rgba16_float)}}, false},
      {"modifier", PassKind::compute, {}, {}, {{"x", Access::read_write, ResourceDesc{}.with(unit_values())}}, false}};
  Plan plan = compile(decls, {{}, {"x"}});
  ASSERT_NE(plan.find("x"), nullptr);
  EXPECT_EQ(plan.find("x")->desc.format, Format::rgba16_float);
  EXPECT_EQ(plan.find("x")->desc.values, unit_values());
  // Two different declared domains are an error naming both passes.
  decls[0].slots[0].desc = image(Format::rgba16_float).with(non_negative_values());
  try {
    compile(decls, {{}, {"x"}});
    FAIL() << "expected GraphError";
  } catch (const GraphError& e) {
    EXPECT_NE(std::string(e.what()).find("pass 'modifier' declares the values of 'x' as 'unit' but pass 'writer' "
                                         "declares 'non_negative'"),
              std::string::npos)
        << e.what();
  }
  decls[1].slots[0].desc = ResourceDesc{}.with(non_negative_values());
  EXPECT_NO_THROW(compile(decls, {{}, {"x"}}));
}

// ---------------------------------------------------------------- GPU scan vs CPU, every format
// Known texels copied into the graph's resources by a transfer pass (buffers uploaded).
struct FillSource {
  std::string name;
  ResourceDesc desc;
  std::shared_ptr<Image> image;
  std::vector<uint8_t> bytes;
};

class FillPass final : public Pass {
 public:
  explicit FillPass(const std::vector<FillSource>& s) : sources_(s) {}
  PassDecl declare(const Scene&, const Settings&) const override {
    PassDecl d;
    d.name = "stability_fill";
    d.kind = PassKind::transfer;
    d.side_effect = true;
    for (auto& s : sources_) d.slots.push_back({s.name, Access::write, s.desc});
    return d;
  }
  void record(RecordContext& ctx) override {
    for (auto& s : sources_) {
      if (s.image)
        ctx.cmd.copy(*s.image, ctx.image(s.name));
      else
        ctx.gpu.upload(ctx.buffer(s.name), s.bytes.data(), s.bytes.size());
    }
  }

 private:
  const std::vector<FillSource>& sources_;
};

// One format under test: texels as floats (4 per texel), then encoded to the format's bytes.
struct FormatCase {
  const char* name;
  Format format;
  ValueDomain values;
  std::vector<uint32_t> categories;  // injectable in this format
  float base_max;                    // valid values lie in [0, base_max) (or +-, finite domains)
};

std::vector<uint8_t> encode(Format f, const std::vector<float>& t /* 4 per texel */) {
  const size_t n = t.size() / 4;
  std::vector<uint8_t> raw(n * format_bytes_per_texel(f));
  auto put32 = [&](size_t i, uint32_t w) { std::memcpy(raw.data() + 4 * i, &w, 4); };
  auto put16 = [&](size_t i, uint16_t h) { std::memcpy(raw.data() + 2 * i, &h, 2); };
  for (size_t i = 0; i < n; ++i) {
    const float* p = &t[4 * i];
    switch (f) {
      case Format::rgba32_float: for (int c = 0; c < 4; ++c) put32(4 * i + c, std::bit_cast<uint32_t>(p[c])); break;
      case Format::r32_float: case Format::d32_float: put32(i, std::bit_cast<uint32_t>(p[0])); break;
      case Format::rgba16_float: for (int c = 0; c < 4; ++c) put16(4 * i + c, codecs::float_to_half(p[c])); break;
      case Format::rg16_float: for (int c = 0; c < 2; ++c) put16(2 * i + c, codecs::float_to_half(p[c])); break;
      case Format::b10g11r11_float: put32(i, codecs::encode_r11g11b10(p)); break;
      case Format::e5b9g9r9_float: case Format::r32_uint: put32(i, codecs::encode_rgb9e5(p)); break;
      case Format::rgba8_unorm:
        for (int c = 0; c < 4; ++c) raw[4 * i + c] = uint8_t(std::lround(std::clamp(p[c], 0.0f, 1.0f) * 255));
        break;
      default: ADD_FAILURE() << "no encoder for " << format_name(f);
    }
  }
  return raw;
}

float offender(uint32_t category, float bound) {
  switch (category) {
    case kNan_: return kNan;
    case kPosInf: return kInf;
    case kNegInf: return -kInf;
    case kNeg: return -0.375f;
    default: return bound * 4.0f + 3.0f;
  }
}

class StabilityScan : public GpuTest {
 protected:
  // One frame of a FillPass writing `sources` (every one requested as an output) with the
  // stability scan on; the executor stays alive for the test's checks.
  Executor& scan_fill(const std::vector<FillSource>& sources) {
    std::vector<std::unique_ptr<Pass>> passes;
    passes.push_back(std::make_unique<FillPass>(sources));
    std::vector<std::string> outputs;
    for (auto& src : sources) outputs.push_back(src.name);
    Settings settings;
    settings.width = 16;
    settings.height = 8;
    fill_ex_ = std::make_unique<Executor>(gpu(), fill_scene_, settings, std::move(passes), outputs);
    fill_ex_->enable_stability_scan();
    fill_frame_ = fill_ex_->run_frame();
    return *fill_ex_;
  }
  Scene fill_scene_ = load_scene(scene_path("sky_plane.json"));
  std::unique_ptr<Executor> fill_ex_;
  FrameResult fill_frame_;
};

TEST_F(StabilityScan, GpuCountsAndFirstTexelsEqualTheCpuOnEveryFormat) {
  constexpr uint32_t kW = 13, kH = 7, kN = kW * kH;
  const std::vector<FormatCase> cases{
      {"s_rgba32f", Format::rgba32_float, non_negative_values().bounded(1.5f).allow_negative(kChannelA),
       {kNan_, kPosInf, kNegInf, kNeg, kAbove}, 1.0f},
      {"s_rgba16f", Format::rgba16_float, unit_values(), {kNan_, kPosInf, kNegInf, kNeg, kAbove, kSat}, 0.9f},
      {"s_rg16f", Format::rg16_float, finite_values().bounded(4.0f), {kNan_, kPosInf, kNegInf, kAbove, kSat}, 2.0f},
      {"s_r32f", Format::r32_float, non_negative_values().bounded(100.0f), {kNan_, kPosInf, kNegInf, kNeg, kAbove}, 50.0f},
      {"s_b10g11r11", Format::b10g11r11_float, non_negative_values().bounded(10.0f), {kNan_, kPosInf, kAbove, kSat}, 5.0f},
      {"s_e5b9g9r9", Format::e5b9g9r9_float, non_negative_values().bounded(8.0f), {kAbove, kSat}, 4.0f},
      {"s_rgb9e5_uint", Format::r32_uint, non_negative_values().bounded(8.0f).encoded(Encoding::rgb9e5), {kAbove, kSat}, 4.0f},
      {"s_depth", Format::d32_float, unit_values(), {}, 1.0f},
      {"s_rgba8", Format::rgba8_unorm, unit_values().bounded(0.5f), {kAbove}, 0.45f},
  };
  std::vector<FillSource> sources;
  std::map<std::string, std::array<uint64_t, kStabilityCategoryCount>> injected;
  std::map<std::string, std::array<uint64_t, kStabilityCategoryCount>> injected_first;
  uint32_t rng = 12345;
  auto next = [&] {
    rng = rng * 1664525u + 1013904223u;
    return float(rng >> 8) / float(1u << 24);
  };
  for (const FormatCase& fc : cases) {
    std::vector<float> t(4 * kN);
    const bool finite = fc.values.domain == Domain::finite;
    for (float& v : t) v = finite ? (next() * 2 - 1) * fc.base_max : next() * fc.base_max;
    if (fc.format == Format::rgba8_unorm)  // exact in 8 bits, below the bound after rounding
      for (float& v : t) v = std::floor(v * 255) / 255;
    auto& inj = injected[fc.name];
    auto& first = injected_first[fc.name];
    inj.fill(0);
    const ValueDomain eff = effective_domain(fc.format, fc.values);
    for (uint32_t c : fc.categories) {
      // Two offending texels per category, in channel c % 3 (all formats have r, g, b but
      // r32f / d32f / rg16f: channel 0).
      const uint32_t ch = (fc.format == Format::r32_float || fc.format == Format::rg16_float) ? 0 : c % 3;
      for (uint32_t texel : {3 + 7 * c, (50 + 9 * c) % kN}) {
        if (c == kSat) {
          // The format's largest finite value in channel ch (2 for R11G11B10F: its B's 64512);
          // it is above every bound here too.
          t[4 * texel + ch] = ch == 2 ? eff.format_max_b : eff.format_max;
          ++inj[kAbove];
        } else {
          t[4 * texel + ch] = offender(c, eff.max_value);
        }
        ++inj[c];
      }
      first[c] = std::min(3 + 7 * c, (50 + 9 * c) % kN);
    }
    if (inj[kSat]) first[kAbove] = std::min(first[kAbove], first[kSat]);
    if (fc.format == Format::rgba32_float) {
      t[4 * 40 + 3] = -1.25f;  // signed alpha: allowed
      t[4 * 41 + 3] = -2.0f;   // signed alpha beyond the bound: |v| > 1.5
      ++inj[kAbove];
    }
    FillSource s;
    s.name = fc.name;
    s.desc = ResourceDesc{fc.format, SizeRule::fixed, kW, kH}.with(fc.values);
    s.bytes = encode(fc.format, t);
    s.image = gpu().create_image(fc.format, kW, kH, std::string("stability_test.") + fc.name);
    gpu().upload(*s.image, s.bytes.data(), s.bytes.size());
    sources.push_back(std::move(s));
  }
  // Buffers: 40 elements of 5 words, values in words 1..3 (words 0 and 4 hold NaN bits that the
  // layout excludes); and RcCell-like 4-word elements with RGB9E5 in word 1.
  constexpr uint32_t kElements = 40;
  {
    std::vector<uint32_t> w(kElements * 5, 0x7fc00000u);
    for (uint32_t e = 0; e < kElements; ++e)
      for (uint32_t k = 1; k <= 3; ++k) w[e * 5 + k] = std::bit_cast<uint32_t>(next() * 20);
    auto& inj = injected["s_buffer_float"];
    inj.fill(0);
    for (uint32_t c : {kNan_, kPosInf, kNegInf, kNeg, kAbove}) {
      for (uint32_t e : {2 + 3 * c, 21 + 4 * c}) {
        w[e * 5 + 1 + c % 3] = std::bit_cast<uint32_t>(offender(c, 50.0f));
        ++inj[c];
      }
      injected_first["s_buffer_float"][c] = 2 + 3 * c;
    }
    FillSource s;
    s.name = "s_buffer_float";
    s.desc = ResourceDesc{Format::buffer, SizeRule::buffer, 0, 0, w.size() * 4}.with(
        non_negative_values().bounded(50.0f).layout(5, 1, 3));
    s.bytes.resize(w.size() * 4);
    std::memcpy(s.bytes.data(), w.data(), s.bytes.size());
    sources.push_back(std::move(s));
  }
  {
    std::vector<uint32_t> w(kElements * 4, 0xffffffffu);
    for (uint32_t e = 0; e < kElements; ++e) w[e * 4 + 1] = codecs::encode_rgb9e5(next(), next(), next());
    auto& inj = injected["s_buffer_rgb9e5"];
    inj.fill(0);
    for (uint32_t e : {7u, 33u}) {
      w[e * 4 + 1] = codecs::encode_rgb9e5(0.5f, 3.0f, 0.5f);
      ++inj[kAbove];
    }
    injected_first["s_buffer_rgb9e5"][kAbove] = 7;
    w[12 * 4 + 1] = codecs::encode_rgb9e5(0.0f, 0.0f, codecs::kRgb9e5Max);  // saturated (and above 2)
    ++inj[kAbove];
    ++inj[kSat];
    injected_first["s_buffer_rgb9e5"][kSat] = 12;
    FillSource s;
    s.name = "s_buffer_rgb9e5";
    s.desc = ResourceDesc{Format::buffer, SizeRule::buffer, 0, 0, w.size() * 4}.with(
        non_negative_values().bounded(2.0f).encoded(Encoding::rgb9e5).layout(4, 1, 1));
    s.bytes.resize(w.size() * 4);
    std::memcpy(s.bytes.data(), w.data(), s.bytes.size());
    sources.push_back(std::move(s));
  }

  Executor& ex = scan_fill(sources);
  const FrameResult& fr = fill_frame_;
  const StabilityReport& rep = ex.stability();
  EXPECT_EQ(rep.frames, 1u);
  EXPECT_EQ(rep.dispatches_per_frame, sources.size());
  EXPECT_EQ(fr.scan_dispatches, sources.size());
  ASSERT_EQ(rep.targets.size(), sources.size());

  for (size_t i = 0; i < sources.size(); ++i) {
    const FillSource& s = sources[i];
    SCOPED_TRACE(s.name);
    const bool buffer = !s.image;
    // The CPU mirror on the exact bytes the GPU scanned (read back, not the source bytes, so a
    // copy or upload that changed bits cannot hide a scan difference).
    StabilityCounts cpu;
    uint32_t width = 0;
    if (buffer) {
      cpu = stability_scan_buffer(ex.read_buffer(s.name), s.desc.values);
    } else {
      std::vector<uint8_t> raw = gpu().download(*s.image);
      EXPECT_EQ(raw, s.bytes) << "upload changed the texels";
      cpu = stability_scan_texels(s.desc.format, kW, kH, raw, s.desc.values);
      width = kW;
    }
    const auto& inj = injected[s.name];
    const StabilityTarget& target = rep.targets[i];
    EXPECT_EQ(target.resource, s.name);
    EXPECT_EQ(target.max_seen, cpu.max_abs);
    for (uint32_t c = 0; c < kStabilityCategoryCount; ++c) {
      SCOPED_TRACE(stability_category_name(StabilityCategory(c)));
      EXPECT_EQ(cpu.count[c], inj[c]) << "CPU mirror vs injected";
      const StabilityRecord* r = rep.find("stability_fill", s.name, StabilityCategory(c));
      EXPECT_EQ(target.count[c], cpu.count[c]);
      if (cpu.count[c] == 0) {
        EXPECT_EQ(r, nullptr);
        continue;
      }
      ASSERT_NE(r, nullptr);
      EXPECT_EQ(r->count, cpu.count[c]);
      EXPECT_EQ(r->first_count, cpu.count[c]);
      EXPECT_EQ(r->frames_with_issue, 1u);
      EXPECT_EQ(r->first_frame, 0u);
      EXPECT_EQ(r->first_index, cpu.first[c]);
      EXPECT_EQ(r->first_index, injected_first[s.name][c]);
      EXPECT_EQ(r->buffer, buffer);
      if (buffer) {
        EXPECT_EQ(r->first_x, cpu.first[c]);
      } else {
        EXPECT_EQ(r->first_x, cpu.first[c] % width);
        EXPECT_EQ(r->first_y, cpu.first[c] / width);
      }
    }
  }
  // Scanning changed nothing it read, and with the scan off nothing is dispatched.
  ex.enable_stability_scan(false);
  FrameResult off = ex.run_frame();
  EXPECT_EQ(off.scan_dispatches, 0u);
  EXPECT_EQ(ex.stability().frames, 1u);
}

// Silent saturation, known answers: a texel whose checked channel is exactly at the format's
// largest finite value is counted, one at the next representable value below is not, on the
// GPU and in the CPU mirror alike. Values are exact in each format, so the bytes hold them as is.
TEST(StabilityCpu, FormatMaximaPerFormat) {
  auto max_of = [](Format f, Encoding e = Encoding::none) {
    const ValueDomain v = effective_domain(f, finite_values().encoded(e));
    return std::pair<float, float>{v.format_max, v.format_max_b};
  };
  EXPECT_EQ(max_of(Format::rgba16_float), std::make_pair(65504.0f, 65504.0f));
  EXPECT_EQ(max_of(Format::rg16_float), std::make_pair(65504.0f, 65504.0f));
  EXPECT_EQ(max_of(Format::b10g11r11_float), std::make_pair(65024.0f, 64512.0f));
  EXPECT_EQ(max_of(Format::e5b9g9r9_float), std::make_pair(65408.0f, 65408.0f));
  EXPECT_EQ(max_of(Format::r32_uint, Encoding::rgb9e5), std::make_pair(65408.0f, 65408.0f));
  EXPECT_EQ(effective_domain(Format::buffer, finite_values().encoded(Encoding::rgb9e5).layout(1, 0, 1)).format_max,
            65408.0f);
  for (Format f : {Format::r32_uint, Format::r32_float, Format::rgba32_float, Format::rgba8_unorm, Format::d32_float,
                   Format::buffer})
    EXPECT_EQ(max_of(f), std::make_pair(kInf, kInf)) << format_name(f);
  // A declared domain never carries them.
  EXPECT_EQ(non_negative_values().format_max, kInf);
  // Saturated is independent of the domain: a signed channel at -max, an unbounded one at max.
  const ValueDomain h = effective_domain(Format::rgba16_float, finite_values());
  EXPECT_EQ(classify({65504.0f, 0, 0, 0}, h), 1u << kSat);
  EXPECT_EQ(classify({0, 0, 0, -65504.0f}, h), 1u << kSat);
  EXPECT_EQ(classify({65472.0f, -65472.0f, 0, 0}, h), 0u);
  EXPECT_EQ(classify({kInf, 0, 0, 0}, h), 1u << kPosInf) << "Inf is not a finite value at the maximum";
  EXPECT_EQ(classify({65504.0f}, effective_domain(Format::r32_float, finite_values())), 0u);
}

TEST_F(StabilityScan, SaturationAtFormatMaximumKnownAnswers) {
  struct Known {
    const char* name;
    Format format;
    ValueDomain values;
    std::vector<std::array<float, 4>> texels;
    std::vector<bool> saturated;
  };
  const float h = codecs::kHalfMax, h_below = 65472.0f;                 // half: ulp 32 at 2^15
  const float r11 = codecs::kR11Max, r11_below = 64512.0f;              // 6 mantissa bits: ulp 512
  const float b10 = codecs::kB10Max, b10_below = 63488.0f;              // 5 mantissa bits: ulp 1024
  const float e9 = codecs::kRgb9e5Max, e9_below = 65280.0f;             // 9 bits at 2^7: ulp 128
  const std::vector<Known> known{
      {"k_rgba16f", Format::rgba16_float, finite_values(),
       {{h, 0, 0, 0}, {h_below, 0, 0, 0}, {0, 0, 0, -h}, {0, 0, -h_below, 0}, {0, 0, 0, h}, {1, 2, 3, 4},
        {h_below, -h_below, h_below, -h_below}},
       {true, false, true, false, true, false, false}},
      {"k_rg16f", Format::rg16_float, non_negative_values(),
       {{0, h, 0, 0}, {h_below, h_below, 0, 0}, {h, 0, 0, 0}, {0.25f, 64, 0, 0}},
       {true, false, true, false}},
      // R and G saturate at 65024; B (10 bits) at 64512, which R and G hold below their maximum.
      {"k_b10g11r11", Format::b10g11r11_float, non_negative_values(),
       {{r11, 0, 0, 0}, {r11_below, 0, 0, 0}, {0, r11, 0, 0}, {0, r11_below, 0, 0}, {0, 0, b10, 0},
        {0, 0, b10_below, 0}, {r11_below, r11_below, b10_below, 0}},
       {true, false, true, false, true, false, false}},
      {"k_rgb9e5_uint", Format::r32_uint, non_negative_values().encoded(Encoding::rgb9e5),
       {{e9, 0, 0, 0}, {e9_below, 0, 0, 0}, {0, 0, e9, 0}, {0, e9_below, 0, 0}, {e9_below, e9_below, e9_below, 0}},
       {true, false, true, false, false}},
  };
  std::vector<FillSource> sources;
  for (const Known& k : known) {
    std::vector<float> t;
    for (auto& texel : k.texels) t.insert(t.end(), texel.begin(), texel.end());
    FillSource s;
    s.name = k.name;
    const uint32_t w = uint32_t(k.texels.size());
    s.desc = ResourceDesc{k.format, SizeRule::fixed, w, 1}.with(k.values);
    s.bytes = encode(k.format, t);
    s.image = gpu().create_image(k.format, w, 1, std::string("stability_test.") + k.name);
    gpu().upload(*s.image, s.bytes.data(), s.bytes.size());
    sources.push_back(std::move(s));
  }
  Executor& ex = scan_fill(sources);
  const StabilityReport& rep = ex.stability();
  ASSERT_EQ(rep.targets.size(), known.size());
  for (size_t i = 0; i < known.size(); ++i) {
    const Known& k = known[i];
    SCOPED_TRACE(k.name);
    const uint32_t w = uint32_t(k.texels.size());
    std::vector<uint8_t> raw = gpu().download(*sources[i].image);
    ASSERT_EQ(raw, sources[i].bytes);
    // The bytes hold the values exactly (so "just below" is the next value down).
    const ValueDomain eff = effective_domain(k.format, k.values);
    if (k.format != Format::r32_uint) {
      const FloatImage img = decode_texels(k.format, w, 1, raw);
      for (uint32_t x = 0; x < w; ++x)
        for (uint32_t c = 0; c < img.channels; ++c) EXPECT_EQ(img.at(x, 0, c), k.texels[x][c]) << x << " " << c;
    } else {
      for (uint32_t x = 0; x < w; ++x) {
        uint32_t word;
        std::memcpy(&word, raw.data() + 4 * x, 4);
        float rgb[3];
        codecs::decode_rgb9e5(word, rgb);
        for (uint32_t c = 0; c < 3; ++c) EXPECT_EQ(rgb[c], k.texels[x][c]) << x << " " << c;
      }
    }
    uint64_t expected = 0, expected_first = ~0ull;
    for (uint32_t x = 0; x < w; ++x) {
      // Per texel: the CPU classification agrees with the expected answer.
      std::vector<float> one(k.texels[x].begin(), k.texels[x].end());
      const uint32_t channels = k.format == Format::rg16_float ? 2 : k.format == Format::rgba16_float ? 4 : 3;
      const bool sat = stability_classify(one.data(), channels, eff) & (1u << kSat);
      EXPECT_EQ(sat, bool(k.saturated[x])) << "texel " << x;
      if (k.saturated[x]) {
        ++expected;
        expected_first = std::min<uint64_t>(expected_first, x);
      }
    }
    const StabilityCounts cpu = stability_scan_texels(k.format, w, 1, raw, k.values);
    EXPECT_EQ(cpu.count[kSat], expected);
    EXPECT_EQ(cpu.first[kSat], expected_first);
    const StabilityTarget& target = rep.targets[i];
    EXPECT_EQ(target.resource, k.name);
    EXPECT_EQ(target.count, cpu.count) << "GPU vs CPU, every category";
    EXPECT_EQ(target.max_seen, cpu.max_abs);
    const StabilityRecord* r = rep.find("stability_fill", k.name, StabilityCategory::saturated);
    ASSERT_NE(r, nullptr);
    EXPECT_EQ(r->count, expected);
    EXPECT_EQ(r->first_x, expected_first);
    EXPECT_EQ(r->first_y, 0u);
  }
  // The first-offender line names the category.
  const StabilityRecord* first = rep.first(StabilityCategory::saturated);
  ASSERT_NE(first, nullptr);
  EXPECT_EQ(describe(*first),
            "Value at format maximum first produced by stability_fill writing k_rgba16f at frame 0, pixel (0, 0) "
            "(3 texels)");
}

// The probe_visibility atlas's shape (RG16F, 2560 x 160 x 3 cascades: more texels than the 16 x
// 16 tiles of 16 x 16 cover, so the scan's grid-stride loop wraps in x and y): a floor of 0.001
// (the moments' clamp) everywhere and the large values at texels far from the origin; the
// scan's max_seen, counts and first offenders must equal the CPU mirror's.
TEST_F(StabilityScan, LargeRg16fAtlasMaxSeenAndCountsEqualTheCpu) {
  constexpr uint32_t kW = 2560, kH = 480;
  std::vector<float> t(size_t(4) * kW * kH, 0.0f);
  for (size_t i = 0; i < size_t(kW) * kH; ++i) {
    t[4 * i] = 0.001f;
    t[4 * i + 1] = 1e-6f;
  }
  auto at = [&](uint32_t x, uint32_t y) { return &t[4 * (size_t(y) * kW + x)]; };
  at(2301, 431)[0] = 8.0f;   // mean distance
  at(2301, 431)[1] = 64.0f;  // its square: the largest value, above the bound of 6
  at(1700, 300)[0] = 5.0f;   // below the bound
  at(2559, 479)[1] = 7.5f;   // above the bound: the last texel
  at(300, 260)[1] = 6.5f;    // above the bound: the first of the three in linear order
  at(17, 259)[0] = -0.5f;    // negative: in the second row of the grid-stride loop
  FillSource s;
  s.name = "s_probe_visibility";
  s.desc = ResourceDesc{Format::rg16_float, SizeRule::fixed, kW, kH}.with(non_negative_values().bounded(6.0f));
  s.bytes = encode(Format::rg16_float, t);
  s.image = gpu().create_image(Format::rg16_float, kW, kH, "stability_test.s_probe_visibility");
  gpu().upload(*s.image, s.bytes.data(), s.bytes.size());
  std::vector<FillSource> sources;
  sources.push_back(std::move(s));

  Executor& ex = scan_fill(sources);
  const StabilityReport& rep = ex.stability();
  ASSERT_EQ(rep.targets.size(), 1u);
  std::vector<uint8_t> raw = gpu().download(*sources[0].image);
  ASSERT_EQ(raw, sources[0].bytes);
  const StabilityCounts cpu = stability_scan_texels(Format::rg16_float, kW, kH, raw, sources[0].desc.values);
  EXPECT_EQ(cpu.max_abs, 64.0f);
  EXPECT_EQ(cpu.count[kAbove], 3u);  // 64, 7.5, 6.5 (8 in the same texel as 64)
  EXPECT_EQ(cpu.first[kAbove], 260ull * kW + 300);
  EXPECT_EQ(cpu.count[kNeg], 1u);
  EXPECT_EQ(cpu.first[kNeg], 259ull * kW + 17);
  const StabilityTarget& target = rep.targets[0];
  EXPECT_EQ(target.max_seen, cpu.max_abs) << "the scan's largest |value| over the whole atlas";
  for (uint32_t c = 0; c < kStabilityCategoryCount; ++c) {
    SCOPED_TRACE(stability_category_name(StabilityCategory(c)));
    EXPECT_EQ(target.count[c], cpu.count[c]);
    const StabilityRecord* r = rep.find("stability_fill", "s_probe_visibility", StabilityCategory(c));
    if (cpu.count[c] == 0) {
      EXPECT_EQ(r, nullptr);
      continue;
    }
    ASSERT_NE(r, nullptr);
    EXPECT_EQ(r->first_index, cpu.first[c]);
    EXPECT_EQ(r->max_seen, cpu.max_abs);
  }
}

// ---------------------------------------------------------------- executor: first offender
// Writes (0.25, 0.5, 0.75, 1) -- or its source -- with `bad_bits` in channel 1 of one texel on
// one frame, and accumulates into a persistent history (so the bad value lives on there).
class InjectPass final : public Pass {
 public:
  InjectPass(std::string name, std::string source, std::string out, std::string history, uint32_t bad_frame,
             uint32_t x, uint32_t y, uint32_t bits)
      : name_(std::move(name)), source_(std::move(source)), out_(std::move(out)), history_(std::move(history)),
        bad_frame_(bad_frame), x_(x), y_(y), bits_(bits) {}
  PassDecl declare(const Scene&, const Settings&) const override {
    ResourceDesc h = ResourceDesc{Format::rgba32_float, SizeRule::render}.with(non_negative_values());
    h.persistent = true;
    PassDecl d;
    d.name = name_;
    if (!source_.empty()) d.slots.push_back({source_, Access::read});
    d.slots.push_back({out_, Access::write, ResourceDesc{Format::rgba32_float, SizeRule::render}.with(non_negative_values())});
    d.slots.push_back({history_, Access::read_write, h});
    return d;
  }
  void record(RecordContext& ctx) override {
    using namespace glsl;
    StabilityTestPush push{ctx.frame, bad_frame_, x_, y_, bits_, source_.empty() ? 0u : 1u, 0, 0};
    record_compute(ctx, {.shader = "stability_test.comp",
                         .images = {{kStabilityTestBindSource, source_.empty() ? history_.c_str() : source_.c_str()},
                                    {kStabilityTestBindOut, out_.c_str()},
                                    {kStabilityTestBindHistory, history_.c_str()}},
                         .groups_x = div_up(ctx.width(out_), kStabilityTestGroup),
                         .groups_y = div_up(ctx.height(out_), kStabilityTestGroup),
                         .push = &push,
                         .push_bytes = sizeof(push),
                         .scene = false});
  }

 private:
  std::string name_, source_, out_, history_;
  uint32_t bad_frame_, x_, y_, bits_;
};

TEST_F(StabilityScan, ReportsThePassFrameAndPixelThatFirstProducedEachCategory) {
  Scene scene = load_scene(scene_path("sky_plane.json"));
  Settings s;
  s.width = 12;
  s.height = 10;
  for (bool batched : {false, true}) {
    SCOPED_TRACE(batched ? "frames in one submission" : "a submission per pass");
    std::vector<std::unique_ptr<Pass>> passes;
    // stability_inject writes a NaN at (5, 7) on frame 2; stability_forward copies it on (same
    // frame, later pass) and writes its own +Inf at (2, 3) on frame 1. Both histories keep what
    // they accumulate, so the bad values live on in later frames.
    passes.push_back(std::make_unique<InjectPass>("stability_inject", "", "inject_out", "inject_history", 2, 5, 7,
                                                  0x7fc00000u));
    passes.push_back(std::make_unique<InjectPass>("stability_forward", "inject_out", "forward_out", "forward_history", 1,
                                                  2, 3, 0x7f800000u));
    Executor ex(gpu(), scene, s, std::move(passes), {"forward_out"});
    ex.enable_stability_scan();
    EXPECT_TRUE(ex.stability().clean());
    // One submission a pass (host-timed, lavapipe's default) or the four frames in one
    // submission (a GPU's): the scans of each frame land in its own results, read in frame order.
    std::vector<FrameResult> frames;
    if (batched) {
      ex.time_passes_on_host(false);
      frames = ex.run_frames(4);
    } else {
      for (int f = 0; f < 4; ++f) frames.push_back(ex.run_frame());
    }
    ASSERT_EQ(frames.size(), 4u);
    for (uint32_t f = 0; f < 4; ++f) {
      EXPECT_EQ(frames[f].frame, f);
      EXPECT_EQ(frames[f].scan_dispatches, 4u);
      EXPECT_EQ(frames[f].passes.size(), 2u);
    }
    const StabilityReport& rep = ex.stability();
    EXPECT_EQ(rep.frames, 4u);
    EXPECT_EQ(rep.dispatches_per_frame, 4u);
    EXPECT_FALSE(rep.clean());

    const StabilityRecord* nan = rep.first(StabilityCategory::nan);
    ASSERT_NE(nan, nullptr);
    EXPECT_EQ(nan->pass, "stability_inject");
    EXPECT_EQ(nan->resource, "inject_out");
    EXPECT_EQ(nan->first_frame, 2u);
    EXPECT_EQ(nan->first_x, 5u);
    EXPECT_EQ(nan->first_y, 7u);
    EXPECT_EQ(nan->count, 1u);
    EXPECT_EQ(nan->frames_with_issue, 1u);
    // Carried on, not produced: the forward pass's copy (same frame, later pass) and the
    // histories (frames 2 and 3) come after it.
    const StabilityRecord* copied = rep.find("stability_forward", "forward_out", StabilityCategory::nan);
    ASSERT_NE(copied, nullptr);
    EXPECT_EQ(copied->first_frame, 2u);
    const StabilityRecord* hist = rep.find("stability_inject", "inject_history", StabilityCategory::nan);
    ASSERT_NE(hist, nullptr);
    EXPECT_EQ(hist->first_frame, 2u);
    EXPECT_EQ(hist->frames_with_issue, 2u);
    EXPECT_EQ(hist->count, 2u);
    EXPECT_EQ(hist->first_x, 5u);
    EXPECT_EQ(hist->first_y, 7u);

    // +Inf: produced a frame earlier by the later pass.
    const StabilityRecord* inf = rep.first(StabilityCategory::pos_inf);
    ASSERT_NE(inf, nullptr);
    EXPECT_EQ(inf->pass, "stability_forward");
    EXPECT_EQ(inf->resource, "forward_out");
    EXPECT_EQ(inf->first_frame, 1u);
    EXPECT_EQ(inf->first_x, 2u);
    EXPECT_EQ(inf->first_y, 3u);
    const StabilityRecord* inf_hist = rep.find("stability_forward", "forward_history", StabilityCategory::pos_inf);
    ASSERT_NE(inf_hist, nullptr);
    EXPECT_EQ(inf_hist->frames_with_issue, 3u);
    EXPECT_EQ(rep.first(StabilityCategory::neg_inf), nullptr);
    EXPECT_EQ(rep.first(StabilityCategory::negative), nullptr);
    EXPECT_EQ(rep.first(StabilityCategory::above_max), nullptr);

    std::vector<std::string> lines = rep.first_offender_lines();
    ASSERT_EQ(lines.size(), 2u);
    EXPECT_EQ(lines[0], "NaN first produced by stability_inject writing inject_out at frame 2, pixel (5, 7) (1 texel)");
    EXPECT_EQ(lines[1], "+Inf first produced by stability_forward writing forward_out at frame 1, pixel (2, 3) (1 texel)");
    EXPECT_EQ(describe(*hist),
              "NaN first produced by stability_inject writing inject_history at frame 2, pixel (5, 7) (1 texel; 2 in 2 "
              "frames in all)");
    for (auto& l : lines) std::printf("%s\n", l.c_str());
  }
}

TEST_F(StabilityScan, DirectTechniqueHasNoOffendersAndIsUnchangedByTheScan) {
  Scene scene = load_scene(scene_path("cornell.json"));
  const Technique& t = find_technique("direct");
  Settings s;
  s.width = 64;
  s.height = 36;
  s = apply_preset(t, "medium", s);
  auto run = [&](bool scan, StabilityReport* report) {
    Executor ex(gpu(), scene, s, make_passes(t), {t.output});
    ex.enable_stability_scan(scan);
    uint32_t dispatches = 0;
    for (int f = 0; f < 2; ++f) dispatches += ex.run_frame().scan_dispatches;
    if (report) *report = ex.stability();
    EXPECT_EQ(dispatches, scan ? 2 * ex.stability().dispatches_per_frame : 0u);
    return ex.read(t.output);
  };
  StabilityReport rep;
  FloatImage with = run(true, &rep);
  FloatImage without = run(false, nullptr);
  for (auto& l : rep.first_offender_lines()) ADD_FAILURE() << l;
  EXPECT_TRUE(rep.clean());
  EXPECT_EQ(rep.frames, 2u);
  std::vector<std::string> scanned;
  for (auto& target : rep.targets) scanned.push_back(target.pass + "/" + target.resource);
  EXPECT_EQ(scanned, (std::vector<std::string>{"visibility/depth", "gbuffer/gbuffer_albedo", "gbuffer/gbuffer_normal",
                                               "gbuffer/gbuffer_position", "gbuffer/gbuffer_emissive",
                                               "direct_lighting/direct_light"}));
  for (auto& target : rep.targets)
    if (target.resource == "direct_light") {
      EXPECT_GT(target.max_seen, 0.0f) << "the scan saw the lit image";
    }
  EXPECT_EQ(with.pixels, without.pixels);
}

// Not run by ctest: the scan's cost per frame (radiance-cache medium, 128x72). Run with
// gib_tests --gtest_also_run_disabled_tests --gtest_filter='*StabilityScanOverhead*'.
TEST_F(StabilityScan, DISABLED_StabilityScanOverheadRadianceCacheMedium) {
  Scene scene = load_scene(scene_path("cornell.json"));
  const Technique& t = find_technique("radiance-cache");
  Settings s;
  s.width = 128;
  s.height = 72;
  s = apply_preset(t, "medium", s);
  for (bool scan : {false, true, false, true}) {
    Executor ex(gpu(), scene, s, make_passes(t), {t.output});
    ex.enable_stability_scan(scan);
    std::vector<double> wall, total, scan_ms;
    for (int f = 0; f < 9; ++f) {
      auto t0 = std::chrono::steady_clock::now();
      FrameResult fr = ex.run_frame();
      double w = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      if (f < 3) continue;  // warm-up: pipelines, caches
      wall.push_back(w);
      total.push_back(fr.total_ms);
      scan_ms.push_back(fr.scan_ms);
    }
    auto median = [](std::vector<double> v) {
      std::sort(v.begin(), v.end());
      return v[v.size() / 2];
    };
    std::printf("scan %-3s: frame wall %.2f ms, total_ms %.2f, scan_ms %.2f, dispatches/frame %u, offenders %zu\n",
                scan ? "on" : "off", median(wall), median(total), median(scan_ms), ex.stability().dispatches_per_frame,
                ex.stability().records.size());
    for (auto& l : ex.stability().first_offender_lines()) std::printf("  %s\n", l.c_str());
  }
}

}  // namespace
}  // namespace gib
