// A crash inside libhdf5 while it reads an input file, reported as a damaged input instead of a segmentation fault.
//
// Debian 12's libhdf5 1.10.8 trusts sizes and indices of damaged files in places its API cannot show us before
// the call (a global heap object index past its collection, a local heap's data size, a compact dataset's
// buffer): a crafted file can make it read through a wild pointer, and the program died with "Segmentation
// fault" (exit 139) and left a core. throng checks what it can first (hdf5.h: bounds, heaps, layouts, filters);
// for the rest, while a ReadingInput lives, a fault (SIGSEGV, SIGBUS, SIGFPE, SIGILL) removes every pending
// temporary output (atomic_output.h), prints a message naming the file, and exits with 3 (invalid input data).
// A fault while no input is being read removes the pending outputs and then takes its default action (a core,
// 128 + signal): a defect of throng is not dressed up as a damaged file. The handler only writes, unlinks and exits
// (async-signal-safe); its message is made when the ReadingInput is.
#pragma once

#include <filesystem>

namespace throng {

/// Installs the fault handlers above (the program calls it once, after install_interrupt_cleanup). Not for
/// processes under a sanitizer or a fuzzer, which report faults themselves.
void install_input_crash_report();

/// Marks `path` as being read (by libhdf5) for as long as it lives. Up to 8 at once; more are not reported.
class ReadingInput {
 public:
  explicit ReadingInput(const std::filesystem::path& path);
  ReadingInput(const ReadingInput&) = delete;
  ReadingInput& operator=(const ReadingInput&) = delete;
  ~ReadingInput();

 private:
  int slot_ = -1;
};

}  // namespace throng
