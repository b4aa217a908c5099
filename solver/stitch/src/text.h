// Numbers and lists in messages of the stitch layer.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace throng::stitch::detail {

/// Shortest text that reads back as the same double (std::to_chars: "0.3", "12", "1e-06").
[[nodiscard]] std::string number(double value);
/// "4.8 s"
[[nodiscard]] std::string seconds(double value);
/// "0, 1, 2, ..., 49" (at most 12 entries shown).
[[nodiscard]] std::string id_list(const std::vector<std::int64_t>& ids);
[[nodiscard]] std::string id_list(const std::vector<std::int32_t>& ids);

}  // namespace throng::stitch::detail
