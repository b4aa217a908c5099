#include "filtered_chunks.h"

#include <throng/core/errors.h>
#include <throng/core/parallel.h>

#include <isa-l/igzip_lib.h>

#if defined(__x86_64__)
#include <immintrin.h>
#endif
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace throng::h5::detail {
namespace {

// Chunks compressed before they are written: enough tasks for every thread, a bounded buffer (≈ 32 × 256 KiB
// in and out).
constexpr std::uint64_t batch_chunks = 32;

// The shuffle filter (H5Z_filter_shuffle) of n elements taken `stride` bytes apart from `in`: byte j of element i
// goes to position j × n + i.
void shuffle_bytes(const unsigned char* in, std::size_t n, std::size_t element_size, std::size_t stride, unsigned char* out) {
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < element_size; ++j) out[j * n + i] = in[i * stride + j];
  }
}

// The same for contiguous elements of ElementSize (4 or 8) bytes, 16 elements at a time in SSE2 registers (GCC
// left the byte loop scalar: 8 % of `throng sketch` at 10,000 agents). The 16 elements fill ElementSize registers;
// byte j of element i sits in register i3 i2 i1 at lane i0 j2 j1 j0 (bits, for 8-byte elements). Each
// round interleaves register k with register k + ElementSize/2 (unpacklo into 2k, unpackhi into 2k + 1): every lane
// index moves up a bit, taking the pair's distinguishing register bit as its lowest, and its highest becomes the
// register bit that tells lo from hi. After four rounds a register's lanes are i3 i2 i1 i0 and register j holds
// byte j of the 16 elements in order: 16 bytes of plane j.
template <std::size_t ElementSize>
void shuffle_elements_of(const unsigned char* in, std::size_t n, unsigned char* out) {
  static_assert(ElementSize == 4 || ElementSize == 8);
  std::size_t i = 0;
#if defined(__SSE2__)
  for (; i + 16 <= n; i += 16) {
    __m128i r[ElementSize], t[ElementSize];
    for (std::size_t k = 0; k < ElementSize; ++k) {
      r[k] = _mm_loadu_si128(reinterpret_cast<const __m128i*>(in + i * ElementSize + 16 * k));
    }
    for (int round = 0; round < 4; ++round) {
      for (std::size_t k = 0; k < ElementSize / 2; ++k) {
        t[2 * k] = _mm_unpacklo_epi8(r[k], r[k + ElementSize / 2]);
        t[2 * k + 1] = _mm_unpackhi_epi8(r[k], r[k + ElementSize / 2]);
      }
      for (std::size_t k = 0; k < ElementSize; ++k) r[k] = t[k];
    }
    for (std::size_t j = 0; j < ElementSize; ++j) _mm_storeu_si128(reinterpret_cast<__m128i*>(out + j * n + i), r[j]);
  }
#endif
  for (; i < n; ++i) {
    for (std::size_t j = 0; j < ElementSize; ++j) out[j * n + i] = in[i * ElementSize + j];
  }
}

// A component (stride > element size) is first gathered into `scratch` (n elements) by whole elements, then
// transposed as contiguous elements.
template <std::size_t ElementSize>
void shuffle_strided(const unsigned char* in, std::size_t n, std::size_t stride, unsigned char* scratch, unsigned char* out) {
  if (stride != ElementSize) {
    for (std::size_t i = 0; i < n; ++i) std::memcpy(scratch + i * ElementSize, in + i * stride, ElementSize);
    in = scratch;
  }
  shuffle_elements_of<ElementSize>(in, n, out);
}

// `scratch`: room for n elements, used when stride > element_size.
void shuffle(const unsigned char* in, std::size_t n, std::size_t element_size, std::size_t stride, unsigned char* scratch,
             unsigned char* out) {
  switch (element_size) {
    case 8: return shuffle_strided<8>(in, n, stride, scratch, out);
    case 4: return shuffle_strided<4>(in, n, stride, scratch, out);
    default: return shuffle_bytes(in, n, element_size, stride, out);  // sizes throng does not write
  }
}

