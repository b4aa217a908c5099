// A crash inside libhdf5 while it reads an input file, reported as a damaged input instead of a segmentation fault.
//
// libhdf5 1.10.8 (Debian 12's) trusts sizes and indices of damaged files in places its API cannot show us before
// the call (a global heap object index past its collection, a local heap's data size, a compact dataset's
// buffer): a crafted file can make it read through a wild pointer, and the program died with "Segmentation
// fault" (exit 139) and left a core. throng checks what it can first (hdf5.h: bounds, heaps, layouts, filters).
// For the rest, install_input_crash_report() handles SIGSEGV, SIGBUS, SIGFPE and SIGILL:
//  - a fault raised by the processor (not a signal sent with kill) at an instruction of libhdf5, of the C
//    library (where libhdf5's copies run) or of ISA-L (which inflates libhdf5's chunks) while a ReadingInput lives: every pending temporary output is removed
//    (atomic_output.h), a message naming the input opened last is printed, and the program exits 3 (invalid
//    input data);
//  - anything else (a fault in throng's own code, a signal sent by another process): the pending outputs are
//    removed and the signal takes its default action (a core, 128 + signal), so a defect of throng is not dressed
//    up as a damaged file.
// The main thread's handler runs on a stack of its own, so a stack overflow there is handled too. A heap
// corruption libhdf5 leaves for glibc to find ends in abort(): install_interrupt_cleanup's handler removes the
// pending outputs and exits 134. The handler only writes, unlinks, resets and exits (async-signal-safe); its
// message is made when the ReadingInput is. Not installed under AddressSanitizer, which reports faults itself.
#pragma once

#include <filesystem>

namespace throng {

/// Installs the fault handlers above (the program calls it once, after install_interrupt_cleanup). Does nothing
/// in a build under AddressSanitizer.
void install_input_crash_report();

namespace detail {
/// The handlers of install_input_crash_report(), installed in any build (its tests run under the sanitizers too).
void install_input_crash_handlers();
}  // namespace detail

/// Marks `path` as being read by libhdf5 for as long as it lives (h5::File::open and open_for_update hold one).
/// Up to 8 at once; more are not reported.
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
