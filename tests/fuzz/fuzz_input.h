// Shared by the fuzz targets: the input bytes as a file a reader can open, and the limits the readers run with.
//
// The fuzz criterion (issue 18): no input of at most 1 MB makes a reader use more than 2 GB or run past 20 s
// without first refusing with an estimate. The fuzzers run with -rss_limit_mb=2048 -malloc_limit_mb=2048
// -timeout=20 (scripts/run-fuzzers); the readers get 1 GiB, leaving room for the sanitizers' own memory and
// for what a reader holds besides its arrays.
#pragma once

#include <throng/core/errors.h>
#include <throng/io/read_limits.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace throng::fuzz {

inline ReadLimits fuzz_limits() { return ReadLimits{std::uint64_t{1} << 30}; }

/// The bytes as a file a reader opens by name: one file per process in a fresh temporary folder, rewritten for
/// each input. (Not a memfd: libhdf5 resolves a file's real path when it opens it, and /proc/self/fd/N of a memfd
/// has none, so every HDF5 input would fail before the reader saw it.)
class InputFile {
 public:
  InputFile(const std::uint8_t* data, std::size_t size) {
    std::FILE* out = std::fopen(path().c_str(), "wb");
    if (!out || (size > 0 && std::fwrite(data, 1, size, out) != size) || std::fclose(out) != 0) std::abort();
  }
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;
  [[nodiscard]] static const std::filesystem::path& path() {
    static const std::filesystem::path file = [] {
      std::string pattern = (std::filesystem::temp_directory_path() / "throng-fuzz-XXXXXX").string();
      if (!::mkdtemp(pattern.data())) std::abort();
      return std::filesystem::path(pattern) / "input";
    }();
    return file;
  }
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
