// Numerical-stability scan results: which pass first produced a NaN, an Inf, a negative value
// where the resource's domain forbids it, a value above its declared bound, or a value at its
// storage format's largest finite value (silent saturation), at which frame and texel / element. The scan itself runs on the GPU (stability_scan*.comp, dispatched by
// the Executor after every pass over each resource it writes whose ResourceDesc::values has a
// domain); this header holds the report and the CPU mirror of the classification.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "renderer/graph/graph.h"

namespace gib {

// saturated: a checked channel's finite |value| >= the largest finite value of the resource's
// storage encoding (RGB9E5 words / E5B9G9R9 65408; R11G11B10F 65024, its B 64512; RGBA16F /
// RG16F 65504), where a store clamps silently; never for 32-bit float, integer or unorm formats.
// Counted for every scanned resource, whatever its declared domain.
enum class StabilityCategory : uint32_t { nan, pos_inf, neg_inf, negative, above_max, saturated };
inline constexpr uint32_t kStabilityCategoryCount = 6;
// "NaN", "+Inf", "-Inf", "Negative value", "Value above bound", "Value at format maximum"
const char* stability_category_name(StabilityCategory c);

// ---- CPU mirror of the GPU scan (tests, tools)
// The domain as the scan applies it to a resource of `format`: channels limited to those the
// format has (images; RGB9E5 words decode to 3), the bound min(max_value, 1) for unit, and
// format_max / format_max_b set to the format's (or RGB9E5 encoding's) largest finite value.
ValueDomain effective_domain(Format format, const ValueDomain& v);
// Categories (bit c = StabilityCategory c) of one element whose checked channel values are
// values[0..count), with `v` already effective. Raises *max_abs to the largest finite |value|.
uint32_t stability_classify(const float* values, uint32_t count, const ValueDomain& v, float* max_abs = nullptr);

struct StabilityCounts {
  std::array<uint64_t, kStabilityCategoryCount> count{};  // offending texels / elements
  std::array<uint64_t, kStabilityCategoryCount> first{};  // smallest linear index (meaningful when count > 0)
  float max_abs = 0;                                      // largest finite |value| of checked channels
  uint64_t elements = 0;
  bool clean() const;
};
// An image's raw texels (as Gpu::download returns them) / a buffer's bytes, scanned on the CPU
// exactly as the GPU scan does (v as declared; effective_domain is applied here).
StabilityCounts stability_scan_texels(Format format, uint32_t width, uint32_t height, const std::vector<uint8_t>& raw,
                                      const ValueDomain& v);
StabilityCounts stability_scan_buffer(const std::vector<uint8_t>& raw, const ValueDomain& v);

// ---- Report, accumulated by the Executor over every frame it ran with the scan on
// One (pass, resource, category) that had offenders in at least one frame.
struct StabilityRecord {
  std::string pass, resource;
  StabilityCategory category = StabilityCategory::nan;
  uint64_t count = 0;              // offending texels / elements, summed over frames
  uint32_t frames_with_issue = 0;
  uint32_t first_frame = 0;        // Executor frame index (0-based, RecordContext::frame)
  uint64_t first_count = 0;        // offending texels / elements in first_frame
  uint64_t first_index = 0;        // smallest linear index (y * width + x, or element) in first_frame
  uint32_t first_x = 0, first_y = 0;  // its pixel; buffers: element index in first_x, 0
  bool buffer = false;
  uint32_t pass_order = 0;         // the pass's position among running passes
  float max_seen = 0;              // largest finite |value| of this (pass, resource) over all frames
};

// One (pass, resource) the scan covers, clean or not.
struct StabilityTarget {
  std::string pass, resource;
  ValueDomain values;  // as declared
  bool buffer = false;
  uint64_t elements = 0;  // texels or buffer elements per scan
  std::array<uint64_t, kStabilityCategoryCount> count{};  // over all frames
  float max_seen = 0;
};

struct StabilityReport {
  uint32_t frames = 0;                // frames scanned
  uint32_t dispatches_per_frame = 0;  // == targets.size()
  std::vector<StabilityTarget> targets;  // execution order, then slot order
  // In order of first offence: frame, then execution order, then slot order, then category.
  // So the first record of a category is where it was first produced: a NaN that a later pass
  // (or a later frame, through history) merely carries on appears after it.
  std::vector<StabilityRecord> records;

  bool clean() const { return records.empty(); }
  uint64_t total(StabilityCategory c) const;  // over every record of category c
  const StabilityRecord* first(StabilityCategory c) const;  // nullptr: none
  const StabilityRecord* find(const std::string& pass, const std::string& resource, StabilityCategory c) const;
  // One line per category that had offenders, e.g. "NaN first produced by gi_denoise writing
  // gi_sh_r at frame 3, pixel (41, 17) (12 texels; 40 in 5 frames in all)".
  std::vector<std::string> first_offender_lines() const;
};
std::string describe(const StabilityRecord& r);  // the line first_offender_lines gives for r

}  // namespace gib
