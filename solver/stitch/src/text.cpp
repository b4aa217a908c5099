#include "text.h"

#include <cstdio>
#include <cstdlib>

namespace throng::stitch::detail {

std::string number(double value) {
  char buffer[32];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
    if (std::strtod(buffer, nullptr) == value) break;
  }
  return buffer;
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
