// HDF5's deflate filter (filter 1), decoded with ISA-L's inflate instead of zlib's, for every file this process
// reads.
//
// Why: reading a crowd is mostly inflating its chunks, and libhdf5 inflates with zlib (bench/export `read_crowd`,
// 10,000 agents × 1,000 frames, 133 MB: zlib's inflate and Adler-32 were the largest part of the 1.36 s). ISA-L
// (already throng's deflater, chunk_deflate.h) inflates the same streams several times faster.
//
// The contract: the filter replaces libhdf5's own for this process (registered with libhdf5's internal
// H5Z_register under the same id, libhdf5 1.10 only), and does what libhdf5 1.10's did, byte for byte where bytes
// are made. Decoding: a zlib stream (header, deflate blocks, Adler-32 checked). Where the reader says what one chunk
// decodes to (DecodedChunkBytes, set by hdf5.cpp around each read), the stream is inflated into one buffer of that
// size and fails if it would inflate beyond it, so a hostile stream cannot make the filter allocate more than the
// read budget allows; elsewhere into a buffer that starts at twice the stored size and doubles when full, up to
// 4 GiB. A stream that is damaged, ends early, needs a preset dictionary or has a wrong checksum fails the read, as
// with zlib (libhdf5 reports the dataset unreadable, and throng's readers say which file); ISA-L accepts a few
// headers zlib refuses (a window field above 32 KiB), which decode the same. Encoding (a dataset libhdf5
// compresses itself, such as a small dataset written with H5Dwrite): zlib's compress2 at the dataset's level into
// at most ⌈1.001 n⌉ + 12 bytes, failing (libhdf5 then stores the chunk unfiltered, the filter being optional) where
// that is too small: the bytes libhdf5 1.10.8 writes.
#pragma once

#include <cstddef>
#include <cstdint>

namespace throng::h5::detail {

/// Registers the filter above once for the process (later calls do nothing). IoError when libhdf5 refuses it.
void use_isal_inflate();

/// While alive, the bytes one chunk decodes to for the deflate filter on this thread (the chunk's elements times
/// their size in the file: with deflate, shuffle and fletcher32 only, what deflate inflates an honest chunk to);
/// 0: not known. Restores the previous value when destroyed.
class DecodedChunkBytes {
 public:
  explicit DecodedChunkBytes(std::uint64_t bytes) noexcept;
  ~DecodedChunkBytes();
  DecodedChunkBytes(const DecodedChunkBytes&) = delete;
  DecodedChunkBytes& operator=(const DecodedChunkBytes&) = delete;

 private:
  std::uint64_t previous_;
};

/// How many chunks this process has inflated through the filter (a test's way to see which filter ran).
[[nodiscard]] std::size_t isal_inflated_chunks();

}  // namespace throng::h5::detail
