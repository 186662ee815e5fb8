// The tests' deterministic random numbers: xorshift64* seeded through a golden-ratio multiply,
// so every test draws the same sequence on every machine.
#pragma once
#include <cstdint>

namespace gib::test {

struct Rng {
  uint64_t s;
  explicit Rng(uint64_t seed) : s(seed * 0x9E3779B97F4A7C15ull + 1) {}
  uint32_t next() {
    s ^= s >> 12;
    s ^= s << 25;
    s ^= s >> 27;
    return uint32_t((s * 0x2545F4914F6CDD1Dull) >> 32);
  }
  uint32_t below(uint32_t n) { return next() % n; }
  float uniform() { return float(next() >> 8) * (1.0f / 16777216.0f); }  // [0, 1), 24 bits
  float uniform(float lo, float hi) { return lo + (hi - lo) * uniform(); }
};

}  // namespace gib::test
