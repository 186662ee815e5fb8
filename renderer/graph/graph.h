// Render graph declarations and compilation. Pure CPU, no Vulkan: passes declare what they
// read and write; compile() decides what runs, in what order, what is allocated, where
// barriers go, and records why everything else was culled.
#pragma once
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "renderer/image/format.h"
#include "renderer/scene/features.h"

namespace gib {

enum class SizeRule : uint32_t { render, half, quarter, fixed, buffer };

// The values a resource may hold, declared next to its format. With the stability scan on
// (Executor::enable_stability_scan) every resource a pass writes is checked against its domain
// on the GPU after the pass: NaN, +Inf, -Inf, negatives where forbidden, values above the bound.
enum class Domain : uint32_t {
  none,          // not scanned: ids, bits, keys, counters
  finite,        // any finite value: positions, normals, signed SH coefficients
  non_negative,  // radiance, irradiance, moments, weights, distances, sample counts
  unit,          // [0, 1]: albedo, roughness, depth
};
// How the words of an r32_uint image or of a buffer's value words decode before the check.
enum class Encoding : uint32_t {
  none,    // the words are float bits
  rgb9e5,  // E5B9G9R9 in a uint word (packing.glsl gib_unpack_rgb9e5): 3 channels; finite and
           // non-negative by construction, so only the bound can fail
};
inline constexpr uint32_t kChannelR = 1u, kChannelG = 2u, kChannelB = 4u, kChannelA = 8u;
inline constexpr uint32_t kChannelsRgb = kChannelR | kChannelG | kChannelB;

struct ValueDomain {
  Domain domain = Domain::none;
  float max_value = std::numeric_limits<float>::infinity();  // bound (+inf: none); unit: min(this, 1)
  // Channel c is checked when bit c is set: image channels r,g,b,a (an image format's missing
  // channels are never checked); for buffers value c of an element (RGB9E5 word k: 3k..3k+2).
  uint32_t channels = ~0u;
  // Channels that may be negative although the domain is non_negative / unit (e.g. SH L1 next to
  // a non-negative L0); the bound applies to |v| there.
  uint32_t signed_channels = 0;
  Encoding encoding = Encoding::none;
  // Buffers only (else not scanned): element i's value words are
  // [i * stride_words + first_word, ... + value_words); elements = bytes / 4 / stride_words.
  uint32_t stride_words = 0, first_word = 0, value_words = 0;
  // Not declared (leave them +inf): effective_domain sets them from the storage format. A checked
  // channel whose |value| >= its format maximum is counted as saturated, since the store clamps
  // there silently: format_max for every channel, format_max_b for channel 2 (R11G11B10F's
  // 10-bit B; equal to format_max elsewhere). +inf: the format has no silent saturation.
  float format_max = std::numeric_limits<float>::infinity();
  float format_max_b = std::numeric_limits<float>::infinity();

