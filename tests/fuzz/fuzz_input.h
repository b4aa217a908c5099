// Shared by the fuzz targets: the input bytes as a file a reader can open, and the limits the readers run with.
//
// The fuzz criterion (issue 18): no input of at most 1 MB makes a reader use more than 2 GB or run past 20 s
// without first refusing with an estimate. The fuzzers run with -rss_limit_mb=2048 -malloc_limit_mb=2048
// -timeout=20 (scripts/run-fuzzers); the readers get 1 GiB, leaving room for the sanitizers' own memory and
// for what a reader holds besides its arrays.
#pragma once

#include <throng/core/errors.h>
#include <throng/io/read_limits.h>

#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace throng::fuzz {

inline ReadLimits fuzz_limits() { return ReadLimits{std::uint64_t{1} << 30}; }

/// The bytes as an anonymous in-memory file (memfd), named /proc/self/fd/N for readers that open by name.
class InputFile {
 public:
  InputFile(const std::uint8_t* data, std::size_t size) : fd_(::memfd_create("fuzz-input", MFD_CLOEXEC)) {
    if (fd_ < 0) std::abort();
    for (std::size_t done = 0; done < size;) {
      const ssize_t n = ::write(fd_, data + done, size - done);
      if (n <= 0) std::abort();
      done += static_cast<std::size_t>(n);
    }
  }
  ~InputFile() { ::close(fd_); }
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;
  [[nodiscard]] std::filesystem::path path() const { return "/proc/self/fd/" + std::to_string(fd_); }

 private:
  int fd_;
};

/// Runs a reader: a throng::Error (bad input refused with a message) is the expected outcome for most inputs;
/// anything else (another exception, a crash, a sanitizer report, a hang, too much memory) is a finding.
template <class Reader>
void expect_only_throng_errors(Reader&& read) {
  try {
    read();
  } catch (const throng::Error&) {
  }
}

}  // namespace throng::fuzz
