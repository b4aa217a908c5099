// The file driver every HDF5 file throng creates is written through: libhdf5's POSIX driver (sec2), except that
// large blocks of raw data go straight to the disk (O_DIRECT) instead of through the page cache.
//
// Why: every throng output is flushed to disk before it replaces the last copy (atomic_output.h), so the page
// cache only adds the kernel's copy of each byte into pages that must be found, filled and written back before
// the flush returns. At 1,000,000 agents that copy, on the one thread that writes the pipeline's compressed
// chunks (filtered_chunks.h), was 1.77 s of the 2.9 s the command spent writing (perf), and on this virtual machine
// new page-cache pages cost a first touch of guest memory each: `dd` of 1.3 GB in 8 MiB blocks, flushed, took
// 1.85-9.98 s (0.73-4.98 s of system time) through the page cache and 0.69-0.88 s (0.09 s) with O_DIRECT.
//
// The contract (the file is byte for byte the one sec2 writes with the same alignment): a raw-data write of at
// least direct_write_minimum bytes whose buffer and file address agree modulo direct_write_block writes its
// whole blocks with O_DIRECT and its unaligned head and tail through the page cache; every other write, every
// read, and every write on a file system that refuses O_DIRECT (tmpfs before Linux 6.6, some network file
// systems: the open fails, or the first direct write with EINVAL) goes through the page cache as in sec2. Smaller
// raw-data writes that follow one another in the file are gathered (up to 4 MiB) and written with one call when
// the run ends: when a small raw-data write does not continue it, any write or read meets it, or libhdf5 flushes,
// truncates or closes the file.
// The file's chunk allocations of at least direct_write_minimum bytes are aligned to direct_write_block
// (H5Pset_alignment), so a chunk compressed into an aligned buffer (filtered_chunks.cpp) goes straight through.
// The file's bytes are right whichever way each write went: Linux writes back and drops the cached pages a direct
// write overlaps. No driver information is stored in the file: any HDF5 reader opens it with its default driver.
// Unlike sec2, the driver takes no flock on the file (throng's outputs are new temporary files, atomic_output.h).
#pragma once

#include <hdf5.h>

#include <cstddef>
#include <memory>
#include <new>

namespace throng::h5::detail {

/// The O_DIRECT block: file offsets, lengths and buffer addresses of direct writes are multiples of it (4 KiB,
/// the page size and the largest logical block size of the disks throng writes to).
constexpr std::size_t direct_write_block = 4096;

/// Raw-data writes below this size go through the page cache, and allocations below it are not aligned (it wastes
/// 2 KB a chunk on average). Measured on `throng sketch` (bench_sketch_command, mode 1): with a minimum of 64 KiB,
/// 100,000 agents' chunks (about 400 KB compressed) went direct and the command took 580-711 ms against 548-654
/// through the page cache, whose pages the command's earlier files had left ready; 1,000,000 agents' (4 MB) gained.
constexpr std::size_t direct_write_minimum = 1024 * 1024;

/// `bytes` uninitialised bytes aligned to direct_write_block: a buffer a raw-data write goes straight to the disk from.
struct AlignedDelete {
  void operator()(unsigned char* p) const noexcept { ::operator delete[](p, std::align_val_t{direct_write_block}); }
};
using AlignedBytes = std::unique_ptr<unsigned char[], AlignedDelete>;
[[nodiscard]] inline AlignedBytes aligned_bytes(std::size_t bytes) {
  return AlignedBytes(static_cast<unsigned char*>(::operator new[](bytes, std::align_val_t{direct_write_block})));
}

/// Sets `file_access` (a file access property list) to the driver above, with the alignment it needs. `direct`
/// false writes everything through the page cache, as on a file system that refuses O_DIRECT (the tests' way to
/// take that path). IoError when libhdf5 refuses the driver.
void use_direct_write_driver(hid_t file_access, bool direct = true);

/// How many bytes the driver wrote with O_DIRECT in this process (a test's way to see the path was taken).
[[nodiscard]] std::size_t direct_write_bytes();

/// How many runs of staged raw-data writes the driver has written in this process, one call each (a test's way to
/// see small writes that follow one another gathered).
[[nodiscard]] std::size_t staged_runs_written();

}  // namespace throng::h5::detail
