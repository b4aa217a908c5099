#include "address_space_cap.h"

#include <sys/resource.h>
#include <unistd.h>

#include <fstream>

namespace throng::h5 {
namespace {

// The address space in use now (bytes), from /proc/self/statm's first field; 0 when it cannot be read.
std::uint64_t address_space_in_use() {
  std::ifstream statm("/proc/self/statm");
  std::uint64_t pages = 0;
  if (!(statm >> pages)) return 0;
  const long page = sysconf(_SC_PAGESIZE);
  return page > 0 ? pages * static_cast<std::uint64_t>(page) : 0;
}

}  // namespace

AddressSpaceCap::AddressSpaceCap(std::uint64_t allowance_bytes) {
  const std::uint64_t in_use = address_space_in_use();
  rlimit limit{};
  if (in_use == 0 || getrlimit(RLIMIT_AS, &limit) != 0) return;
  const std::uint64_t cap = in_use + allowance_bytes < in_use ? RLIM_INFINITY : in_use + allowance_bytes;
  if (limit.rlim_cur != RLIM_INFINITY && limit.rlim_cur <= cap) return;
  previous_soft_ = limit.rlim_cur;
  limit.rlim_cur = cap;
  capped_ = setrlimit(RLIMIT_AS, &limit) == 0;
}

AddressSpaceCap::~AddressSpaceCap() {
  if (!capped_) return;
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) != 0) return;
  limit.rlim_cur = previous_soft_;
  setrlimit(RLIMIT_AS, &limit);
}

}  // namespace throng::h5
