#include "output_file.h"

#include <throng/core/errors.h>

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <string>
#include <unistd.h>

namespace throng::detail {

OutputFile::OutputFile(std::filesystem::path target) : output_(std::move(target)) {
  fd_ = ::open(output_.temporary().c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) throw IoError(output_.target().string() + ": cannot be created (" + std::strerror(errno) + ")");
}

OutputFile::~OutputFile() {
  if (fd_ >= 0) ::close(fd_);
}

void OutputFile::write(const void* data, std::size_t size) {
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd_, p, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw IoError(output_.target().string() + ": write failed (" + std::strerror(errno) + "; is the disk full?)");
    p += n;
    size -= static_cast<std::size_t>(n);
  }
}

void OutputFile::commit() {
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) throw IoError(output_.target().string() + ": write failed on close (" + std::strerror(errno) + ")");
  output_.commit();
}

}  // namespace throng::detail
