#include "filtered_chunks.h"

#include <throng/core/errors.h>
#include <throng/core/parallel.h>

#include <isa-l/igzip_lib.h>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace throng::h5::detail {
namespace {

// Chunks compressed before they are written: enough tasks for every thread, a bounded buffer (≈ 32 × 256 KiB
// in and out).
constexpr std::uint64_t batch_chunks = 32;

// The shuffle filter (H5Z_filter_shuffle): byte j of element i goes to position j × n + i, n elements.
template <std::size_t ElementSize>
void shuffle_elements_of(const unsigned char* in, std::size_t n, unsigned char* out) {
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < ElementSize; ++j) out[j * n + i] = in[i * ElementSize + j];
  }
}

// The element size a compile-time constant for the sizes throng writes (8: float64 and int64, nearly every byte;
// 4: int32), so the compiler vectorises the transpose: at -O3, 240 kB chunks of float64 here, 2.9 GB/s with the
// size a variable, 20.8 GB/s with it constant.
void shuffle(const unsigned char* in, std::size_t bytes, std::size_t element_size, unsigned char* out) {
  const std::size_t n = bytes / element_size;
  switch (element_size) {
    case 8: return shuffle_elements_of<8>(in, n, out);
    case 4: return shuffle_elements_of<4>(in, n, out);
    case 2: return shuffle_elements_of<2>(in, n, out);
    default:
      for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t j = 0; j < element_size; ++j) out[j * n + i] = in[i * element_size + j];
      }
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
                   const std::function<void(std::uint64_t first_row, const std::vector<unsigned char>& bytes)>& write) {
  if (layout.element_size == 0 || layout.row_bytes % layout.element_size != 0 || layout.chunk_rows == 0) {
    throw std::logic_error("filter_chunks: rows of whole elements and chunks of at least one row expected");
  }
  const std::uint64_t chunk_bytes = layout.chunk_rows * layout.row_bytes;
  if (zlib_stream_bound(chunk_bytes) > std::numeric_limits<std::uint32_t>::max()) {  // libhdf5's limit is 4 GiB too
    throw std::logic_error("filter_chunks: a chunk of " + std::to_string(chunk_bytes) + " bytes is beyond ISA-L's 32-bit sizes");
  }
  const std::uint64_t chunks = (layout.rows + layout.chunk_rows - 1) / layout.chunk_rows;
  for (std::uint64_t first = 0; first < chunks; first += batch_chunks) {
    const std::uint64_t count = std::min(batch_chunks, chunks - first);
    std::vector<std::vector<unsigned char>> packed(count);
    std::vector<int> failed(count, 0);  // ISA-L's status of each chunk that failed
    parallel_for(count, 1, [&](std::size_t begin, std::size_t end) {
      // One level buffer per task (ISA-L's hash tables and token space, about 0.3 MB; buffers kept per thread
      // instead measured no faster).
      std::vector<std::uint8_t> level_buffer(level_buffer_bytes(layout.level));
      std::vector<unsigned char> padded, shuffled(layout.element_size > 1 ? chunk_bytes : 0);
      std::vector<unsigned char> out(zlib_stream_bound(chunk_bytes));
      for (std::size_t k = begin; k < end; ++k) {
        const std::uint64_t row0 = (first + k) * layout.chunk_rows;
        const std::uint64_t rows = std::min(layout.chunk_rows, layout.rows - row0);
        const auto* source = reinterpret_cast<const unsigned char*>(data) + row0 * layout.row_bytes;
        const unsigned char* chunk = source;
        if (rows < layout.chunk_rows) {  // the edge chunk: its rows, then zero bytes (libhdf5's fill)
          padded.assign(chunk_bytes, 0);
          std::memcpy(padded.data(), source, rows * layout.row_bytes);
          chunk = padded.data();
        }
        if (layout.element_size > 1) {
          shuffle(chunk, chunk_bytes, layout.element_size, shuffled.data());
          chunk = shuffled.data();
        }
        // Value-initialised first: 2.30's init leaves hist_bits (the match window) unset, and garbage there would
        // make a chunk's bytes differ from run to run (0: the default, 32 KiB).
        isal_zstream stream{};
        isal_deflate_stateless_init(&stream);
        stream.hist_bits = 0;
        stream.level = static_cast<std::uint32_t>(isal_level(layout.level));
        stream.level_buf = level_buffer.data();
        stream.level_buf_size = static_cast<std::uint32_t>(level_buffer.size());
        stream.gzip_flag = IGZIP_ZLIB;  // zlib header and Adler-32 trailer: what HDF5's deflate filter inflates
        stream.end_of_stream = 1;
        stream.flush = NO_FLUSH;
        stream.next_in = const_cast<std::uint8_t*>(chunk);
        stream.avail_in = static_cast<std::uint32_t>(chunk_bytes);
        stream.next_out = out.data();
        stream.avail_out = static_cast<std::uint32_t>(out.size());
        const int status = isal_deflate_stateless(&stream);
        clear_upper_vector_state();
        if (status != COMP_OK) failed[k] = status;  // not within the bound: a failure, not an empty chunk
        else packed[k].assign(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(stream.total_out));
      }
    });
    for (std::uint64_t k = 0; k < count; ++k) {
      if (failed[k] != 0) {
        throw IoError("cannot write " + where + ": ISA-L could not deflate chunk " + std::to_string(first + k) +
                      " (status " + std::to_string(failed[k]) + ")");
      }
      write((first + k) * layout.chunk_rows, packed[k]);
    }
  }
}

}  // namespace throng::h5::detail
