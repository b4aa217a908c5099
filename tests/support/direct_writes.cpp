#include "direct_writes.h"

#include <fcntl.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>

namespace throng::test {

bool takes_direct_writes(const std::filesystem::path& folder) {
  constexpr std::size_t block = 4096;
  const auto probe = folder / "direct_probe";
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_DIRECT | O_CLOEXEC, 0644);
  bool written = false;
  if (fd >= 0) {
    void* bytes = nullptr;
    if (::posix_memalign(&bytes, block, block) == 0) {
      std::memset(bytes, 7, block);
      written = ::pwrite(fd, bytes, block, 0) == static_cast<ssize_t>(block);
      std::free(bytes);
    }
    ::close(fd);
  }
  std::filesystem::remove(probe);
  return written;
}

}  // namespace throng::test