// ISA-L 2.30's AVX2 and AVX-512 deflate code returns with the upper halves of the vector registers dirty (no
// vzeroupper): every SSE instruction after it, on that thread, then pays for merging them, and throng's code (built
// for baseline x86-64, SSE2) ran 3.6x slower on that thread (a float loop 11.7 -> 42.7 ms; the sketch's simulation
// 2x). One vzeroupper after each call clears them; it leaves the low 128 bits that SSE code uses untouched. In a
// function of its own built for AVX, so that the compiler knows what the instruction clobbers.
#if defined(__x86_64__)
__attribute__((target("avx"))) void zero_upper_halves() { _mm256_zeroupper(); }
#endif

void clear_upper_vector_state() {
#if defined(__x86_64__)
  static const bool has_avx = __builtin_cpu_supports("avx");
  if (has_avx) zero_upper_halves();
#endif
}

// ISA-L's levels are 0-3 (0 its fastest, not stored blocks); a dataset's deflate level 1-9 (zlib's scale, kept in
// the file's filter pipeline) maps to the nearest: 1 -> 1, 2-5 -> 2, 6-9 -> 3.
int isal_level(int zlib_level) {
  if (zlib_level <= 1) return 1;
  return zlib_level <= 5 ? 2 : 3;
}

std::size_t level_buffer_bytes(int zlib_level) {
  switch (isal_level(zlib_level)) {
    case 1: return ISAL_DEF_LVL1_DEFAULT;
    case 2: return ISAL_DEF_LVL2_DEFAULT;
    default: return ISAL_DEF_LVL3_DEFAULT;
  }
}

// Room for any chunk's stream: ISA-L falls back to stored blocks (5 bytes of header per 65,535 bytes) when the
// data does not compress, after the zlib header (2 bytes) and before the Adler-32 (4); its largest block header,
// once more, as margin.
std::size_t zlib_stream_bound(std::size_t bytes) {
  return bytes + 5 * (bytes / 65535 + 1) + 6 + ISAL_DEF_MAX_HDR_SIZE;
}

}  // namespace

