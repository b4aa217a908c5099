// Starting a helper program (no shell) with its standard streams on chosen descriptors, and scratch files that
// vanish by themselves: what the picture writers need to drive rsvg-convert and ffmpeg without leaving files
// behind.
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace throng {

/// A program started with stdin, stdout and stderr on the given descriptors (dup'ed into the child; descriptors
/// opened with O_CLOEXEC elsewhere stay closed in it). The destructor waits for a program not yet waited for, so
/// none is left behind as a zombie.
class SpawnedProgram {
 public:
  /// Starts argv[0], found on PATH. started() is false when it could not be started (not installed).
  SpawnedProgram(const std::vector<std::string>& argv, int in, int out, int err);
  ~SpawnedProgram();
  SpawnedProgram(const SpawnedProgram&) = delete;
  SpawnedProgram& operator=(const SpawnedProgram&) = delete;

  [[nodiscard]] bool started() const noexcept { return pid_ > 0; }
  /// Waits for the program to end: its exit status, 128 + the signal that ended it, −1 if it never started.
  int wait();

 private:
  pid_t pid_ = -1;
  int status_ = -1;
};

/// A file with no name (created in $TMPDIR or /tmp and unlinked at once), open for reading and writing with
/// O_CLOEXEC: a program's input or output that disappears when closed, whatever happens.
class ScratchFile {
 public:
  /// IoError when no scratch file can be created.
  ScratchFile();
  ~ScratchFile();
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;

  [[nodiscard]] int descriptor() const noexcept { return fd_; }
  /// Replaces the content with `bytes` and rewinds. IoError on failure.
  void assign(const std::string& bytes);
  /// The whole content (at most `limit` bytes: the last ones when longer), read from the start. IoError on failure.
  [[nodiscard]] std::string content(std::size_t limit = static_cast<std::size_t>(-1)) const;
  /// Empties the file and rewinds (before a program writes into it).
  void clear();
  /// Moves to the start (before a program reads what another wrote). IoError on failure.
  void rewind();

 private:
  int fd_ = -1;
};

/// Writes all of `size` bytes to the pipe `fd`. False when the reader is gone (EPIPE: the program ended early);
/// SIGPIPE is held back meanwhile, so a program that stops reading fails the write instead of ending this process.
bool write_to_pipe(int fd, const void* data, std::size_t size);

}  // namespace throng