  bool scanned() const { return domain != Domain::none; }
  bool operator==(const ValueDomain&) const = default;
  // Builders: non_negative().only(kChannelsRgb).bounded(16)
  ValueDomain only(uint32_t mask) const { ValueDomain v = *this; v.channels = mask; return v; }
  ValueDomain allow_negative(uint32_t mask) const { ValueDomain v = *this; v.signed_channels = mask; return v; }
  ValueDomain bounded(float max) const { ValueDomain v = *this; v.max_value = max; return v; }
  ValueDomain encoded(Encoding e) const { ValueDomain v = *this; v.encoding = e; return v; }
  ValueDomain layout(uint32_t stride, uint32_t first, uint32_t words) const {
    ValueDomain v = *this;
    v.stride_words = stride;
    v.first_word = first;
    v.value_words = words;
    return v;
  }
};
inline ValueDomain finite_values() { return {Domain::finite}; }
inline ValueDomain non_negative_values() { return {Domain::non_negative}; }
inline ValueDomain unit_values() { return {Domain::unit}; }
const char* domain_name(Domain d);
std::string describe(const ValueDomain& v);  // "non_negative rgb <= 16 rgb9e5", "" when none

struct ResourceDesc {
  Format format = Format::rgba32_float;
  SizeRule size = SizeRule::render;
  uint32_t width = 0, height = 0;  // SizeRule::fixed
  uint64_t bytes = 0;              // SizeRule::buffer
  bool persistent = false;         // lives across frames (history, accumulation)
  ValueDomain values;              // metadata for the stability scan (same_desc ignores it)
  ResourceDesc with(const ValueDomain& v) const { ResourceDesc d = *this; d.values = v; return d; }
};

// Same resource: format, size rule, extent (fixed) / bytes (buffer) and persistence agree.
// The value domain is not compared: compile() takes it from whichever slot declares one and
// fails when two slots declare different ones.
bool same_desc(const ResourceDesc& a, const ResourceDesc& b);
std::string describe(const ResourceDesc& d);  // "rgba16_float half persistent"

enum class Access : uint32_t { read, write, read_write, read_prev };
const char* access_name(Access a);

// What a pass moves of a buffer it touches sparsely (a hash table's cells, a list's entries),
// for `gibench bench`'s memory time in place of the buffer's size (perf.h, pass_bytes):
// elements = fixed + the sum of count x the GPU-counted work `counter` over `per` (each counter
// a PassDecl::measured name of any running pass, read back after the timed frames). Each element
// moves element_bytes rounded up to a 32-byte sector (a scattered access moves a whole sector),
// or exactly element_bytes when `contiguous` (an appended list). Never more than the buffer.
// An upper bound: no element is assumed to stay in a cache.
struct Touched {
  struct Per {
    std::string counter;
    double count = 0;  // elements per unit of the counter
  };
  double fixed = 0;
  std::vector<Per> per;
  uint32_t element_bytes = 0;
  bool contiguous = false;
};

struct Slot {
  std::string name;  // resource name: a noun, e.g. "vbuffer", "gbuffer_normal"
  Access access = Access::read;
  ResourceDesc desc;  // meaningful on write / read_write (the producer defines the resource)
  std::optional<Touched> touched;  // a sparse access: the bytes it moves (bench only)
};

enum class PassKind : uint32_t { compute, graphics, transfer };
const char* pass_kind_name(PassKind k);

// Work a pass does per frame, known from the settings (rays, probes, samples): reported by
// `gibench bench` and the pass benchmarks next to its time.
struct WorkCounter {
  std::string name;  // e.g. "rays"
  double per_frame = 0;
};

// A work counter the GPU counts: the uint32 at byte `offset` of buffer resource `resource` after
// a frame. Read back by `gibench bench` after its timed frames (never inside a frame), and
// reported next to the declared work: for work that depends on the frame (cells queued).
struct MeasuredCounter {
  std::string name;
  std::string resource;
  uint64_t offset = 0;
};

struct PassDecl {
  std::string name;     // == folder == timer label == bench key
  PassKind kind = PassKind::compute;
  SceneFeatures needs;  // culled when the scene lacks any of these
  // Non-empty: the settings switch the pass off (an option it exists for is 0); culled with this
  // text as the reason, before anything else, and its readers cascade as for a missing feature.
  std::string switched_off;
  std::vector<Slot> slots;
  bool side_effect = false;  // never culled for unused outputs (readbacks, stats)
  std::vector<WorkCounter> work;  // besides "pixels", which every pass reports
  std::vector<MeasuredCounter> measured;  // read back by bench after its timed frames
  // Its shaders walk the BVH (bvh.glsl) for rays the pass exists to trace. Our devices have no
  // ray queries, so the walk runs as shader code, where a console with RT hardware runs it in
  // fixed-function units: bench says so beside its time and its seed rows, since the FLOP split
  // scales the walk as arithmetic. (Not set for a pass that walks only on a rare fallback.)
  bool traces_rays = false;
};

struct GraphError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct CompileOptions {
  SceneFeatures features;                  // what the scene has
  std::vector<std::string> outputs;        // requested sinks (e.g. "final_color", a --dump name)
  uint32_t render_width = 256, render_height = 144;
};

struct ResolvedResource {
  std::string name;
  ResourceDesc desc;
  uint32_t width = 0, height = 0;  // resolved extent (images)
  uint64_t bytes = 0;              // memory it occupies
  int producer = -1;               // index into Plan::passes of the pass that first writes it
  uint32_t copies = 1;             // 2 for a persistent resource read with read_prev (ping-pong)
  uint64_t bytes_per_copy = 0;     // bytes == bytes_per_copy * copies
};

// A barrier before a pass: the listed resources were last written by an earlier pass.
struct Barrier {
  std::vector<std::string> resources;
  uint32_t src_kinds = 0;  // bitmask of (1 << PassKind) of the writers
  uint32_t dst_kind = 0;   // (1 << PassKind) of the pass about to run
};

struct PlannedPass {
  uint32_t decl_index = 0;  // index into the decls given to compile()
  std::string name;
  bool runs = false;
  std::string reason;       // why culled ("" when it runs)
  Barrier barrier_before;   // empty resources: none needed
  uint64_t bytes_written = 0;  // sum of the sizes (one copy) of resources it writes
  PassKind kind = PassKind::compute;
  bool traces_rays = false;    // as declared
  std::vector<Slot> slots;     // as declared
  std::vector<WorkCounter> work;  // as declared
  std::vector<MeasuredCounter> measured;  // as declared
};

struct Plan {
  std::vector<PlannedPass> passes;       // running passes in execution order, then culled ones
  std::vector<ResolvedResource> resources;  // only those used by running passes, first use first
  std::vector<std::string> unproduced_outputs;  // requested outputs whose producers were all culled
  uint32_t render_width = 0, render_height = 0;
  uint64_t total_bytes() const;
  const ResolvedResource* find(const std::string& name) const;
  std::vector<const PlannedPass*> running() const;
  std::string to_text() const;  // the --plan listing
  std::string to_dot() const;   // graphviz
};

// Errors (GraphError, message names the pass and slot): a read of a resource no pass declares
// writing; two passes `write` the same resource; a cycle; a requested output nobody produces;
// inconsistent descs between writers of one resource; read_prev of a non-persistent resource.
// A read_write slot whose desc is left default-constructed inherits the resource's desc; a
// non-default one must match the writer's. Persistent resources may be produced by read_write
// alone (they start zeroed). The resource's value domain is the one its slots declare (writer
// or read_write, any desc); two different declared domains are an error.
Plan compile(const std::vector<PassDecl>& decls, const CompileOptions& options);

}  // namespace gib
