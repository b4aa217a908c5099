// Arithmetic on numbers that come from files: products of sizes that report overflow instead of wrapping, and
// conversions of a parsed double to an integer that refuse what the integer cannot hold.
#pragma once

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <span>

namespace throng {

/// a · b, or nullopt when the product does not fit in 64 bits.
[[nodiscard]] inline std::optional<std::uint64_t> checked_product(std::uint64_t a, std::uint64_t b) {
  std::uint64_t out = 0;
  if (__builtin_mul_overflow(a, b, &out)) return std::nullopt;
  return out;
}

/// The product of every factor (1 for none), or nullopt when it does not fit in 64 bits. A zero factor makes
/// the product 0 even when the others would overflow (an empty dataset holds nothing, whatever its other sides).
[[nodiscard]] inline std::optional<std::uint64_t> checked_product(std::span<const std::uint64_t> factors) {
  for (std::uint64_t f : factors) {
    if (f == 0) return 0;
  }
  std::uint64_t out = 1;
  for (std::uint64_t f : factors) {
    if (__builtin_mul_overflow(out, f, &out)) return std::nullopt;
  }
  return out;
}
[[nodiscard]] inline std::optional<std::uint64_t> checked_product(std::initializer_list<std::uint64_t> factors) {
  return checked_product(std::span<const std::uint64_t>(factors.begin(), factors.size()));
}

/// a + b, or nullopt on overflow.
[[nodiscard]] inline std::optional<std::uint64_t> checked_sum(std::uint64_t a, std::uint64_t b) {
  std::uint64_t out = 0;
  if (__builtin_add_overflow(a, b, &out)) return std::nullopt;
  return out;
}

/// Largest whole number a double holds exactly together with every smaller one: 2^53. Counts and frame numbers
/// read as doubles beyond it are not whole numbers any more (neighbours round to the same value).
inline constexpr double largest_exact_integer = 9007199254740992.0;

/// `v` as an integer when it is a whole number in [lo, hi] (and |v| ≤ 2^53), else nullopt: NaN, infinities,
/// fractions and values out of range are refused instead of being converted (a cast would be undefined or wrap).
[[nodiscard]] inline std::optional<std::int64_t> whole_number_in(double v, std::int64_t lo, std::int64_t hi) {
  if (!std::isfinite(v) || v != std::floor(v) || std::fabs(v) > largest_exact_integer) return std::nullopt;
  const auto i = static_cast<std::int64_t>(v);  // exact: |v| ≤ 2^53
  if (i < lo || i > hi) return std::nullopt;
  return i;
}

}  // namespace throng
