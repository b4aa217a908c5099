#include "deflate_filter.h"

#include "chunk_deflate.h"

#include <throng/core/errors.h>

#include <hdf5.h>
#include <isa-l/igzip_lib.h>
#include <zlib.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <mutex>

// libhdf5's own registration, which H5Zregister calls after refusing the predefined filters' ids (below 256), and
// which libhdf5 calls to register them: exported by libhdf5 1.10 (Debian's 1.10.8 included) though not declared in
// its public headers. It replaces a registered filter of the same id.
extern "C" herr_t H5Z_register(const H5Z_class2_t* cls);

namespace throng::h5::detail {
namespace {

std::atomic<std::size_t> inflated{0};

// libhdf5 1.10's bound on a compressed chunk (H5Z_DEFLATE_SIZE_ADJUST): a chunk that does not fit is not compressed.
std::size_t compressed_room(std::size_t bytes) {
  return static_cast<std::size_t>(std::ceil(static_cast<double>(bytes) * static_cast<double>(1.001f))) + 12;
}

// The largest output a chunk may inflate to: libhdf5's chunks are at most 4 GiB.
constexpr std::size_t largest_chunk = std::size_t{1} << 32;

thread_local std::uint64_t decoded_chunk_bytes = 0;

// Room past a known chunk size: an honest stream fills the chunk exactly and ISA-L then still reads its end and
// checksum, which it does only with output room left; a stream that writes into it inflates beyond its chunk.
constexpr std::size_t past_chunk = 64;

// A filter callback fails by returning 0; on success it replaces *buf (allocated with H5allocate_memory, as libhdf5
// allocates the pipeline's buffers) and returns the bytes in it.
std::size_t inflate_chunk(std::size_t bytes, std::size_t* buf_size, void** buf) {
  if (bytes > std::numeric_limits<std::uint32_t>::max()) return 0;
  const std::uint64_t expected = decoded_chunk_bytes;
  if (expected > largest_chunk) return 0;
  // Known: the chunk and a little room, never grown. Unknown: twice the stored size to start with, doubled when
  // full (the last buffer under twice what the stream inflates to).
  const std::size_t most = expected > 0 ? static_cast<std::size_t>(expected) + past_chunk : largest_chunk;
  std::size_t room = expected > 0 ? most : std::max({*buf_size, std::min(2 * bytes, largest_chunk), std::size_t{4096}});
  auto* out = static_cast<std::uint8_t*>(H5allocate_memory(room, false));
  if (out == nullptr) return 0;
  // ISA-L's state (tables and history, about 87 KB): one per thread, made once and initialised for each stream.
  thread_local const std::unique_ptr<inflate_state> kept(new inflate_state);
  inflate_state* state = kept.get();
  isal_inflate_init(state);
  state->crc_flag = ISAL_ZLIB;  // the zlib header parsed, the Adler-32 trailer checked
  state->next_in = static_cast<std::uint8_t*>(*buf);
  state->avail_in = static_cast<std::uint32_t>(bytes);
  std::size_t made = 0;
  for (;;) {
    const std::size_t free_room = std::min<std::size_t>(room - made, std::numeric_limits<std::uint32_t>::max());
    state->next_out = out + made;
    state->avail_out = static_cast<std::uint32_t>(free_room);
    const int status = isal_inflate(state);
    clear_upper_vector_state();
    made += free_room - state->avail_out;
    if (status != ISAL_DECOMP_OK) break;  // damaged, a dictionary asked for, or a wrong checksum
    if (state->block_state == ISAL_BLOCK_FINISH) {
      if (expected > 0 && made > expected) break;  // more than its chunk: a hostile stream
      H5free_memory(*buf);
      *buf = out;
      *buf_size = room;
      inflated.fetch_add(1, std::memory_order_relaxed);
      return made;
    }
    if (state->avail_out != 0) break;  // the input ended before the stream did
    if (room >= most) break;           // beyond its chunk, or beyond any chunk
    room = std::min(2 * room, most);
    auto* grown = static_cast<std::uint8_t*>(H5resize_memory(out, room));
    if (grown == nullptr) break;
    out = grown;
  }
  H5free_memory(out);
  return 0;
}

std::size_t deflate_chunk(int level, std::size_t bytes, std::size_t* buf_size, void** buf) {
  uLongf room = compressed_room(bytes);
  auto* out = static_cast<Bytef*>(H5allocate_memory(room, false));
  if (out == nullptr) return 0;
  if (compress2(out, &room, static_cast<const Bytef*>(*buf), static_cast<uLong>(bytes), level) != Z_OK) {
    H5free_memory(out);
    return 0;
  }
  H5free_memory(*buf);
  *buf = out;
  *buf_size = bytes;
  return room;
}

std::size_t deflate_filter(unsigned flags, std::size_t cd_nelmts, const unsigned cd_values[], std::size_t nbytes,
                           std::size_t* buf_size, void** buf) {
  if (cd_nelmts != 1 || cd_values[0] > 9) return 0;  // what libhdf5 calls an invalid aggression level
  if ((flags & H5Z_FLAG_REVERSE) != 0) return inflate_chunk(nbytes, buf_size, buf);
  return deflate_chunk(static_cast<int>(cd_values[0]), nbytes, buf_size, buf);
}

}  // namespace

void use_isal_inflate() {
  static std::once_flag once;
  std::call_once(once, [] {
    // Only where the library is the 1.10 this filter copies (its encoder's bound; H5Z_register's contract).
    unsigned major = 0, minor = 0, release = 0;
    if (H5get_libversion(&major, &minor, &release) < 0 || major != 1 || minor != 10) return;
    static const H5Z_class2_t filter{H5Z_CLASS_T_VERS, H5Z_FILTER_DEFLATE, 1, 1, "deflate", nullptr, nullptr,
                                     deflate_filter};
    if (H5Z_register(&filter) < 0) throw IoError("libhdf5 refused throng's deflate filter (ISA-L's inflate)");
  });
}

DecodedChunkBytes::DecodedChunkBytes(std::uint64_t bytes) noexcept : previous_(decoded_chunk_bytes) {
  decoded_chunk_bytes = bytes;
}

DecodedChunkBytes::~DecodedChunkBytes() { decoded_chunk_bytes = previous_; }

std::size_t isal_inflated_chunks() { return inflated.load(std::memory_order_relaxed); }

}  // namespace throng::h5::detail
