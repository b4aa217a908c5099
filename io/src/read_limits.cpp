#include <throng/core/errors.h>
#include <throng/io/checked_numbers.h>
#include <throng/io/read_limits.h>

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>

#include <cstdio>

namespace throng {

std::uint64_t physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long page = ::sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page <= 0) return std::uint64_t{1} << 63;
  return checked_product(static_cast<std::uint64_t>(pages), static_cast<std::uint64_t>(page)).value_or(std::uint64_t{1} << 63);
}

std::uint64_t default_memory_limit() {
  std::uint64_t limit = physical_memory_bytes();
  for (int resource : {RLIMIT_AS, RLIMIT_DATA}) {
    struct rlimit r {};
    if (::getrlimit(resource, &r) == 0 && r.rlim_cur != RLIM_INFINITY) limit = std::min<std::uint64_t>(limit, r.rlim_cur);
  }
  return limit;
}

std::string format_bytes(std::uint64_t bytes) {
  static const char* units[] = {"KB", "MB", "GB", "TB", "PB", "EB"};
  if (bytes < 1000) return std::to_string(bytes) + " bytes";
  double v = static_cast<double>(bytes) / 1000.0;
  std::size_t u = 0;
  while (v >= 1000.0 && u + 1 < sizeof units / sizeof units[0]) {
    v /= 1000.0;
    ++u;
  }
  char text[32];
  std::snprintf(text, sizeof text, v < 10 ? "%.1f %s" : "%.0f %s", v, units[u]);
  return text;
}

namespace {

[[noreturn]] void refuse(std::uint64_t bytes, std::uint64_t used, std::uint64_t limit, const std::string& what, const std::string& detail) {
  std::string message = what + ": reading it needs about " + format_bytes(bytes);
  if (!detail.empty()) message += " (" + detail + ")";
  if (used > 0) message += " on top of " + format_bytes(used) + " already read";
  message += ", more than the memory limit of " + format_bytes(limit) + "; refused before reading";
  throw InputError(message);
}

}  // namespace

void MemoryBudget::charge(std::uint64_t bytes, const std::string& what, const std::string& detail) {
  require(bytes, what, detail);
  used_ += bytes;
}

void MemoryBudget::require(std::uint64_t bytes, const std::string& what, const std::string& detail) const {
  const auto total = checked_sum(used_, bytes);
  if (!total || *total > limit_) refuse(bytes, used_, limit_, what, detail);
}

}  // namespace throng
