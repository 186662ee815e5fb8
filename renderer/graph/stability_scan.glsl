// The stability scan kernel, included by stability_scan_{image,uint,buffer}.comp, each of which
// defines scan_element (load texel (x, y) when STABILITY_SCAN_IMAGE is defined, else buffer
// element i, and call scan_value per channel). One dispatch reduces one resource into record
// pc.record: a thread walks elements in a grid-stride loop, the workgroup reduces in shared
// memory, and one thread per category adds to the global record. Everything is decided on float bits, so a device's NaN / denormal handling in
// comparisons cannot change a verdict. CPU mirror: stability_classify (stability.cpp).
#include "renderer/graph/stability_scan_shared.h"
#include "packing.glsl"

#ifdef STABILITY_SCAN_IMAGE
layout(local_size_x = kStabilityScanTile, local_size_y = kStabilityScanTile) in;
#else
layout(local_size_x = kStabilityScanGroup) in;
#endif
layout(push_constant) uniform Push { StabilityScanPush pc; };
layout(std430, set = 0, binding = kStabilityScanBindResults) buffer Results { uint results[]; };

shared uint s_count[kStabilityCategories];
shared uint s_first[kStabilityCategories];
shared uint s_max;

uint t_flags = 0u;     // categories the current element falls in
uint t_max_bits = 0u;  // largest finite |value| this thread saw (bits of a non-negative float)

// Branch-free on purpose: a CPU device runs lanes in SIMD and pays for every divergent path.
void scan_value(float v, uint channel) {
  const uint bit = 1u << channel;
  if ((pc.channels & bit) == 0u) return;  // uniform
  const uint bits = floatBitsToUint(v);
  const uint mag = bits & 0x7fffffffu;
  const bool neg = (bits >> 31) != 0u && mag != 0u;  // -0 is not negative
  const bool finite = mag < 0x7f800000u;
  const bool may_be_negative = (pc.signed_channels & bit) != 0u;
  uint f = mag > 0x7f800000u ? (1u << kStabilityNan) : 0u;
  f |= mag == 0x7f800000u ? (1u << (neg ? kStabilityNegInf : kStabilityPosInf)) : 0u;
  f |= finite && neg && !may_be_negative && pc.domain >= kStabilityDomainNonNegative ? (1u << kStabilityNegative) : 0u;
  f |= finite && (may_be_negative || !neg) && uintBitsToFloat(mag) > pc.max_value ? (1u << kStabilityAboveMax) : 0u;
  const uint format_max_bits = floatBitsToUint(channel == 2u ? pc.format_max_b : pc.format_max);
  f |= finite && mag >= format_max_bits ? (1u << kStabilitySaturated) : 0u;
  t_flags |= f;
  t_max_bits = max(t_max_bits, finite ? mag : 0u);
}

#ifdef STABILITY_SCAN_IMAGE
void scan_element(uint x, uint y);  // image: texel (x, y), linear index y * width + x
#else
void scan_element(uint i);  // buffer: element i
#endif

uint count[kStabilityCategories];
uint first[kStabilityCategories];  // ~index: the largest is the smallest index

void tally(uint i) {
  if (t_flags == 0u) return;
  for (uint c = 0u; c < kStabilityCategories; ++c)
    if ((t_flags & (1u << c)) != 0u) {
      count[c] += 1u;
      first[c] = max(first[c], ~i);
    }
}

void main() {
  const uint lid = gl_LocalInvocationIndex;
  if (lid < kStabilityCategories) {
    s_count[lid] = 0u;
    s_first[lid] = 0u;
  }
  if (lid == 0u) s_max = 0u;
  barrier();

  for (uint c = 0u; c < kStabilityCategories; ++c) {
    count[c] = 0u;
    first[c] = 0u;
  }
#ifdef STABILITY_SCAN_IMAGE
  // 2D grid-stride loop: no integer division per texel (scalarised on a CPU device).
  const uvec2 step = gl_NumWorkGroups.xy * uvec2(kStabilityScanTile);
  for (uint y = gl_GlobalInvocationID.y; y < pc.height; y += step.y)
    for (uint x = gl_GlobalInvocationID.x; x < pc.width; x += step.x) {
      t_flags = 0u;
      scan_element(x, y);
      tally(y * pc.width + x);
    }
#else
  const uint step = gl_NumWorkGroups.x * kStabilityScanGroup;
  for (uint i = gl_GlobalInvocationID.x; i < pc.count; i += step) {
    t_flags = 0u;
    scan_element(i);
    tally(i);
  }
#endif
  for (uint c = 0u; c < kStabilityCategories; ++c)
    if (count[c] != 0u) {
      atomicAdd(s_count[c], count[c]);
      atomicMax(s_first[c], first[c]);
    }
  if (t_max_bits != 0u) atomicMax(s_max, t_max_bits);
  barrier();

  const uint base = pc.record * kStabilityRecordWords;
  if (lid < kStabilityCategories && s_count[lid] != 0u) {
    atomicAdd(results[base + lid], s_count[lid]);
    atomicMax(results[base + kStabilityRecordFirst + lid], s_first[lid]);
  }
  if (lid == kStabilityCategories && s_max != 0u) atomicMax(results[base + kStabilityRecordMaxAbs], s_max);
}
