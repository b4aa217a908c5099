// Atomic output files: write to a temporary file beside the target, rename on success.
//
// A failed or interrupted run leaves no partial output: the temporary file is removed when an AtomicOutput is
// destroyed without commit(), and on SIGINT/SIGTERM by the handler that install_interrupt_cleanup() sets up
// (the program calls it once). The target is replaced only by a complete file (rename is atomic on one file
// system), and an input is never opened for writing.
#pragma once

#include <filesystem>

namespace throng {

class AtomicOutput {
 public:
  /// Prepares to write `target`: checks its folder exists and is writable (IoError otherwise) and picks a
  /// temporary name in that folder. Nothing is created yet.
  explicit AtomicOutput(std::filesystem::path target);
  ~AtomicOutput();
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;

  /// Where to write the data now.
  [[nodiscard]] const std::filesystem::path& temporary() const noexcept { return temporary_; }
  [[nodiscard]] const std::filesystem::path& target() const noexcept { return target_; }

  /// Renames the temporary file onto the target. Throws IoError if that fails (the temporary is then removed).
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path temporary_;
  int slot_ = -1;
  bool committed_ = false;
};

/// Installs SIGINT/SIGTERM handlers that remove every pending temporary output and exit with 128 + signal
/// (130 for Ctrl-C). Safe to call more than once.
void install_interrupt_cleanup();

/// Throws ConfigError when `output` names the same file as `input` (an input is never overwritten).
void check_distinct(const std::filesystem::path& input, const std::filesystem::path& output);

}  // namespace throng
