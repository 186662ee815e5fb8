// Stability report formatting and the CPU mirror of stability_scan.glsl.
#include "renderer/graph/stability.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <limits>

#include "renderer/codecs/half.h"
#include "renderer/codecs/packed_float.h"
#include "renderer/codecs/r11g11b10.h"
#include "renderer/codecs/rgb9e5.h"
#include "renderer/graph/executor.h"

namespace gib {

const char* stability_category_name(StabilityCategory c) {
  switch (c) {
    case StabilityCategory::nan: return "NaN";
    case StabilityCategory::pos_inf: return "+Inf";
    case StabilityCategory::neg_inf: return "-Inf";
    case StabilityCategory::negative: return "Negative value";
    case StabilityCategory::above_max: return "Value above bound";
    case StabilityCategory::saturated: return "Value at format maximum";
  }
  return "?";
}

namespace {

uint32_t format_channel_mask(Format f, Encoding e) {
  switch (f) {
    case Format::r32_uint: return e == Encoding::rgb9e5 ? 0x7u : 0x1u;
    case Format::r32_float: case Format::d32_float: return 0x1u;
    case Format::rg32_uint: case Format::rg32_float: case Format::rg16_float: return 0x3u;
    case Format::b10g11r11_float: case Format::e5b9g9r9_float: return 0x7u;
    case Format::rgba32_uint: case Format::rgba32_float: case Format::rgba16_float: case Format::rgba16_uint:
    case Format::rgba8_unorm:
      return 0xfu;
    case Format::buffer: break;
  }
  return 0u;
}

// The largest finite value a store to `f` (words decoded as `e`) keeps, where the store clamps
// silently; channel 2's in *b. +inf: none (32-bit float, integer, unorm, depth formats).
float format_max(Format f, Encoding e, float* b) {
  float m = std::numeric_limits<float>::infinity();
  switch (f) {
    case Format::r32_uint: case Format::buffer:
      if (e == Encoding::rgb9e5) m = codecs::kRgb9e5Max;
      break;
    case Format::e5b9g9r9_float: m = codecs::kRgb9e5Max; break;
    case Format::rgba16_float: case Format::rg16_float: m = codecs::kHalfMax; break;
    case Format::b10g11r11_float: *b = codecs::kB10Max; return codecs::kR11Max;
    default: break;
  }
  *b = m;
  return m;
}

}  // namespace

ValueDomain effective_domain(Format format, const ValueDomain& v) {
  ValueDomain e = v;
  uint32_t mask = 0;
  if (format == Format::buffer) {
    uint32_t n = v.encoding == Encoding::rgb9e5 ? 3 * v.value_words : v.value_words;
    mask = n >= 32 ? ~0u : (1u << n) - 1u;
  } else {
    mask = format_channel_mask(format, v.encoding);
  }
  e.channels &= mask;
  e.signed_channels &= e.channels;
  if (v.domain == Domain::unit) e.max_value = std::min(v.max_value, 1.0f);
  e.format_max = format_max(format, v.encoding, &e.format_max_b);
  return e;
}

uint32_t stability_classify(const float* values, uint32_t count, const ValueDomain& v, float* max_abs) {
  uint32_t flags = 0;
  for (uint32_t c = 0; c < count && c < 32; ++c) {
    if (!(v.channels & (1u << c))) continue;
    const uint32_t bits = std::bit_cast<uint32_t>(values[c]);
    const uint32_t mag = bits & 0x7fffffffu;
    const bool neg = (bits >> 31) && mag;
    if (mag > 0x7f800000u) {
      flags |= 1u << uint32_t(StabilityCategory::nan);
      continue;
    }
    if (mag == 0x7f800000u) {
      flags |= 1u << uint32_t(neg ? StabilityCategory::neg_inf : StabilityCategory::pos_inf);
      continue;
    }
    const float a = std::bit_cast<float>(mag);
    if (max_abs && a > *max_abs) *max_abs = a;
    const bool is_signed = v.signed_channels & (1u << c);
    if (neg && !is_signed && (v.domain == Domain::non_negative || v.domain == Domain::unit))
      flags |= 1u << uint32_t(StabilityCategory::negative);
    if ((is_signed || !neg) && a > v.max_value) flags |= 1u << uint32_t(StabilityCategory::above_max);
    // On bits, as the GPU: a finite magnitude's bits order like its value; +inf is above all.
    if (mag >= std::bit_cast<uint32_t>(c == 2 ? v.format_max_b : v.format_max))
      flags |= 1u << uint32_t(StabilityCategory::saturated);
  }
  return flags;
}

bool StabilityCounts::clean() const {
  return std::all_of(count.begin(), count.end(), [](uint64_t n) { return n == 0; });
}

namespace {

void tally(StabilityCounts& out, uint64_t index, uint32_t flags) {
  for (uint32_t c = 0; c < kStabilityCategoryCount; ++c) {
    if (!(flags & (1u << c))) continue;
    if (out.count[c]++ == 0) out.first[c] = index;
  }
}

}  // namespace

StabilityCounts stability_scan_texels(Format format, uint32_t width, uint32_t height, const std::vector<uint8_t>& raw,
                                      const ValueDomain& declared) {
  const ValueDomain v = effective_domain(format, declared);
  StabilityCounts out;
  const size_t n = size_t(width) * height;
  out.elements = n;
  auto u32 = [&](size_t i) {
    uint32_t w;
    std::memcpy(&w, raw.data() + 4 * i, 4);
    return w;
  };
  const bool uint_format = format == Format::r32_uint || format == Format::rg32_uint || format == Format::rgba32_uint;
  if (uint_format) {
    const uint32_t words = format_bytes_per_texel(format) / 4;
    if (raw.size() != n * words * 4)
      throw GraphError(fmt::format("stability_scan_texels: {} {}x{} expects {} bytes, got {}", format_name(format),
                                   width, height, n * words * 4, raw.size()));
    for (size_t i = 0; i < n; ++i) {
      float vals[4] = {};
      uint32_t count = words;
      if (v.encoding == Encoding::rgb9e5) {
        codecs::decode_rgb9e5(u32(i * words), vals);
        count = 3;
      } else {
        for (uint32_t k = 0; k < words; ++k) vals[k] = std::bit_cast<float>(u32(i * words + k));
      }
      tally(out, i, stability_classify(vals, count, v, &out.max_abs));
    }
    return out;
  }
  const FloatImage img = decode_texels(format, width, height, raw);
  for (size_t i = 0; i < n; ++i)
    tally(out, i, stability_classify(&img.pixels[i * img.channels], img.channels, v, &out.max_abs));
  return out;
}

StabilityCounts stability_scan_buffer(const std::vector<uint8_t>& raw, const ValueDomain& declared) {
  const ValueDomain v = effective_domain(Format::buffer, declared);
  StabilityCounts out;
  if (!v.scanned() || v.stride_words == 0) return out;
  const size_t elements = raw.size() / 4 / v.stride_words;
  out.elements = elements;
  std::vector<float> vals(size_t(v.value_words) * 3);
  for (size_t i = 0; i < elements; ++i) {
    uint32_t count = 0;
    for (uint32_t k = 0; k < v.value_words; ++k) {
      uint32_t w;
      std::memcpy(&w, raw.data() + 4 * (i * v.stride_words + v.first_word + k), 4);
      if (v.encoding == Encoding::rgb9e5) {
        codecs::decode_rgb9e5(w, &vals[3 * k]);
        count += 3;
      } else {
        vals[k] = std::bit_cast<float>(w);
        count += 1;
      }
    }
    tally(out, i, stability_classify(vals.data(), count, v, &out.max_abs));
  }
  return out;
}

// ---------------------------------------------------------------- report
uint64_t StabilityReport::total(StabilityCategory c) const {
  uint64_t n = 0;
  for (auto& r : records)
    if (r.category == c) n += r.count;
  return n;
}

const StabilityRecord* StabilityReport::first(StabilityCategory c) const {
  for (auto& r : records)
    if (r.category == c) return &r;
  return nullptr;
}

const StabilityRecord* StabilityReport::find(const std::string& pass, const std::string& resource,
                                             StabilityCategory c) const {
  for (auto& r : records)
    if (r.pass == pass && r.resource == resource && r.category == c) return &r;
  return nullptr;
}

std::string describe(const StabilityRecord& r) {
  const char* unit = r.buffer ? "element" : "texel";
  std::string where = r.buffer ? fmt::format("element {}", r.first_x) : fmt::format("pixel ({}, {})", r.first_x, r.first_y);
  std::string counts = fmt::format("{} {}{}", r.first_count, unit, r.first_count == 1 ? "" : "s");
  if (r.frames_with_issue > 1) counts += fmt::format("; {} in {} frames in all", r.count, r.frames_with_issue);
  return fmt::format("{} first produced by {} writing {} at frame {}, {} ({})", stability_category_name(r.category),
                     r.pass, r.resource, r.first_frame, where, counts);
}

std::vector<std::string> StabilityReport::first_offender_lines() const {
  std::vector<std::string> out;
  for (uint32_t c = 0; c < kStabilityCategoryCount; ++c)
    if (const StabilityRecord* r = first(StabilityCategory(c))) out.push_back(describe(*r));
  return out;
}

}  // namespace gib
