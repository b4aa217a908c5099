// An export's output file: written through an AtomicOutput (a temporary beside the target, flushed to disk and
// renamed on commit; nothing is left behind on failure or interrupt).
//
// The bytes are gathered into a staging buffer of stage_bytes and written a full buffer at a time, straight to
// the disk (O_DIRECT) where the file system allows it: commit flushes the file to disk anyway, so going through
// the page cache would only add the kernel's copy of every byte (on the development machine that copy cost more
// CPU than formatting a binary format's data) and leave commit's flush the whole file to wait for. The tail
// short of a full buffer, and every write on a file system that refuses O_DIRECT, go through the page cache,
// whose writeback is started every stage_bytes so commit waits for the last stretch only. Small files (under
// stage_bytes) are one ordinary write at commit, from a buffer no larger than they are (to within twice).
#pragma once

#include <throng/io/atomic_output.h>

#include <cstddef>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string_view>

namespace throng::detail {

class OutputFile {
 public:
  /// Whether full buffers may go straight to the disk: when_allowed (the exports), or never (every byte through
  /// the page cache: the path a file system that refuses O_DIRECT takes, chosen by the tests to check it).
  enum class Direct { when_allowed, never };

  /// Checks the target's folder exists and is writable (IoError otherwise) and creates the temporary file.
  explicit OutputFile(std::filesystem::path target, Direct direct = Direct::when_allowed);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  /// Appends bytes; IoError naming the target on failure (a full disk shows here or at commit). Calls may come
  /// from different threads, one at a time.
  void write(const void* data, std::size_t size);
  void write(std::string_view text) { write(text.data(), text.size()); }
  /// Writes what is staged, closes the temporary, flushes it to disk and renames it onto the target.
  void commit();
  [[nodiscard]] const std::filesystem::path& target() const noexcept { return output_.target(); }
  /// Bytes written straight to the disk so far (0 for a small file, Direct::never, or a file system that refuses).
  [[nodiscard]] std::size_t direct_bytes() const noexcept { return direct_bytes_; }

  /// The staging buffer's size: a multiple of every block size O_DIRECT asks (512 or 4,096 bytes), and so is every
  /// offset a full buffer is written at. A write() that fills it waits for the disk to take it all (8 ms or more
  /// here): a caller that makes its bytes on other threads keeps them busy meanwhile with that much buffered.
  static constexpr std::size_t stage_bytes = 8 << 20;

 private:
  static constexpr std::size_t stage_alignment = 4096;

  // Makes the staging buffer hold at least `needed` bytes (up to stage_bytes), keeping what it holds: it starts
  // at 64 KiB and doubles, so a small file never holds the full buffer.
  void grow_stage(std::size_t needed);
  // Writes the full staging buffer (directly where allowed) and empties it.
  void write_stage();
  // Writes bytes through the page cache, all of them (EINTR and short writes retried).
  void write_all(const char* data, std::size_t size);
  [[nodiscard]] bool set_direct(bool on);

  struct FreeAligned {
    void operator()(char* p) const noexcept { std::free(p); }
  };

  AtomicOutput output_;
  int fd_ = -1;
  std::unique_ptr<char, FreeAligned> stage_;  // stage_capacity_ bytes, aligned to stage_alignment
  std::size_t stage_capacity_ = 0, staged_ = 0;  // its size (at most stage_bytes) and the bytes it holds
  std::size_t written_ = 0, written_back_ = 0;  // bytes written to the file; bytes whose writeback was started
  std::size_t direct_bytes_ = 0;                // of written_, those written with O_DIRECT
  bool direct_allowed_ = true;                  // false for Direct::never, or once the file system refused O_DIRECT
};

}  // namespace throng::detail
