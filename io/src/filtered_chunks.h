// Writing a compressed dataset chunk by chunk, the chunks shuffled and deflated in parallel.
//
// libhdf5 runs a dataset's filters on one thread, chunk after chunk: zlib was 60 % of `throng sketch` at 6,000
// agents. Here each chunk goes through the same pipeline libhdf5 would run (the shuffle filter's byte transpose,
// then deflate at the dataset's level into a zlib stream: chunk_deflate.h, ISA-L's igzip with the byte planes that
// are noise stored) on the threads of a pipeline, and is handed in chunk order to the caller, who writes it as it
// is (H5Dwrite_chunk) while the next chunks compress. ISA-L's streams are ordinary zlib streams, so every HDF5
// reader inflates them with zlib.
// Every chunk's bytes depend on its rows alone, so the file is the same whatever the thread count, and any HDF5
// reader decodes it as one written by H5Dwrite.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace throng::h5::detail {

class PlaneCodes;

/// The Huffman codes of a dataset's components (chunk_deflate.h's PlaneCodes), made from the dataset's first chunk
/// of each component by the first filter_chunks call given this object, and used by the calls after it: a dataset
/// written block by block (crowd_stream.cpp) codes every block as a dataset written in one call does.
struct DatasetCodes {
  bool made = false;
  std::vector<std::shared_ptr<const PlaneCodes>> by_component;  ///< null: that component at the dataset's level
};

/// The layout of a dataset created with chunks of `chunk_rows` whole rows along its first axis and the filters
/// shuffle (element size `element_size`) then deflate (`level`). With `components` > 1 the last axis (that many
/// values, e.g. x, y, z of a position) is chunked one index at a time: chunk (r, c) holds component c of the rows
/// from r × chunk_rows. The shuffle's byte planes then each hold one component of neighbouring agents instead of
/// x, y and z interleaved: on a 10,000-agent sketch's frames the chunks came out 15-23 % smaller and deflated in
/// about half the time (66 -> 56 % of the raw bytes for positions, 55 -> 43 % for orientations).
struct ChunkedLayout {
  std::uint64_t rows = 0;          ///< the first axis
  std::uint64_t row_bytes = 0;     ///< bytes of one row (the product of the other axes × element size)
  std::uint64_t chunk_rows = 0;    ///< rows per chunk (the last chunk is padded with zero bytes, as libhdf5 pads it)
  std::size_t element_size = 0;
  int level = 1;
  std::uint64_t components = 1;    ///< the last axis's length when it is chunked an index at a time, else 1
  /// Kept by the caller across the calls that write one dataset (the first call's rows start at the dataset's
  /// first row); null: made for this call alone, from its first chunk.
  DatasetCodes* codes = nullptr;
};

/// The shuffle filter (H5Z_filter_shuffle) of n elements of `element_size` bytes taken `stride` bytes apart from
/// `in` (stride == element_size: contiguous; larger: one component of rows) into `out` (n × element_size bytes):
/// byte j of element i goes to j × n + i. SSE2 for elements of 4 and 8 bytes.
void shuffle(const unsigned char* in, std::size_t n, std::size_t element_size, std::size_t stride, unsigned char* out);

/// Filters `data` (rows × row_bytes bytes, already in the dataset's file type) chunk by chunk as a dataset of that
/// layout stores it (deflate level 1 with components: each component's structured planes with the codes of its
/// first chunk, DatasetCodes), and calls write(first row of the chunk, its component (0 without components), its filtered
/// bytes and their count) for every chunk in order: by rows, then by component, one call at a time (from any of
/// the threads: libhdf5 may be called there, never concurrently). The bytes lie at the start of a buffer aligned to
/// direct_write_block (direct_write_driver.h), so the file driver writes them straight to the disk.
/// IoError naming `where` when ISA-L fails on a chunk; std::logic_error for a row that is not whole elements (of
/// every component) or a chunk beyond 4 GiB.
void filter_chunks(const std::byte* data, const ChunkedLayout& layout, const std::string& where,
                   const std::function<void(std::uint64_t first_row, std::uint64_t component,
                                            const unsigned char* bytes, std::size_t size)>& write);

}  // namespace throng::h5::detail
