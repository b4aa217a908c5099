// One chunk's zlib stream, as HDF5's deflate filter stores it, made by ISA-L (Intel's igzip) with the byte planes
// that are noise stored instead of searched.
//
// The shuffle filter leaves a chunk of n elements of E bytes as E byte planes of n bytes (byte j of every element
// together). In a crowd's trajectories the high planes of a float64 (sign, exponent, the leading mantissa bits)
// compress well and the low ones are noise: on a 10,000-agent sketch's x positions zlib keeps 100 % of planes 0-5,
// 32 % of plane 6 and 1 % of plane 7. ISA-L searched the noise for matches all the same, and a deflate stream may
// mix stored blocks with compressed ones (RFC 1951, 3.2.3): so the planes that look like noise go in as stored
// blocks (a copy) and ISA-L compresses the runs of other planes, each run's blocks ending on a byte boundary (its
// FULL_FLUSH) so that the next run's blocks follow. On that sketch's frames a chunk of x positions took 47 instead of
// 78 µs and 4 % fewer bytes (the structured planes get Huffman codes of their own); chunks without noise (the
// constant z of a position) are deflated whole, as before.
//
// The stream depends on the chunk's bytes alone (which planes are stored is decided from them), so a file's bytes
// do not depend on the thread count; zlib, and so every HDF5 reader, inflates it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

struct isal_hufftables;

namespace throng::h5::detail {

/// Clears the upper halves of the vector registers after a call into ISA-L, whose AVX2 and AVX-512 code (2.30:
/// deflate, inflate, Adler-32) leaves them dirty and slows every SSE instruction after it on that thread (3.6x on a
/// float loop); call it after each ISA-L call.
void clear_upper_vector_state();

/// Whether a byte plane of n bytes looks like noise deflate cannot shrink: judged on 16 windows of 64 bytes spread
/// over it. Noise has bytes spread evenly (the windows' byte histogram close to uniform: its sum of squared counts
/// within 0.1 × n²/256 of what uniform random bytes give), no runs (a byte equal to the one before in under 1 in
/// 32), and no repeats one row earlier (`row_elements` bytes back: an agent's value in the frame before, within one
/// chunk of several frames; none in a chunk of one row, n ≤ row_elements; 0: none looked for). Planes under 4,096 bytes are never called noise (too few
/// samples; ISA-L is quick on them anyway). Deterministic: the same plane, the same answer. A plane with repeats
/// at other distances that still passes (a crowd tiled from copies of one patch, agent by agent) is stored whole:
/// a larger file, never a wrong one.
[[nodiscard]] bool looks_like_noise(const unsigned char* plane, std::size_t n, std::size_t row_elements);

/// The byte planes of a chunk that looks_like_noise does not call noise, one after the other (its `planes` planes of
/// bytes / planes bytes each); empty when none is noise or every one is (such a chunk is deflated whole, or stored).
[[nodiscard]] std::vector<unsigned char> structured_planes(const unsigned char* chunk, std::size_t bytes,
                                                           std::size_t planes, std::size_t row_elements);

/// Huffman codes for the structured planes of every chunk of one dataset's component, made once from its first
/// chunk's (structured_planes) with ISA-L's isal_update_histogram and isal_create_hufftables: every literal, length
/// and distance has a code, so any bytes can be coded with them. ISA-L's level 1 builds codes for each chunk from
/// its own histogram; with these its level 0 codes each chunk's structured planes without that step and with a
/// lighter match search: on a 6,000-agent sketch's position and orientation planes 15.3 instead of 27.4 µs a chunk,
/// 33.2 instead of 29.1 % of the planes' bytes (a file 1-2 % larger: the structured planes are a quarter of a chunk,
/// the rest stored). The codes depend on the first chunk's bytes alone, so a dataset's bytes still depend on its
/// values alone.
class PlaneCodes {
 public:
  /// Codes made from `bytes` bytes at `sample` (at least one).
  PlaneCodes(const unsigned char* sample, std::size_t bytes);
  ~PlaneCodes();
  PlaneCodes(const PlaneCodes&) = delete;
  PlaneCodes& operator=(const PlaneCodes&) = delete;
  [[nodiscard]] isal_hufftables& tables() const noexcept { return *tables_; }