void filter_chunks(const std::byte* data, const ChunkedLayout& layout, const std::string& where,
                   const std::function<void(std::uint64_t first_row, std::uint64_t component,
                                            const std::vector<unsigned char>& bytes)>& write) {
  const std::uint64_t C = layout.components;
  if (layout.element_size == 0 || C == 0 || layout.row_bytes % (C * layout.element_size) != 0 || layout.chunk_rows == 0) {
    throw std::logic_error("filter_chunks: rows of whole elements and chunks of at least one row expected");
  }
  const std::uint64_t rows_bytes = layout.chunk_rows * layout.row_bytes;  // a chunk's rows, every component
  const std::uint64_t chunk_bytes = rows_bytes / C;
  if (zlib_stream_bound(rows_bytes) > std::numeric_limits<std::uint32_t>::max()) {  // libhdf5's limit is 4 GiB too
    // (A chunk's rows, every component: a bound C times stricter than the chunk needs, kept simple.)
    throw std::logic_error("filter_chunks: a chunk's rows of " + std::to_string(rows_bytes) + " bytes are beyond ISA-L's 32-bit sizes");
  }
  // Chunk k: rows from (k / C) × chunk_rows, component k % C.
  const std::uint64_t chunks = (layout.rows + layout.chunk_rows - 1) / layout.chunk_rows * C;
  const bool transposed = layout.element_size > 1 || C > 1;  // shuffled, or one component taken out of the rows
  for (std::uint64_t first = 0; first < chunks; first += batch_chunks) {
    const std::uint64_t count = std::min(batch_chunks, chunks - first);
    std::vector<std::vector<unsigned char>> packed(count);
    std::vector<int> failed(count, 0);  // ISA-L's status of each chunk that failed
    parallel_for(count, 1, [&](std::size_t begin, std::size_t end) {
      // One level buffer per task (ISA-L's hash tables and token space, about 0.3 MB; buffers kept per thread
      // instead measured no faster).
      // Left uninitialised (ISA-L's level 1 resets what it reads of the level buffer; the others are written before
      // they are read): zeroing them cost about 1 % of `throng sketch` at 10,000 agents. Levels 2-3 gave the same
      // streams from garbage too, but valgrind saw their assembly branch on it: zeroed there.
      const std::size_t level_bytes = level_buffer_bytes(layout.level), out_bytes = zlib_stream_bound(chunk_bytes);
      const auto level_buffer = std::make_unique_for_overwrite<std::uint8_t[]>(level_bytes);
      if (isal_level(layout.level) > 1) std::memset(level_buffer.get(), 0, level_bytes);
      const auto shuffled = std::make_unique_for_overwrite<unsigned char[]>(transposed ? chunk_bytes : 0);
      const auto gathered = std::make_unique_for_overwrite<unsigned char[]>(C > 1 ? chunk_bytes : 0);
      const auto out = std::make_unique_for_overwrite<unsigned char[]>(out_bytes);
      std::vector<unsigned char> padded;  // the edge chunk's rows, padded once for all its components
      std::uint64_t padded_row0 = std::numeric_limits<std::uint64_t>::max();
      for (std::size_t k = begin; k < end; ++k) {
        const std::uint64_t row0 = (first + k) / C * layout.chunk_rows, component = (first + k) % C;
        const std::uint64_t rows = std::min(layout.chunk_rows, layout.rows - row0);
        const auto* source = reinterpret_cast<const unsigned char*>(data) + row0 * layout.row_bytes;
        const unsigned char* chunk = source;
        if (rows < layout.chunk_rows) {  // the edge chunk: its rows, then zero bytes (libhdf5's fill)
          if (padded_row0 != row0) {
            padded.assign(rows_bytes, 0);
            std::memcpy(padded.data(), source, rows * layout.row_bytes);
            padded_row0 = row0;
          }
          chunk = padded.data();
        }
        if (transposed) {
          shuffle(chunk + component * layout.element_size, chunk_bytes / layout.element_size, layout.element_size,
                  C * layout.element_size, gathered.get(), shuffled.get());
          chunk = shuffled.get();
        }
        // Value-initialised first: 2.30's init leaves hist_bits (the match window) unset, and garbage there would
        // make a chunk's bytes differ from run to run (0: the default, 32 KiB).
        isal_zstream stream{};
        isal_deflate_stateless_init(&stream);
        stream.hist_bits = 0;
        stream.level = static_cast<std::uint32_t>(isal_level(layout.level));
        stream.level_buf = level_buffer.get();
        stream.level_buf_size = static_cast<std::uint32_t>(level_bytes);
        stream.gzip_flag = IGZIP_ZLIB;  // zlib header and Adler-32 trailer: what HDF5's deflate filter inflates
        stream.end_of_stream = 1;
        stream.flush = NO_FLUSH;
        stream.next_in = const_cast<std::uint8_t*>(chunk);
        stream.avail_in = static_cast<std::uint32_t>(chunk_bytes);
        stream.next_out = out.get();
        stream.avail_out = static_cast<std::uint32_t>(out_bytes);
        const int status = isal_deflate_stateless(&stream);
        clear_upper_vector_state();
        if (status != COMP_OK) failed[k] = status;  // not within the bound: a failure, not an empty chunk
        else packed[k].assign(out.get(), out.get() + stream.total_out);
      }
    });
    for (std::uint64_t k = 0; k < count; ++k) {
      if (failed[k] != 0) {
        throw IoError("cannot write " + where + ": ISA-L could not deflate chunk " + std::to_string(first + k) +
                      " (status " + std::to_string(failed[k]) + ")");
      }
      write((first + k) / C * layout.chunk_rows, (first + k) % C, packed[k]);
    }
  }
}

}  // namespace throng::h5::detail
