#include "chunk_deflate.h"

#include <isa-l/igzip_lib.h>

#if defined(__x86_64__)
#include <immintrin.h>
#endif
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace throng::h5::detail {
namespace {

// ISA-L 2.30's AVX2 and AVX-512 code (deflate and Adler-32) returns with the upper halves of the vector registers
// dirty (no vzeroupper): every SSE instruction after it, on that thread, then pays for merging them, and throng's
// code (built for baseline x86-64, SSE2) ran 3.6x slower on that thread (a float loop 11.7 -> 42.7 ms; the sketch's
// simulation 2x). One vzeroupper after each call clears them; it leaves the low 128 bits that SSE code uses
// untouched. In a function of its own built for AVX, so that the compiler knows what the instruction clobbers.
#if defined(__x86_64__)
__attribute__((target("avx"))) void zero_upper_halves() { _mm256_zeroupper(); }
#endif

int isal_level(int zlib_level) {
  if (zlib_level <= 1) return 1;
  return zlib_level <= 5 ? 2 : 3;
}

std::size_t level_buffer_bytes(int isal_level) {
  switch (isal_level) {
    case 1: return ISAL_DEF_LVL1_DEFAULT;
    case 2: return ISAL_DEF_LVL2_DEFAULT;
    default: return ISAL_DEF_LVL3_DEFAULT;
  }
}

// Stored blocks hold at most 65,535 bytes each, behind 5 bytes of header (RFC 1951, 3.2.4).
constexpr std::size_t stored_block_bytes = 65535;

// Appends `bytes` bytes at `in` to `out` as stored blocks, the last one final when `last`; returns the bytes written.
// The stream is on a byte boundary here (the start, or after ISA-L's FULL_FLUSH), so each block's 3 header bits
// take a whole byte.
std::size_t store(const unsigned char* in, std::size_t bytes, bool last, unsigned char* out) {
  std::size_t written = 0;
  for (std::size_t done = 0; done < bytes;) {
    const std::size_t n = std::min(stored_block_bytes, bytes - done);
    const auto len = static_cast<std::uint16_t>(n), nlen = static_cast<std::uint16_t>(~len);
    out[written++] = (last && done + n == bytes) ? 1 : 0;  // BFINAL, BTYPE 00 (stored)
    out[written++] = static_cast<unsigned char>(len & 0xff);
    out[written++] = static_cast<unsigned char>(len >> 8);
    out[written++] = static_cast<unsigned char>(nlen & 0xff);
    out[written++] = static_cast<unsigned char>(nlen >> 8);
    std::memcpy(out + written, in + done, n);
    written += n;
    done += n;
  }
  return written;
}

// How many of the 64 bytes at a equal those at b (64 bytes too).
std::size_t equal_bytes(const unsigned char* a, const unsigned char* b) {
  std::size_t count = 0;
#if defined(__SSE2__)
  for (std::size_t i = 0; i < 64; i += 16) {
    const __m128i x = _mm_loadu_si128(reinterpret_cast<const __m128i*>(a + i));
    const __m128i y = _mm_loadu_si128(reinterpret_cast<const __m128i*>(b + i));
    count += static_cast<std::size_t>(__builtin_popcount(static_cast<unsigned>(_mm_movemask_epi8(_mm_cmpeq_epi8(x, y)))));
  }
#else
  for (std::size_t i = 0; i < 64; ++i) count += a[i] == b[i];
#endif
  return count;
}

// Whether the `bytes` bytes at `data` are all zero.
bool all_zero(const unsigned char* data, std::size_t bytes) {
  std::size_t i = 0;
  for (; i + 64 <= bytes; i += 64) {
    std::uint64_t words[8];
    std::memcpy(words, data + i, 64);
    std::uint64_t any = 0;
    for (const std::uint64_t w : words) any |= w;
    if (any != 0) return false;
  }
  for (; i < bytes; ++i) {
    if (data[i] != 0) return false;
  }
  return true;
}

// Which of a chunk's `planes` planes (bytes / planes bytes each) look like noise: none for a chunk of one plane, of
// more than NoisePlanes holds, or not of whole planes. deflate() stores those planes; structured_planes() skips them.
constexpr std::size_t most_planes = 16;
using NoisePlanes = std::array<bool, most_planes>;
NoisePlanes noise_planes(const unsigned char* chunk, std::size_t bytes, std::size_t planes, std::size_t row_elements) {
  NoisePlanes noise{};
  const std::size_t n = planes > 0 ? bytes / planes : bytes;
  if (planes > 1 && planes <= most_planes && n * planes == bytes) {
    for (std::size_t j = 0; j < planes; ++j) noise[j] = looks_like_noise(chunk + j * n, n, row_elements);
  }
  return noise;
}

}  // namespace

void clear_upper_vector_state() {
#if defined(__x86_64__)
  static const bool has_avx = __builtin_cpu_supports("avx");
  if (has_avx) zero_upper_halves();
#endif
}

bool looks_like_noise(const unsigned char* plane, std::size_t n, std::size_t row_elements) {
  constexpr std::size_t window = 64, windows = 16;
  if (n < 4096) return false;
  // Four histograms, so that consecutive equal bytes do not wait on one counter.
  std::array<std::array<std::uint32_t, 256>, 4> counts{};
  std::size_t runs = 0, run_samples = 0, repeats = 0, repeat_samples = 0;
  for (std::size_t k = 0; k < windows; ++k) {
    const std::size_t start = (n - window) * k / (windows - 1);
    const unsigned char* p = plane + start;
    for (std::size_t i = 0; i < window; i += 4) {
      ++counts[0][p[i]];
      ++counts[1][p[i + 1]];
      ++counts[2][p[i + 2]];
      ++counts[3][p[i + 3]];
    }
    if (start >= 1) {
      runs += equal_bytes(p, p - 1);
      run_samples += window;
    }
    if (row_elements > 0 && start >= row_elements) {
      repeats += equal_bytes(p, p - row_elements);
      repeat_samples += window;
    }
    // The run and repeat tests below can only fail from here on (at most 15 windows take samples, 960 bytes): a
    // plane of runs (a constant one, the sign and exponent bytes) is told after two windows.
    if (32 * runs > 15 * window || 32 * repeats > 15 * window) return false;
  }
  // Uniform random bytes: E[Σ c²] = m + m(m - 1)/256, with a standard deviation of about 0.088 m at m = 1,024
  // samples; 0.1 m²/256 more is 4.5 of them.
  constexpr std::uint64_t m = window * windows;
  std::uint64_t squares = 0;
  for (std::size_t v = 0; v < 256; ++v) {
    const std::uint64_t c = std::uint64_t{counts[0][v]} + counts[1][v] + counts[2][v] + counts[3][v];
    squares += c * c;
  }
  if (256 * squares > m * m + 256 * m + m * m / 10) return false;
  // Random bytes repeat one in 256 times; 1 in 32 is 8 times that.
  if (32 * runs > run_samples) return false;
  return !(repeat_samples > 0 && 32 * repeats > repeat_samples);
}

ChunkDeflater::ChunkDeflater(int zlib_level)
    : level_(isal_level(zlib_level)),
      level_bytes_(level_buffer_bytes(level_)),
      // Left uninitialised at level 1 (ISA-L's level 1 resets what it reads of it: zeroing cost about 1 % of
      // `throng sketch` at 10,000 agents); levels 2-3 gave the same streams from garbage too, but valgrind saw their
      // assembly branch on it: zeroed there.
      level_buffer_(std::make_unique_for_overwrite<std::uint8_t[]>(level_bytes_)) {
  if (level_ > 1) std::memset(level_buffer_.get(), 0, level_bytes_);
}

std::size_t ChunkDeflater::bound(std::size_t bytes, std::size_t planes) {
  // Every byte stored at worst (ISA-L falls back to stored blocks too), 5 bytes a block; per run of planes (at most
  // `planes` of them), one more partial block, ISA-L's largest block header and its flush's empty stored block;
  // the zlib header (2 bytes) and Adler-32 (4).
  return bytes + 5 * (bytes / stored_block_bytes + 1) + planes * (5 + ISAL_DEF_MAX_HDR_SIZE + 5) + 6;
}

std::vector<unsigned char> structured_planes(const unsigned char* chunk, std::size_t bytes, std::size_t planes,
                                             std::size_t row_elements) {
  std::vector<unsigned char> kept;
  const NoisePlanes noise = noise_planes(chunk, bytes, planes, row_elements);
  const auto noisy = static_cast<std::size_t>(std::count(noise.begin(), noise.end(), true));
  if (noisy == 0 || noisy == planes) return kept;
  const std::size_t n = bytes / planes;
  kept.reserve((planes - noisy) * n);
  for (std::size_t j = 0; j < planes; ++j) {
    if (!noise[j]) kept.insert(kept.end(), chunk + j * n, chunk + (j + 1) * n);
  }
  return kept;
}

PlaneCodes::PlaneCodes(const unsigned char* sample, std::size_t bytes) : tables_(std::make_unique<isal_hufftables>()) {
  // isal_update_histogram takes an int.
  if (bytes == 0 || bytes > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    throw std::logic_error("PlaneCodes: a sample of 1 to 2^31 - 1 bytes expected, not " + std::to_string(bytes));
  }
  isal_huff_histogram histogram{};
  isal_update_histogram(const_cast<std::uint8_t*>(sample), static_cast<int>(bytes), &histogram);
  clear_upper_vector_state();
  // Every symbol gets a code (ISA-L's contract for custom tables), so any chunk's planes can be coded.
  if (isal_create_hufftables(tables_.get(), &histogram) != 0) throw std::logic_error("PlaneCodes: ISA-L made no codes");
  clear_upper_vector_state();
}

PlaneCodes::~PlaneCodes() = default;

std::size_t ChunkDeflater::run_isal(const unsigned char* in, std::size_t bytes, bool zlib, bool last, unsigned char* out,
                                    std::size_t out_bytes, int* status, const PlaneCodes* codes) {
  // Value-initialised first: 2.30's init leaves hist_bits (the match window) unset, and garbage there would make a
  // chunk's bytes differ from run to run (0: the default, 32 KiB).
  isal_zstream stream{};
  isal_deflate_stateless_init(&stream);
  stream.hist_bits = 0;
  if (codes != nullptr) {  // level 0 with the dataset's codes: no level buffer, no codes built here
    stream.level = 0;
    if (isal_deflate_set_hufftables(&stream, &codes->tables(), IGZIP_HUFFTABLE_CUSTOM) != COMP_OK) {
      *status = ISAL_INVALID_OPERATION;
      return 0;
    }
  } else {
    stream.level = static_cast<std::uint32_t>(level_);
    stream.level_buf = level_buffer_.get();
    stream.level_buf_size = static_cast<std::uint32_t>(level_bytes_);
  }
  stream.gzip_flag = zlib ? IGZIP_ZLIB : IGZIP_DEFLATE;  // a zlib header and Adler-32 trailer, or neither
  stream.end_of_stream = last ? 1 : 0;
  stream.flush = last ? NO_FLUSH : FULL_FLUSH;  // not last: byte-aligned, the next blocks follow
  stream.next_in = const_cast<std::uint8_t*>(in);
  stream.avail_in = static_cast<std::uint32_t>(bytes);
  stream.next_out = out;
  stream.avail_out = static_cast<std::uint32_t>(out_bytes);
  const int result = isal_deflate_stateless(&stream);
  clear_upper_vector_state();
  if (result != COMP_OK) {
    *status = result;
    return 0;
  }
  return stream.total_out;
}

void ChunkDeflater::require_room(std::size_t bytes, std::size_t planes, std::size_t out_bytes) {
  if (bytes > std::numeric_limits<std::uint32_t>::max() || out_bytes < bound(bytes, planes)) {
    throw std::logic_error("ChunkDeflater: a chunk of " + std::to_string(bytes) + " bytes needs " +
                           std::to_string(bound(bytes, planes)) + " bytes of room within ISA-L's 32-bit sizes, not " +
                           std::to_string(out_bytes));
  }
}

std::size_t ChunkDeflater::zeros_stream(const unsigned char* zeros, std::size_t bytes, unsigned char* out,
                                        std::size_t out_bytes, int* status) {
  if (zero_bytes_ != bytes || zero_stream_.empty()) {
    std::vector<unsigned char> made_here;
    if (zeros == nullptr) {
      made_here.assign(bytes, 0);
      zeros = made_here.data();
    }
    const std::size_t made = run_isal(zeros, bytes, true, true, out, out_bytes, status);
    if (made == 0) return 0;
    zero_stream_.assign(out, out + made);
    zero_bytes_ = bytes;
    return made;
  }
  std::memcpy(out, zero_stream_.data(), zero_stream_.size());
  return zero_stream_.size();
}

std::size_t ChunkDeflater::deflate_zeros(std::size_t bytes, unsigned char* out, std::size_t out_bytes, int* status) {
  *status = 0;
  require_room(bytes, 1, out_bytes);
  return zeros_stream(nullptr, bytes, out, out_bytes, status);
}

std::size_t ChunkDeflater::deflate(const unsigned char* chunk, std::size_t bytes, std::size_t planes,
                                   std::size_t row_elements, unsigned char* out, std::size_t out_bytes, int* status,
                                   const PlaneCodes* codes) {
  *status = 0;
  require_room(bytes, planes, out_bytes);
  if (all_zero(chunk, bytes)) return zeros_stream(chunk, bytes, out, out_bytes, status);
  const NoisePlanes noise = noise_planes(chunk, bytes, planes, row_elements);
  const bool any_noise = std::find(noise.begin(), noise.end(), true) != noise.end();
  const std::size_t n = planes > 0 ? bytes / planes : bytes;
  if (!any_noise) return run_isal(chunk, bytes, true, true, out, out_bytes, status);  // the whole chunk deflated

  // zlib's header for a 32 KiB window at its fastest levels (CMF 0x78, FLG 0x01: 0x7801 is a multiple of 31).
  std::size_t written = 0;
  out[written++] = 0x78;
  out[written++] = 0x01;
  for (std::size_t first = 0; first < planes;) {  // runs of planes alike: stored, or deflated by ISA-L
    std::size_t end = first + 1;
    while (end < planes && noise[end] == noise[first]) ++end;
    const bool last = end == planes;
    const unsigned char* in = chunk + first * n;
    const std::size_t run_bytes = (end - first) * n;
    if (noise[first]) {
      written += store(in, run_bytes, last, out + written);
    } else {
      const std::size_t made = run_isal(in, run_bytes, false, last, out + written, out_bytes - written, status, codes);
      if (made == 0) return 0;
      written += made;
    }
    first = end;
  }
  const std::uint32_t adler = isal_adler32(1, chunk, bytes);  // of the uncompressed bytes, big-endian
  clear_upper_vector_state();
  for (int shift = 24; shift >= 0; shift -= 8) out[written++] = static_cast<unsigned char>(adler >> shift);
  return written;
}

}  // namespace throng::h5::detail
