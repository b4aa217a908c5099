// Half-precision numbers as USD's quath holds them, written as text (detail::put_number's shortest float form of
// the half's exact value, so a reader's half parse gives it back unchanged).
#pragma once

#include <cstddef>

namespace throng::detail {

/// The value a quath stores for v: the nearest half-precision number, ties to even (±infinity from 65520 up, NaN
/// kept), as a float (every half is one exactly).
[[nodiscard]] float as_half(double v);

/// Writes as_half(v) at `out` (room for max_number_chars) as put_number writes that float, and returns the end.
/// Halves of magnitude up to 1 (every quaternion component) come from a table of their texts made once, the
/// rest from put_number: the same characters either way.
char* put_half(char* out, double v);

}  // namespace throng::detail
