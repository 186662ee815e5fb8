// The suite's two tiers.
//   ci:  each case's width x height (small: 128x72 for most), its committed path-traced
//        references (goldens/<case>/reference*.exr) and technique goldens; the default on
//        lavapipe, and CI's smoke test.
//   gpu: each case's gpu_width x gpu_height (640x360 unless the case says), the default on
//        every other device. References are not committed at this size: they are path traced
//        on the GPU on demand, to the noise-floor rule (cases/README.md), and kept in a local
//        cache keyed by everything that changes them (harness/references.h); approved technique goldens live in
//        goldens/<case>/gpu/ as half-float EXR (float where a value exceeds half's range).
#pragma once
#include <string>

#include "harness/case.h"
#include "harness/goldens.h"

namespace gib {

enum class Tier { ci, gpu };

// `requested`: "ci", "gpu" or "" (by device: ci on lavapipe, gpu elsewhere). Anything else is
// an error naming --tier.
Tier resolve_tier(const std::string& requested, const std::string& device_class);
const char* tier_name(Tier t);
// The case as rendered at the tier (the GPU tier's size; nothing else changes).
Case at_tier(const Case& c, Tier t);
// Where the approved technique goldens of the tier live: goldens/<case> or goldens/<case>/gpu.
GoldenStore technique_store(const std::string& goldens_dir, const std::string& case_name, Tier t);

}  // namespace gib
