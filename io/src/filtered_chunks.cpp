#include "filtered_chunks.h"

#include <throng/core/errors.h>
#include <throng/core/parallel.h>

#include <libdeflate.h>

#include <algorithm>
#include <memory>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace throng::h5::detail {
namespace {

// Chunks compressed before they are written: enough tasks for every thread, a bounded buffer (≈ 32 × 256 KiB
// in and out).
constexpr std::uint64_t batch_chunks = 32;

// The shuffle filter (H5Z_filter_shuffle): byte j of element i goes to position j × n + i, n elements.
void shuffle(const unsigned char* in, std::size_t bytes, std::size_t element_size, unsigned char* out) {
  const std::size_t n = bytes / element_size;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < element_size; ++j) out[j * n + i] = in[i * element_size + j];
  }
}

}  // namespace

void filter_chunks(const std::byte* data, const ChunkedLayout& layout, const std::string& where,
                   const std::function<void(std::uint64_t first_row, const std::vector<unsigned char>& bytes)>& write) {
  if (layout.element_size == 0 || layout.row_bytes % layout.element_size != 0 || layout.chunk_rows == 0) {
    throw std::logic_error("filter_chunks: rows of whole elements and chunks of at least one row expected");
  }
  const std::uint64_t chunk_bytes = layout.chunk_rows * layout.row_bytes;
  const std::uint64_t chunks = (layout.rows + layout.chunk_rows - 1) / layout.chunk_rows;
  for (std::uint64_t first = 0; first < chunks; first += batch_chunks) {
    const std::uint64_t count = std::min(batch_chunks, chunks - first);
    std::vector<std::vector<unsigned char>> packed(count);
    std::vector<char> failed(count, 0);
    parallel_for(count, 1, [&](std::size_t begin, std::size_t end) {
      // One compressor per task (its match finder's tables, about 0.3 MB), freed on every path out.
      const std::unique_ptr<libdeflate_compressor, decltype(&libdeflate_free_compressor)> compressor(
          libdeflate_alloc_compressor(layout.level), &libdeflate_free_compressor);
      std::vector<unsigned char> padded, shuffled(layout.element_size > 1 ? chunk_bytes : 0);
      std::vector<unsigned char> out(compressor ? libdeflate_zlib_compress_bound(compressor.get(), chunk_bytes) : 0);
      for (std::size_t k = begin; k < end; ++k) {
        if (!compressor) {
          failed[k] = 1;
          continue;
        }
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
        const std::size_t size = libdeflate_zlib_compress(compressor.get(), chunk, chunk_bytes, out.data(), out.size());
        if (size == 0) failed[k] = 1;  // cannot happen within the bound; a failure, not an empty chunk
        else packed[k].assign(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(size));
      }
    });
    for (std::uint64_t k = 0; k < count; ++k) {
      if (failed[k]) throw IoError("cannot write " + where + ": libdeflate could not compress chunk " + std::to_string(first + k) + " (out of memory?)");
      write((first + k) * layout.chunk_rows, packed[k]);
    }
  }
}

}  // namespace throng::h5::detail
