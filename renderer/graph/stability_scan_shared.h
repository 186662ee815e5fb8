// The stability scan's contract (C++ and GLSL): after a pass runs, the executor dispatches
// stability_scan_{image,uint,buffer}.comp over every resource the pass writes whose
// ResourceDesc::values declares a domain. Each dispatch reduces one resource into one record
// of the per-frame result buffer: per category the number of offending texels / elements and
// the smallest linear index among them. CPU mirror and report: renderer/graph/stability.h.
#ifndef GIB_STABILITY_SCAN_SHARED_H
#define GIB_STABILITY_SCAN_SHARED_H
#include "gib_shared.h"
GIB_SHARED_BEGIN

GIB_CONST(uint, kStabilityScanGroup, 256)    // buffers: 1D workgroup
GIB_CONST(uint, kStabilityScanTile, 16)      // images: 16 x 16 workgroup
GIB_CONST(uint, kStabilityScanMaxGroups, 256)  // buffers: groups; images: 16 x 16 groups at most; grid-stride beyond
GIB_CONST(uint, kStabilityScanBindResults, 0)   // uint words: kStabilityRecordWords per record
GIB_CONST(uint, kStabilityScanBindSource, 1)    // sampled float image, r32ui storage image or storage buffer

// Categories, in this order everywhere (StabilityCategory in stability.h).
GIB_CONST(uint, kStabilityNan, 0)
GIB_CONST(uint, kStabilityPosInf, 1)
GIB_CONST(uint, kStabilityNegInf, 2)
GIB_CONST(uint, kStabilityNegative, 3)  // finite and < 0 where the domain forbids it
GIB_CONST(uint, kStabilityAboveMax, 4)  // finite and > the bound (|v| for signed channels)
GIB_CONST(uint, kStabilitySaturated, 5)  // finite and |v| >= the storage format's largest finite value
GIB_CONST(uint, kStabilityCategories, 6)

// One record: words [0,6) counts per category, [6,12) first offender per category stored as
// ~linear_index with atomicMax (0: none, so a zero-filled buffer is a reset one), word 12 the
// largest finite |value| seen (float bits, atomicMax), the rest padding.
GIB_CONST(uint, kStabilityRecordWords, 16)
GIB_CONST(uint, kStabilityRecordFirst, 6)
GIB_CONST(uint, kStabilityRecordMaxAbs, 12)

// Domain codes (Domain in graph.h): 1 finite, 2 non-negative, 3 unit ([0, 1]).
GIB_CONST(uint, kStabilityDomainFinite, 1)
GIB_CONST(uint, kStabilityDomainNonNegative, 2)
GIB_CONST(uint, kStabilityDomainUnit, 3)
// Encoding codes (Encoding in graph.h): 0 raw float, 1 RGB9E5 word (3 channels).
GIB_CONST(uint, kStabilityEncodingRgb9e5, 1)

struct StabilityScanPush {
  uint record;           // record index in the result buffer
  uint count;            // buffer elements to scan (images: width x height)
  uint width;            // images: linear index = y * width + x
  uint channels;         // bit c: channel c is checked (image channel, or buffer value c)
  uint signed_channels;  // bit c: channel c may be negative; the bound applies to |v|
  uint domain;           // kStabilityDomain*
  float max_value;       // bound (+inf: none); already min(bound, 1) for unit
  uint encoding;         // 0 or kStabilityEncodingRgb9e5
  uint stride_words;     // buffers: element stride in 32-bit words
  uint first_word;       // buffers: first value word of an element
  uint words;            // buffers: consecutive value words per element
  uint height;           // images
  float format_max;      // saturated: |v| >= this (bits compared; +inf: never), every channel but 2
  float format_max_b;    // the same for channel 2 (R11G11B10F's 10-bit B)
};

GIB_SHARED_END
#endif
