// The attribution game over a technique's stages (error attribution, harness/attribution/):
// v(S) is the final error with the stages in S replaced by their oracles, S a bit mask over at
// most kMaxStages stages (bit i = stage i). Pure arithmetic, no rendering.
#pragma once
#include <cstdint>
#include <vector>

namespace gib::attribution {

constexpr uint32_t kMaxStages = 6;  // exact Shapley: 2^n renders

// Each stage's exact Shapley value of the gap v(none) - v(all):
//   phi_i = sum over S without i of |S|! (n - |S| - 1)! / n! x (v(S) - v(S + i)),
// signed so that a stage whose oracle lowers the error gets a positive share. The values sum
// to v(0) - v(all) up to rounding. `v` has 2^n entries; throws std::invalid_argument otherwise
// or when n is 0 or above kMaxStages.
std::vector<double> shapley(const std::vector<double>& v, uint32_t n);

// The cheap pair of stage i: the error its oracle removes alone (v(none) - v({i})) and the
// error left by every other oracle that its own removes (v(all - i) - v(all)).
struct CheapPair {
  double alone = 0, last = 0;
};
CheapPair cheap_pair(const std::vector<double>& v, uint32_t n, uint32_t i);

}  // namespace gib::attribution
