#include "filtered_chunks.h"

#include "chunk_deflate.h"
#include "direct_write_driver.h"

#include <throng/core/errors.h>
#include <throng/core/parallel.h>

#include <tbb/parallel_pipeline.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace throng::h5::detail {
namespace {

// Chunks are compressed in groups of about this many (a task of about 0.15 ms at 10,000 agents), at most
// groups_in_flight groups at a time: a bounded buffer (≈ 4 × 16 × 256 KiB in and out).
constexpr std::uint64_t group_chunks = 4;
constexpr std::size_t groups_in_flight = 16;

// The shuffle filter (H5Z_filter_shuffle) of n elements taken `stride` bytes apart from `in`: byte j of element i
// goes to position j × n + i.
void shuffle_bytes(const unsigned char* in, std::size_t n, std::size_t element_size, std::size_t stride, unsigned char* out) {
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < element_size; ++j) out[j * n + i] = in[i * stride + j];
  }
}

#if defined(__SSE2__)
// Sixteen bytes of elements 2k and 2k + 1 (8-byte elements) or 4k to 4k + 3 (4-byte ones) of the 16 at `in`,
// elements `stride` bytes apart: register k of shuffle_elements_of's transpose, as if the elements were contiguous.
template <std::size_t ElementSize>
__m128i gather_register(const unsigned char* in, std::size_t stride, std::size_t k) {
  if constexpr (ElementSize == 8) {
    const auto* e = in + 2 * k * stride;
    return _mm_unpacklo_epi64(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(e)),
                              _mm_loadl_epi64(reinterpret_cast<const __m128i*>(e + stride)));
  } else {
    const auto* e = in + 4 * k * stride;
    std::int32_t v[4];
    for (std::size_t m = 0; m < 4; ++m) std::memcpy(&v[m], e + m * stride, 4);
    return _mm_setr_epi32(v[0], v[1], v[2], v[3]);
  }
}
#endif

