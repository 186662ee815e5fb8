// Helpers for tests that render a committed case's rows directly: the case's plain row of a
// technique, and probe-volume's probe records read back from its probe_state buffer.
#pragma once
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "harness/case.h"
#include "renderer/techniques/probe_volume/include/probe_volume_shared.h"

namespace gib::test {

// The case's row of `technique` without a label (the variants carry one); an empty
// TechniqueRun (technique "") when the case has none.
inline TechniqueRun plain_row(const Case& c, const std::string& technique) {
  TechniqueRun run;
  for (const TechniqueRun& r : c.techniques)
    if (r.technique == technique && r.label.empty()) run = r;
  return run;
}

// probe_state's probes, after its cascade header.
inline std::vector<glsl::PvProbe> probes_of(const std::vector<uint8_t>& bytes) {
  const size_t header = glsl::kPvMaxCascades * sizeof(glsl::PvCascade);
  std::vector<glsl::PvProbe> p((bytes.size() - header) / sizeof(glsl::PvProbe));
  std::memcpy(p.data(), bytes.data() + header, p.size() * sizeof(glsl::PvProbe));
  return p;
}

}  // namespace gib::test