 private:
  std::unique_ptr<isal_hufftables> tables_;
};

/// ISA-L's deflate at a dataset's level, with buffers one task reuses from chunk to chunk.
class ChunkDeflater {
 public:
  /// `zlib_level`: the dataset's deflate level 1-9 (zlib's scale, kept in the file's filter pipeline), mapped to
  /// ISA-L's nearest: 1 -> 1, 2-5 -> 2, 6-9 -> 3.
  explicit ChunkDeflater(int zlib_level);

  /// Room for any stream deflate() makes of `bytes` bytes in `planes` planes.
  [[nodiscard]] static std::size_t bound(std::size_t bytes, std::size_t planes);

  /// Writes the zlib stream of `bytes` bytes at `chunk`, taken as `planes` byte planes of bytes / planes each
  /// (1: one plane, deflated whole) to `out` (room for bound(bytes, planes)); `row_elements` as looks_like_noise's.
  /// With `codes` and some planes noise, the structured planes are coded with those codes at ISA-L's level 0
  /// instead of at the dataset's level (a chunk deflated whole is not: the codes were made for structured planes).
  /// Returns the stream's length, or 0 with ISA-L's status in *status when ISA-L fails; std::logic_error for a
  /// chunk beyond 4 GiB or `out_bytes` under bound(bytes, planes).
  std::size_t deflate(const unsigned char* chunk, std::size_t bytes, std::size_t planes, std::size_t row_elements,
                      unsigned char* out, std::size_t out_bytes, int* status, const PlaneCodes* codes = nullptr);

  /// What deflate() writes for a chunk of `bytes` zero bytes (whatever its planes), without the chunk: for a caller
  /// that knows it is zeros before gathering it. The same failures as deflate().
  std::size_t deflate_zeros(std::size_t bytes, unsigned char* out, std::size_t out_bytes, int* status);

 private:
  // One ISA-L call: a raw deflate (zlib = false: no header, no trailer; its last block final when `last`, else
  // ending on a byte boundary) or a whole zlib stream. Returns the bytes written, 0 on failure (*status set).
  // With `codes`: ISA-L's level 0 with those codes (a raw deflate only).
  std::size_t run_isal(const unsigned char* in, std::size_t bytes, bool zlib, bool last, unsigned char* out,
                       std::size_t out_bytes, int* status, const PlaneCodes* codes = nullptr);

  // std::logic_error unless a chunk of `bytes` bytes in `planes` planes fits ISA-L's 32-bit sizes and `out_bytes`
  // holds bound(bytes, planes): deflate()'s and deflate_zeros()'s precondition.
  static void require_room(std::size_t bytes, std::size_t planes, std::size_t out_bytes);

  // The zlib stream of `bytes` zero bytes, from zero_stream_ when it is that size's, else made by ISA-L from
  // `zeros` (`bytes` zero bytes; null: made here) and kept.
  std::size_t zeros_stream(const unsigned char* zeros, std::size_t bytes, unsigned char* out, std::size_t out_bytes,
                           int* status);

  int level_;
  std::size_t level_bytes_;
  std::unique_ptr<std::uint8_t[]> level_buffer_;  // ISA-L's hash tables and token space, about 0.3 MB
  // The stream of the last chunk of zero_bytes_ zero bytes (the z of positions, the x and y of yaw quaternions:
  // three chunks of seven in a sketch's frame), as ISA-L made it: the same bytes again for the next such chunk.
  std::vector<unsigned char> zero_stream_;
  std::size_t zero_bytes_ = 0;
};

}  // namespace throng::h5::detail
