#include "harness/attribution/game.h"

#include <fmt/format.h>

#include <bit>
#include <stdexcept>

namespace gib::attribution {

namespace {

void check_game(const std::vector<double>& v, uint32_t n) {
  if (n == 0 || n > kMaxStages)
    throw std::invalid_argument(fmt::format("attribution: expected 1..{} stages, got {}", kMaxStages, n));
  if (v.size() != (size_t(1) << n))
    throw std::invalid_argument(fmt::format("attribution: expected 2^{} = {} subset values, got {}", n,
                                            size_t(1) << n, v.size()));
}

double factorial(uint32_t k) {
  double f = 1;
  for (uint32_t i = 2; i <= k; ++i) f *= i;
  return f;
}

}  // namespace

std::vector<double> shapley(const std::vector<double>& v, uint32_t n) {
  check_game(v, n);
  std::vector<double> phi(n, 0.0);
  const double n_fact = factorial(n);
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t bit = 1u << i;
    for (uint32_t s = 0; s < (1u << n); ++s) {
      if (s & bit) continue;
      const uint32_t k = uint32_t(std::popcount(s));
      const double weight = factorial(k) * factorial(n - k - 1) / n_fact;
      phi[i] += weight * (v[s] - v[s | bit]);
    }
  }
  return phi;
}

CheapPair cheap_pair(const std::vector<double>& v, uint32_t n, uint32_t i) {
  check_game(v, n);
  if (i >= n) throw std::invalid_argument(fmt::format("attribution: stage {} of {}", i, n));
  const uint32_t all = (1u << n) - 1, bit = 1u << i;
  return {v[0] - v[bit], v[all & ~bit] - v[all]};
}

}  // namespace gib::attribution
