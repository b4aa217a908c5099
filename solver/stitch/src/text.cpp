#include "text.h"

#include <charconv>
#include <system_error>

namespace throng::stitch::detail {

std::string number(double value) {
  // std::to_chars without a format: the shortest text that reads back as the same double, in fixed or
  // scientific notation, whichever is shorter ("10", "0.3", "1250", "1e-06").
  char buffer[64];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return error == std::errc{} ? std::string(buffer, end) : std::string("?");
}

std::string seconds(double value) { return number(value) + " s"; }

namespace {
template <typename T>
std::string list(const std::vector<T>& ids) {
  std::string out;
  for (std::size_t k = 0; k < ids.size(); ++k) {
    if (k == 10 && ids.size() > 12) {
      out += ", ..., " + std::to_string(ids.back());
      break;
    }
    out += (k ? ", " : "") + std::to_string(ids[k]);
  }
  return out.empty() ? "none" : out;
}
}  // namespace

std::string id_list(const std::vector<std::int64_t>& ids) { return list(ids); }
std::string id_list(const std::vector<std::int32_t>& ids) { return list(ids); }

}  // namespace throng::stitch::detail
