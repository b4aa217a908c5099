#include "output_file.h"

#include <throng/core/errors.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <string>
#include <unistd.h>

namespace throng::detail {

OutputFile::OutputFile(std::filesystem::path target, Direct direct)
    : output_(std::move(target)), direct_allowed_(direct == Direct::when_allowed) {
  fd_ = ::open(output_.temporary().c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) throw IoError(output_.target().string() + ": cannot be created (" + std::strerror(errno) + ")");
}

OutputFile::~OutputFile() {
  if (fd_ >= 0) ::close(fd_);
}

void OutputFile::write(const void* data, std::size_t size) {
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    if (staged_ + size > stage_capacity_ && stage_capacity_ < stage_bytes) grow_stage(staged_ + size);
    const std::size_t take = std::min(size, stage_bytes - staged_);
    std::memcpy(stage_.get() + staged_, p, take);
    staged_ += take;
    p += take;
    size -= take;
    if (staged_ == stage_bytes) write_stage();
  }
}

void OutputFile::grow_stage(std::size_t needed) {
  std::size_t capacity = std::max<std::size_t>(stage_capacity_, 64 << 10);
  while (capacity < needed && capacity < stage_bytes) capacity *= 2;
  capacity = std::min(capacity, stage_bytes);
  std::unique_ptr<char, FreeAligned> stage(static_cast<char*>(std::aligned_alloc(stage_alignment, capacity)));
  if (!stage) throw IoError(output_.target().string() + ": no memory for the write buffer");
  if (staged_) std::memcpy(stage.get(), stage_.get(), staged_);
  stage_ = std::move(stage);
  stage_capacity_ = capacity;
}

bool OutputFile::set_direct(bool on) {
  const int flags = ::fcntl(fd_, F_GETFL);
  return flags >= 0 && ::fcntl(fd_, F_SETFL, on ? flags | O_DIRECT : flags & ~O_DIRECT) == 0;
}

void OutputFile::write_stage() {
  // A full buffer at an offset that is a multiple of stage_bytes: what O_DIRECT asks. A file system that refuses
  // it (tmpfs before Linux 6.6, some FUSE and network file systems) refuses at fcntl or at the first write, with
  // EINVAL; from then on this file goes through the page cache.
  if (direct_allowed_ && set_direct(true)) {
    const ssize_t n = ::write(fd_, stage_.get(), stage_bytes);
    if (n == static_cast<ssize_t>(stage_bytes)) {
      written_ += stage_bytes;
      direct_bytes_ += stage_bytes;
      written_back_ = written_;
      staged_ = 0;
      return;
    }
    if (n >= 0 || errno != EINVAL) {
      // A short direct write (the disk filled) or an error other than a refusal: the rest through the page cache,
      // which reports the error plainly.
      const std::size_t done = n > 0 ? static_cast<std::size_t>(n) : 0;
      direct_bytes_ += done;
      direct_allowed_ = false;
      (void)set_direct(false);  // if it stays on, the unaligned writes below fail and say so
      written_ += done;
      write_all(stage_.get() + done, stage_bytes - done);
      staged_ = 0;
      return;
    }
  }
  direct_allowed_ = false;
  if (!set_direct(false)) throw IoError(output_.target().string() + ": cannot switch off direct writes (" + std::strerror(errno) + ")");
  write_all(stage_.get(), stage_bytes);
  staged_ = 0;
}

void OutputFile::write_all(const char* p, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd_, p, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw IoError(output_.target().string() + ": write failed (" + std::strerror(errno) + "; is the disk full?)");
    p += n;
    size -= static_cast<std::size_t>(n);
    written_ += static_cast<std::size_t>(n);
  }
  if (written_ - written_back_ >= stage_bytes) {
    // Only a start (the pages are queued for the disk, this does not wait for them): commit's fsync still makes
    // the file durable and reports any error, so a file system without sync_file_range loses only the overlap.
    ::sync_file_range(fd_, static_cast<off64_t>(written_back_), static_cast<off64_t>(written_ - written_back_), SYNC_FILE_RANGE_WRITE);
    written_back_ = written_;
  }
}

void OutputFile::commit() {
  if (staged_ > 0) {
    // The tail, short of a full buffer (and of O_DIRECT's block multiple): through the page cache.
    if (!set_direct(false)) throw IoError(output_.target().string() + ": cannot switch off direct writes (" + std::strerror(errno) + ")");
    write_all(stage_.get(), staged_);
    staged_ = 0;
  }
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) throw IoError(output_.target().string() + ": write failed on close (" + std::strerror(errno) + ")");
  output_.commit();
}

}  // namespace throng::detail
