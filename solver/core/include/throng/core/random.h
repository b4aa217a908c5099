// Seeded, portable random numbers: the same seed gives the same stream on every platform and thread count.
//
// Seeds come in from the caller (the --seed flag) and are written to the output. Parallel tasks never share
// an engine: task i draws from Rng(derive_seed(seed, i)), so results do not depend on scheduling.
#pragma once

#include <cstdint>

namespace throng {

/// A well-mixed 64-bit seed for stream `index` of `seed` (SplitMix64 of both), so nearby indices give
/// unrelated streams.
[[nodiscard]] std::uint64_t derive_seed(std::uint64_t seed, std::uint64_t index) noexcept;

/// xoshiro256** engine with portable conversions (std::uniform_real_distribution is implementation-defined,
/// so it is not used: these formulas are the contract).
class Rng {
 public:
  explicit Rng(std::uint64_t seed) noexcept;

  /// Next raw 64 bits.
  std::uint64_t next() noexcept;
  /// Uniform in [0, 1), 53 random bits.
  double uniform() noexcept;
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) noexcept { return lo + (hi - lo) * uniform(); }
  /// Uniform integer in [0, n), n > 0 (Lemire's unbiased method).
  std::uint64_t below(std::uint64_t n) noexcept;
  /// Standard normal (Box–Muller; one value per call, the pair's second value is discarded for simplicity).
  double normal() noexcept;

 private:
  std::uint64_t state_[4];
};

}  // namespace throng