// The same for elements of ElementSize (4 or 8) bytes, 16 elements at a time in SSE2 registers (GCC left the byte
// loop scalar: 8 % of `throng sketch` at 10,000 agents). The 16 elements fill ElementSize registers (contiguous
// ones loaded 16 bytes at a time; one component of rows, `stride` bytes apart, an element at a time, so that it is
// not first copied out of its rows: that copy was 60 % of this step); byte j of element i sits in register
// i3 i2 i1 at lane i0 j2 j1 j0 (bits, for 8-byte elements). Each round interleaves register k with register
// k + ElementSize/2 (unpacklo into 2k, unpackhi into 2k + 1): every lane index moves up a bit, taking the pair's
// distinguishing register bit as its lowest, and its highest becomes the register bit that tells lo from hi. After
// four rounds a register's lanes are i3 i2 i1 i0 and register j holds byte j of the 16 elements in order: 16 bytes
// of plane j.
template <std::size_t ElementSize>
void shuffle_elements_of(const unsigned char* in, std::size_t n, std::size_t stride, unsigned char* out) {
  static_assert(ElementSize == 4 || ElementSize == 8);
  std::size_t i = 0;
#if defined(__SSE2__)
  for (; i + 16 <= n; i += 16) {
    __m128i r[ElementSize], t[ElementSize];
    for (std::size_t k = 0; k < ElementSize; ++k) {
      r[k] = stride == ElementSize ? _mm_loadu_si128(reinterpret_cast<const __m128i*>(in + i * ElementSize + 16 * k))
                                   : gather_register<ElementSize>(in + i * stride, stride, k);
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
    for (std::size_t j = 0; j < ElementSize; ++j) out[j * n + i] = in[i * stride + j];
  }
}


// Whether the n elements of ElementSize bytes taken `stride` bytes apart from `in` are all zero bytes; it stops at
// the first that is not (a component that varies: at once).
template <std::size_t ElementSize>
bool zero_elements(const unsigned char* in, std::size_t n, std::size_t stride) {
  using Word = std::conditional_t<ElementSize == 8, std::uint64_t, std::uint32_t>;
  static_assert(sizeof(Word) == ElementSize);
  for (std::size_t i = 0; i < n; ++i) {
    Word w;
    std::memcpy(&w, in + i * stride, ElementSize);
    if (w != 0) return false;
  }
  return true;
}

// The same for any element size: false for sizes throng does not write (the chunk is then gathered and checked).
bool zero_component(const unsigned char* in, std::size_t n, std::size_t element_size, std::size_t stride) {
  switch (element_size) {
    case 8: return zero_elements<8>(in, n, stride);
    case 4: return zero_elements<4>(in, n, stride);
    default: return false;
  }
}

// A thread's deflater (ISA-L's level buffer, 0.3 MB) and shuffled chunk, grown as needed and kept from group to
// group: made per group, they were page-faulted in again and again.
struct ThreadBuffers {
  std::unique_ptr<ChunkDeflater> deflater;
  int level = 0;
  std::vector<unsigned char> shuffled;
  // The last single-component chunk this thread compressed, as it was before the shuffle, and its stream: a
  // crowd's ids (and mostly its actions) are the same frame after frame, so the next chunk is often the same bytes,
  // and the same bytes make the same stream (chunk_deflate.h). Kept for chunks up to reused_chunk_bytes (the
  // thread holds it and its stream, about twice that, for the process's life).
  std::vector<unsigned char> last_chunk, last_stream;
  std::size_t last_element_size = 0, last_row_elements = 0;
};

// Single-component chunks up to this size are kept per thread with their streams, to be reused (ThreadBuffers): a
// chunk of 10,000 agents' ids is 240 KB, of 100,000 agents' 800 KB.
constexpr std::size_t reused_chunk_bytes = 1024 * 1024;

// Shuffled chunks up to this size are kept per thread (a 10,000-agent frame's component is 80 KB); larger ones
// (a frame of 1,000,000 agents: 8 MB) are made per group, so that no thread keeps them for the process's life.
constexpr std::size_t kept_shuffled_bytes = 4 * 1024 * 1024;

// Compressed chunks' buffers, kept for the next groups and calls. Made per chunk and freed once written, their
// pages went back to the kernel (glibc gives back what is free at the top of a thread's heap, and maps large
// buffers on their own) and were faulted in again block after block: perf of bench_sketch_command at 10,000 agents
// put 24 % of the command's page faults in deflate's first writes to them. Buffers of up to kept_packed_bytes, at
// most kept_packed_count of them (about the chunks of the groups in flight), are kept for the process's life: at
// 10,000 agents 80 KB (a component's chunk) or 240 KB (ids, actions) each, at 100,000 agents about 800 KB.
constexpr std::size_t kept_packed_bytes = 1024 * 1024;
constexpr std::size_t kept_packed_count = groups_in_flight * group_chunks;

class PackedPool {
 public:
  PackedPool() { kept_.reserve(kept_packed_count); }  // give() then never allocates (it runs in destructors)

  // A buffer of at least `bytes` bytes, and its size: the smallest kept one that is large enough (holding an earlier
  // stream), or a new one (uninitialised).
  std::pair<AlignedBytes, std::size_t> take(std::size_t bytes) {
    if (bytes <= kept_packed_bytes) {
      std::lock_guard lock(mutex_);
      std::size_t best = kept_.size();
      for (std::size_t i = 0; i < kept_.size(); ++i) {
        if (kept_[i].second >= bytes && (best == kept_.size() || kept_[i].second < kept_[best].second)) best = i;
      }
      if (best < kept_.size()) {
        auto found = std::move(kept_[best]);
        kept_[best] = std::move(kept_.back());
        kept_.pop_back();
        return found;
      }
    }
    return {aligned_bytes(bytes), bytes};
  }
  // Keeps `buffer` (of `bytes` bytes) for a later take, or frees it.
  void give(AlignedBytes buffer, std::size_t bytes) noexcept {
    if (!buffer || bytes > kept_packed_bytes) return;
    std::lock_guard lock(mutex_);
    if (kept_.size() < kept_packed_count) kept_.emplace_back(std::move(buffer), bytes);
  }

 private:
  std::mutex mutex_;
  std::vector<std::pair<AlignedBytes, std::size_t>> kept_;
};

PackedPool& packed_pool() {
  static PackedPool pool;
  return pool;
}

ThreadBuffers& thread_buffers(int level) {
  thread_local ThreadBuffers buffers;
  if (!buffers.deflater || buffers.level != level) {
    buffers.deflater = std::make_unique<ChunkDeflater>(level);
    buffers.level = level;
    buffers.last_chunk.clear();  // its stream was made at another level
    buffers.last_stream.clear();
    buffers.last_element_size = buffers.last_row_elements = 0;
  }
  return buffers;
}

// Room for `bytes` shuffled bytes: the thread's kept buffer, or `own` made for the caller.
unsigned char* shuffled_room(ThreadBuffers& buffers, std::size_t bytes, std::unique_ptr<unsigned char[]>& own) {
  if (bytes > kept_shuffled_bytes) {
    own = std::make_unique_for_overwrite<unsigned char[]>(bytes);
    return own.get();
  }
  if (buffers.shuffled.size() < bytes) buffers.shuffled.resize(bytes);
  return buffers.shuffled.data();
}

// The chunk whose rows start at `source` (`rows` of them, fewer than chunk_rows only at the dataset's end): those
// rows, or at the end `padded` filled with them and then zero bytes, libhdf5's fill, as the chunk is stored.
const unsigned char* whole_chunk(const unsigned char* source, std::uint64_t rows, const ChunkedLayout& layout,
                                 std::vector<unsigned char>& padded) {
  if (rows >= layout.chunk_rows) return source;
  padded.assign(layout.chunk_rows * layout.row_bytes, 0);
  std::memcpy(padded.data(), source, rows * layout.row_bytes);
  return padded.data();
}

// Codes are made for chunks whose structured planes are at most this many bytes. What they save is ISA-L's level 1
// building codes for each chunk, a cost per chunk; its level 0 codes a byte more slowly than level 1 (perf of
// `bench_sketch_command`: ISA-L's samples 590 -> 455 with codes at 10,000 agents, structured planes of 20 KB a
// chunk, but 371 -> 418 at 100,000, 200 KB a chunk), so larger chunks keep level 1.
constexpr std::size_t coded_planes_most = 64 * 1024;

// Makes `codes` (once) from the first chunk of `data`, component by component: for a layout of several components at
// deflate level 1 (a crowd's positions and orientations, whose low planes are noise); none otherwise, nor for a
// component of zeros, one with no plane of noise in its first chunk (deflated whole at the dataset's level) or one
// whose structured planes are beyond coded_planes_most.
void make_codes(const unsigned char* data, const ChunkedLayout& layout, std::uint64_t chunk_bytes, DatasetCodes& codes) {
  if (layout.rows == 0) return;  // nothing to make them from: the next call's first chunk is the dataset's
  codes.made = true;
  const std::uint64_t C = layout.components;
  if (C <= 1 || layout.level > 1 || layout.element_size < 2) return;
  codes.by_component.assign(C, nullptr);
  std::vector<unsigned char> padded;
  const unsigned char* chunk = whole_chunk(data, std::min(layout.chunk_rows, layout.rows), layout, padded);
  const std::size_t n = chunk_bytes / layout.element_size;
  std::vector<unsigned char> shuffled(chunk_bytes);
  for (std::uint64_t c = 0; c < C; ++c) {
    const unsigned char* first = chunk + c * layout.element_size;
    if (zero_component(first, n, layout.element_size, C * layout.element_size)) continue;
    shuffle(first, n, layout.element_size, C * layout.element_size, shuffled.data());
    // Noise judged without the repeat test (row_elements 0): a crowd's first frames often stand still, so their low
    // planes repeat one row back and would count as structured, though they are noise in the frames after.
    const std::vector<unsigned char> sample = structured_planes(shuffled.data(), chunk_bytes, layout.element_size, 0);
    if (!sample.empty() && sample.size() <= coded_planes_most) {
      codes.by_component[c] = std::make_shared<const PlaneCodes>(sample.data(), sample.size());
    }
  }
}

[[noreturn]] void not_deflated(const std::string& where, std::uint64_t chunk, int status) {
  throw IoError("cannot write " + where + ": ISA-L could not deflate chunk " + std::to_string(chunk) + " (status " +
                std::to_string(status) + ")");
}

}  // namespace

