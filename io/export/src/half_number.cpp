#include "half_number.h"

#include "text_numbers.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

namespace throng::detail {

// The value a quath stores: the nearest half-precision number, ties to even (written as text of that exact value,
// so a reader's half parse gives it back unchanged). Computed, not cast through _Float16, which clang 14 does not
// support on x86-64 (the asan preset builds with it): 11 significant bits above 2^-14, steps of 2^-24 below, and
// infinity from 65520 up (it rounds past the largest half, 65504). Agreed with GCC's _Float16 cast on 7.5 million
// values (every half, its neighbours and the midpoints between halves among them).
float as_half(double v) {
  if (!std::isfinite(v)) return static_cast<float>(v);
  const double magnitude = std::fabs(v);
  if (magnitude >= 65520.0) return static_cast<float>(std::copysign(HUGE_VAL, v));
  if (magnitude >= 0x1p-14) {
    // A normal half: keep 11 significant bits of the double's 53, rounding the 42 dropped bits to nearest, ties
    // to even (a carry into the exponent is the right result too). The same value as the general path below,
    // without its frexp, ldexp and nearbyint (four values per agent and frame).
    std::uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    constexpr std::uint64_t dropped = (std::uint64_t{1} << 42) - 1;
    bits += (dropped >> 1) + ((bits >> 42) & 1);
    bits &= ~dropped;
    double rounded;
    std::memcpy(&rounded, &bits, sizeof rounded);
    return static_cast<float>(rounded);
  }
  int exponent = 0;
  (void)std::frexp(magnitude, &exponent);  // magnitude = m · 2^exponent, m in [0.5, 1)
  const double step = std::ldexp(1.0, std::max(exponent, -13) - 11);
  return static_cast<float>(std::copysign(std::nearbyint(magnitude / step) * step, v));
}

namespace {

// The texts of the halves in [2^-24, 1]: a float of one of them has a biased exponent 103 (2^-24, the least
// subnormal half) to 127 (1) and at most the top 10 of its 23 mantissa bits set, so (exponent − 103, those 10
// bits) indexes them.
constexpr std::uint32_t least_exponent = 103, exponents = 25;

struct HalfText {
  std::array<char, 15> chars;
  std::uint8_t size;
};

const std::vector<HalfText>& half_texts() {
  static const std::vector<HalfText> table = [] {
    std::vector<HalfText> t(exponents << 10);
    for (std::uint32_t k = 0; k < t.size(); ++k) {
      const std::uint32_t bits = ((least_exponent + (k >> 10)) << 23) | ((k & 1023) << 13);
      float value;
      std::memcpy(&value, &bits, sizeof value);
      char text[max_number_chars];
      const std::size_t size = static_cast<std::size_t>(put_number(text, value) - text);
      t[k].size = static_cast<std::uint8_t>(std::min(size, t[k].chars.size()));  // every one fits: at most 13
      std::memcpy(t[k].chars.data(), text, t[k].size);
    }
    return t;
  }();
  return table;
}

}  // namespace

char* put_half(char* out, double v) {
  if (v == 0) return put_number(out, static_cast<float>(v));  // ±0 (a derived facing's x and y): no rounding to do
  const float h = as_half(v);
  const float magnitude = std::fabs(h);
  if (!(magnitude <= 1.0f) || magnitude == 0.0f) return put_number(out, h);
  static const std::vector<HalfText>& table = half_texts();
  std::uint32_t bits;
  std::memcpy(&bits, &magnitude, sizeof bits);
  const HalfText& text = table[(((bits >> 23) - least_exponent) << 10) | ((bits >> 13) & 1023)];
  if (std::signbit(h)) *out++ = '-';
  // All 16 bytes of the entry in one fixed-size copy (the caller's room is max_number_chars), then the text's end:
  // a copy of the text's own length is a call per value.
  static_assert(sizeof(HalfText) == 16 && max_number_chars >= 17);
  std::memcpy(out, &text, sizeof text);
  return out + text.size;
}

}  // namespace throng::detail
