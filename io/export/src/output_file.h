// An export's output file: written through an AtomicOutput (a temporary beside the target, renamed on commit;
// nothing is left behind on failure or interrupt) with plain large writes, so a stream of chunks costs what
// writing the bytes costs.
#pragma once

#include <throng/io/atomic_output.h>

#include <cstddef>
#include <filesystem>
#include <string_view>

namespace throng::detail {

class OutputFile {
 public:
  /// Checks the target's folder exists and is writable (IoError otherwise) and creates the temporary file.
  explicit OutputFile(std::filesystem::path target);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  /// Appends bytes; IoError naming the target on failure (a full disk shows here).
  void write(const void* data, std::size_t size);
  void write(std::string_view text) { write(text.data(), text.size()); }
  /// Closes the temporary and renames it onto the target.
  void commit();
  [[nodiscard]] const std::filesystem::path& target() const noexcept { return output_.target(); }

 private:
  AtomicOutput output_;
  int fd_ = -1;
};

}  // namespace throng::detail
