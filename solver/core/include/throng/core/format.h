// Numbers and lists as messages and files write them: one way to format, shared by every layer.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace throng {

/// The shortest text that reads back as the same double, fixed or scientific, whichever is shorter
/// ("10", "0.3", "1250", "1e-06", "1e+09"); "nan", "inf", "-inf" for the others.
[[nodiscard]] std::string shortest(double value);

/// `value` with `digits` significant digits ("0.123", "1.23e+04"), for measured quantities in messages.
[[nodiscard]] std::string with_digits(double value, int digits);

/// "a, b, c".
[[nodiscard]] std::string join_words(const std::vector<std::string>& words, const std::string& separator = ", ");

/// Up to `most` ids ("3, 5, 8, ..."), for messages about many agents.
[[nodiscard]] std::string id_list(const std::vector<std::int64_t>& ids, std::size_t most = 10);

}  // namespace throng