void shuffle(const unsigned char* in, std::size_t n, std::size_t element_size, std::size_t stride, unsigned char* out) {
  switch (element_size) {
    case 8: return shuffle_elements_of<8>(in, n, stride, out);
    case 4: return shuffle_elements_of<4>(in, n, stride, out);
    default: return shuffle_bytes(in, n, element_size, stride, out);  // sizes throng does not write
  }
}

void filter_chunks(const std::byte* data, const ChunkedLayout& layout, const std::string& where,
                   const std::function<void(std::uint64_t first_row, std::uint64_t component,
                                            const unsigned char* bytes, std::size_t size)>& write) {
  const std::uint64_t C = layout.components;
  if (layout.element_size == 0 || C == 0 || layout.row_bytes % (C * layout.element_size) != 0 || layout.chunk_rows == 0) {
    throw std::logic_error("filter_chunks: rows of whole elements and chunks of at least one row expected");
  }
  const std::uint64_t rows_bytes = layout.chunk_rows * layout.row_bytes;  // a chunk's rows, every component
  const std::uint64_t chunk_bytes = rows_bytes / C;
  if (ChunkDeflater::bound(rows_bytes, layout.element_size) > std::numeric_limits<std::uint32_t>::max()) {  // libhdf5's limit is 4 GiB too
    // (A chunk's rows, every component: a bound C times stricter than the chunk needs, kept simple.)
    throw std::logic_error("filter_chunks: a chunk's rows of " + std::to_string(rows_bytes) + " bytes are beyond ISA-L's 32-bit sizes");
  }
  // Chunk k: rows from (k / C) × chunk_rows, component k % C.
  const std::uint64_t chunks = (layout.rows + layout.chunk_rows - 1) / layout.chunk_rows * C;
  const bool transposed = layout.element_size > 1 || C > 1;  // shuffled, or one component taken out of the rows
  const std::uint64_t row_elements = layout.row_bytes / (C * layout.element_size);  // one component's, in a row
  const std::size_t out_bytes = ChunkDeflater::bound(chunk_bytes, layout.element_size);
  DatasetCodes call_codes;  // without the caller's: this call's own
  DatasetCodes& codes = layout.codes != nullptr ? *layout.codes : call_codes;
  if (!codes.made) make_codes(reinterpret_cast<const unsigned char*>(data), layout, chunk_bytes, codes);
  // A group of consecutive chunks, compressed: chunk first + k's stream in packed[k].
  struct Group {
    std::uint64_t first = 0, count = 0;
    std::vector<AlignedBytes> packed;  // from packed_pool, each room[k] long; the first size[k] bytes are the stream
    std::vector<std::size_t> room, size;
    Group() = default;
    Group(const Group&) = delete;
    Group& operator=(const Group&) = delete;
    ~Group() {
      const std::size_t made = std::min(packed.size(), room.size());
      for (std::size_t k = 0; k < made; ++k) {
        if (packed[k]) packed_pool().give(std::move(packed[k]), room[k]);
      }
    }
    // Chunk k's buffer, of at least `bytes` bytes.
    unsigned char* make_room(std::size_t k, std::size_t bytes) {
      auto [buffer, got] = packed_pool().take(bytes);
      packed[k] = std::move(buffer);
      room[k] = got;
      return packed[k].get();
    }
  };
  const auto compress = [&](Group& group) {
    ThreadBuffers& buffers = thread_buffers(layout.level);
    std::unique_ptr<unsigned char[]> own;
    unsigned char* const shuffled = transposed ? shuffled_room(buffers, chunk_bytes, own) : nullptr;
    group.room.assign(group.count, 0);
    group.packed.resize(group.count);
    group.size.assign(group.count, 0);
    std::vector<unsigned char> padded;  // the edge chunk's rows, padded once for all its components
    std::uint64_t padded_row0 = std::numeric_limits<std::uint64_t>::max();
    for (std::uint64_t k = 0; k < group.count; ++k) {
      const std::uint64_t row0 = (group.first + k) / C * layout.chunk_rows, component = (group.first + k) % C;
      const std::uint64_t rows = std::min(layout.chunk_rows, layout.rows - row0);
      const auto* source = reinterpret_cast<const unsigned char*>(data) + row0 * layout.row_bytes;
      const unsigned char* chunk = padded_row0 == row0 ? padded.data() : whole_chunk(source, rows, layout, padded);
      if (rows < layout.chunk_rows) padded_row0 = row0;
      // A single-component chunk equal to the thread's last one: its stream again.
      const bool reusable = C == 1 && chunk_bytes <= reused_chunk_bytes;
      if (reusable && buffers.last_chunk.size() == chunk_bytes && buffers.last_element_size == layout.element_size &&
          buffers.last_row_elements == row_elements && std::memcmp(buffers.last_chunk.data(), chunk, chunk_bytes) == 0) {
        group.make_room(k, out_bytes);
        std::memcpy(group.packed[k].get(), buffers.last_stream.data(), buffers.last_stream.size());
        group.size[k] = buffers.last_stream.size();
        continue;
      }
      // A component of zeros (the z of positions on the ground, the x and y of yaw quaternions: three of a sketch's
      // seven chunks a frame) needs no gather: its stream is the same for every such chunk.
      if (C > 1 && zero_component(chunk + component * layout.element_size, chunk_bytes / layout.element_size,
                                  layout.element_size, C * layout.element_size)) {
        int status = 0;
        group.make_room(k, out_bytes);
        group.size[k] = buffers.deflater->deflate_zeros(chunk_bytes, group.packed[k].get(), out_bytes, &status);
        if (group.size[k] == 0) not_deflated(where, group.first + k, status);
        continue;
      }
      const unsigned char* const raw = chunk;  // the chunk's bytes before the shuffle
      if (transposed) {
        shuffle(chunk + component * layout.element_size, chunk_bytes / layout.element_size, layout.element_size,
                C * layout.element_size, shuffled);
        chunk = shuffled;
      }
      // The shuffled chunk's byte planes (one of a chunk that is not shuffled), an element's value one row earlier
      // row_elements bytes back in its plane; deflated straight into the group's buffer (new and uninitialised, or
      // holding an earlier stream: only the first size[k] bytes, written here, are read; aligned for the file
      // driver's direct writes, direct_write_driver.h, so a chunk of 1 MiB or more goes to the disk without a copy
      // into the page cache).
      int status = 0;
      group.make_room(k, out_bytes);
      const PlaneCodes* plane_codes = component < codes.by_component.size() ? codes.by_component[component].get() : nullptr;
      group.size[k] = buffers.deflater->deflate(chunk, chunk_bytes, layout.element_size, row_elements,
                                                group.packed[k].get(), out_bytes, &status, plane_codes);
      if (group.size[k] == 0) not_deflated(where, group.first + k, status);  // a failure, not an empty chunk
      if (reusable) {
        buffers.last_chunk.assign(raw, raw + chunk_bytes);
        buffers.last_stream.assign(group.packed[k].get(), group.packed[k].get() + group.size[k]);
        buffers.last_element_size = layout.element_size;
        buffers.last_row_elements = row_elements;
      }
    }
  };
  const auto hand_over = [&](const Group& group) {
    for (std::uint64_t k = 0; k < group.count; ++k) {
      write((group.first + k) / C * layout.chunk_rows, (group.first + k) % C, group.packed[k].get(), group.size[k]);
    }
  };

  // A pipeline: groups are compressed on every thread and written one after the other in order as they come,
  // while the next ones compress. Writing is one thread's work at a time (libhdf5 is never called concurrently);
  // compressed in batches and then written, the other threads waited while a batch was written and the writer
  // waited for a batch's slowest group (at 10,000 agents a block is only one or two batches of 32).
  // Whole rows of chunks (every component of the same rows) in a group, so that one thread reads those rows out of
  // memory once and takes each component from its cache.
  const std::uint64_t group_size = C * std::max<std::uint64_t>(1, group_chunks / C);
  // No exception leaves a stage (oneTBB frees an item only after its stage returns: one thrown through it leaked the
  // group): the first failure is kept, the input stops, the groups still in flight are dropped unwritten, and the
  // failure is rethrown once the pipeline has drained.
  std::exception_ptr failure;
  std::mutex failure_mutex;
  std::atomic<bool> failed{false};
  const auto keep = [&](std::exception_ptr e) {
    std::lock_guard lock(failure_mutex);
    if (!failure) failure = std::move(e);
    failed = true;
  };
  std::uint64_t next = 0;
  tbb::parallel_pipeline(
      groups_in_flight,
      tbb::make_filter<void, std::shared_ptr<Group>>(
          tbb::filter_mode::serial_in_order,
          [&](tbb::flow_control& control) -> std::shared_ptr<Group> {
            if (next >= chunks || failed) {
              control.stop();
              return nullptr;
            }
            try {
              auto group = std::make_shared<Group>();
              group->first = next;
              group->count = std::min(group_size, chunks - next);
              next += group->count;
              return group;
            } catch (...) {
              keep(std::current_exception());
              control.stop();
              return nullptr;
            }
          }) &
          tbb::make_filter<std::shared_ptr<Group>, std::shared_ptr<Group>>(
              tbb::filter_mode::parallel,
              [&](std::shared_ptr<Group> group) {
                if (!failed) {
                  try {
                    compress(*group);
                  } catch (...) {
                    keep(std::current_exception());
                  }
                }
                return group;
              }) &
          tbb::make_filter<std::shared_ptr<Group>, void>(tbb::filter_mode::serial_in_order,
                                                          [&](const std::shared_ptr<Group>& group) {
                                                            if (failed) return;
                                                            try {
                                                              hand_over(*group);
                                                            } catch (...) {
                                                              keep(std::current_exception());
                                                            }
                                                          }));
  if (failure) std::rethrow_exception(failure);
}

}  // namespace throng::h5::detail
