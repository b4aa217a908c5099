#include <throng/core/format.h>

#include <charconv>
#include <cmath>
#include <sstream>

namespace throng {

std::string shortest(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[64];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return error == std::errc{} ? std::string(buffer, end) : std::string("?");
}

std::string with_digits(double value, int digits) {
  std::ostringstream s;
  s.precision(digits);
  s << value;
  return s.str();
}

std::string join_words(const std::vector<std::string>& words, const std::string& separator) {
  std::string out;
  for (const std::string& w : words) out += (out.empty() ? "" : separator) + w;
  return out;
}

std::string id_list(const std::vector<std::int64_t>& ids, std::size_t most) {
  std::string out;
  for (std::size_t k = 0; k < ids.size() && k < most; ++k) out += (k ? ", " : "") + std::to_string(ids[k]);
  if (ids.size() > most) out += ", ...";
  return out;
}

}  // namespace throng
