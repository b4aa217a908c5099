// One chunk's zlib stream with its noise planes stored (io/src/chunk_deflate.h): zlib inflates every stream back
// to the chunk, the planes that are noise are stored and only those, planes that repeat a row earlier or hold runs
// are deflated, and a chunk of zeros gives ISA-L's own stream every time.
#include "chunk_deflate.h"

#include <catch2/catch.hpp>
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

using namespace throng::h5::detail;

namespace {

// The shuffle filter's byte planes of `values` (8-byte elements): byte j of element i at j × n + i.
std::vector<unsigned char> planes_of(const std::vector<double>& values) {
  const std::size_t n = values.size();
  std::vector<unsigned char> out(8 * n);
  for (std::size_t i = 0; i < n; ++i) {
    unsigned char b[8];
    std::memcpy(b, &values[i], 8);
    for (std::size_t j = 0; j < 8; ++j) out[j * n + i] = b[j];
  }
  return out;
}

struct Deflated {
  std::vector<unsigned char> stream;
  int status = 0;
};

Deflated deflate_chunk(ChunkDeflater& deflater, const std::vector<unsigned char>& chunk, std::size_t planes,
                       std::size_t row_elements) {
  Deflated d;
  d.stream.resize(ChunkDeflater::bound(chunk.size(), planes));
  const std::size_t made =
      deflater.deflate(chunk.data(), chunk.size(), planes, row_elements, d.stream.data(), d.stream.size(), &d.status);
  d.stream.resize(made);
  return d;
}

// zlib's inflate of a whole zlib stream (header and Adler-32 checked by zlib), or empty when it fails.
std::vector<unsigned char> inflate_stream(const std::vector<unsigned char>& stream, std::size_t bytes) {
  std::vector<unsigned char> out(bytes + 1);
  uLongf length = static_cast<uLongf>(out.size());
  if (uncompress(out.data(), &length, stream.data(), static_cast<uLong>(stream.size())) != Z_OK) return {};
  out.resize(length);
  return out;
}

// Positions along a walk: the high bytes alike from agent to agent, the low ones noise.
std::vector<double> walk(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = 40.0 + 0.01 * static_cast<double>(i) + jitter(random);
  return v;
}

}  // namespace

TEST_CASE("looks_like_noise: random bytes are noise, and constant, run-length or row-repeating planes are not") {
  std::mt19937_64 random(3);
  std::vector<unsigned char> plane(20'000);
  for (auto& b : plane) b = static_cast<unsigned char>(random());
  CHECK(looks_like_noise(plane.data(), plane.size(), 0));
  // Small planes are never called noise.
  CHECK_FALSE(looks_like_noise(plane.data(), 4095, 0));
  CHECK(looks_like_noise(plane.data(), 4096, 0));

  std::vector<unsigned char> constant(20'000, 0x40);
  CHECK_FALSE(looks_like_noise(constant.data(), constant.size(), 0));
  // A fifth of the plane constant (agents not yet in the crowd): the byte histogram is far from even.
  std::vector<unsigned char> part = plane;
  std::fill(part.begin() + 16'000, part.end(), 0);
  CHECK_FALSE(looks_like_noise(part.data(), part.size(), 0));
  // Every byte value in turn: an even histogram, but runs of equal bytes.
  std::vector<unsigned char> runs(20'000);
  for (std::size_t i = 0; i < runs.size(); ++i) runs[i] = static_cast<unsigned char>(random() % 256 > 40 ? i / 8 : i);
  CHECK_FALSE(looks_like_noise(runs.data(), runs.size(), 0));
  // Random rows of 5,000 bytes, each the same as the one before (agents holding still from frame to frame).
  std::vector<unsigned char> rows(20'000);
  for (std::size_t i = 0; i < rows.size(); ++i) rows[i] = plane[i % 5'000];
  CHECK_FALSE(looks_like_noise(rows.data(), rows.size(), 5'000));
  CHECK(looks_like_noise(rows.data(), rows.size(), 0));  // not told where a row starts: it looks like noise
}

TEST_CASE("a chunk with noise planes: zlib inflates it, the noise is stored and the high bytes deflated") {
  const std::size_t n = 10'000;
  const std::vector<unsigned char> chunk = planes_of(walk(n, 11));
  // Which planes are noise: the low six bytes of the mantissa, not the sign, exponent and leading bits.
  std::size_t noise_planes = 0;
  for (std::size_t j = 0; j < 8; ++j) noise_planes += looks_like_noise(chunk.data() + j * n, n, 0);
  INFO(noise_planes << " noise planes");
  CHECK(noise_planes >= 4);
  CHECK(noise_planes <= 6);
  CHECK_FALSE(looks_like_noise(chunk.data() + 7 * n, n, 0));

  ChunkDeflater deflater(1);
  const Deflated d = deflate_chunk(deflater, chunk, 8, 0);
  REQUIRE(d.status == 0);
  REQUIRE(!d.stream.empty());
  CHECK(inflate_stream(d.stream, chunk.size()) == chunk);
  // zlib's header, and the noise stored: the stream holds each noise plane's n bytes verbatim, and the rest shrank.
  CHECK(d.stream[0] == 0x78);
  CHECK(d.stream.size() >= noise_planes * n);
  CHECK(d.stream.size() < noise_planes * n + (8 - noise_planes) * n / 2);
  for (std::size_t j = 0; j < 8; ++j) {
    if (!looks_like_noise(chunk.data() + j * n, n, 0)) continue;
    const auto* plane = chunk.data() + j * n;
    CHECK(std::search(d.stream.begin(), d.stream.end(), plane, plane + n) != d.stream.end());
  }
  // The same chunk, the same stream (from this deflater again, and from a new one).
  CHECK(deflate_chunk(deflater, chunk, 8, 0).stream == d.stream);
  ChunkDeflater other(1);
  CHECK(deflate_chunk(other, chunk, 8, 0).stream == d.stream);
}

TEST_CASE("a chunk whose rows repeat is deflated whole, and finds the repeats") {
  // Eight rows (frames) of 1,000 agents, each frame the same random doubles: every plane repeats a row earlier.
  const std::vector<double> frame = walk(1'000, 5);
  std::vector<double> frames;
  for (int r = 0; r < 8; ++r) frames.insert(frames.end(), frame.begin(), frame.end());
  const std::vector<unsigned char> chunk = planes_of(frames);
  for (std::size_t j = 0; j < 8; ++j) CHECK_FALSE(looks_like_noise(chunk.data() + j * 8'000, 8'000, 1'000));
  ChunkDeflater deflater(1);
  const Deflated d = deflate_chunk(deflater, chunk, 8, 1'000);
  REQUIRE(d.status == 0);
  CHECK(inflate_stream(d.stream, chunk.size()) == chunk);
  // Stored, the five or six noise planes would take 8,000 bytes each (40-48 KB of the 64); deflated, the repeats
  // are found (ISA-L's level 1 finds most of them: 34 % of the bytes kept).
  CHECK(d.stream.size() < chunk.size() / 2);
}

TEST_CASE("chunks of zeros give ISA-L's own stream again, and levels 4 and 9 and unshuffled chunks inflate back") {
  const std::vector<unsigned char> zeros(80'000, 0);
  ChunkDeflater fresh(1), reused(1);
  const Deflated first = deflate_chunk(reused, zeros, 8, 0);
  REQUIRE(first.status == 0);
  CHECK(inflate_stream(first.stream, zeros.size()) == zeros);
  CHECK(first.stream.size() < 200);
  // A noisy chunk in between, then zeros again: the same bytes as a deflater that never saw a chunk before.
  (void)deflate_chunk(reused, planes_of(walk(10'000, 2)), 8, 0);
  CHECK(deflate_chunk(reused, zeros, 8, 0).stream == deflate_chunk(fresh, zeros, 8, 0).stream);
  // Zeros of another length: their own stream.
  const std::vector<unsigned char> fewer(40'000, 0);
  CHECK(inflate_stream(deflate_chunk(reused, fewer, 8, 0).stream, fewer.size()) == fewer);

  const std::vector<unsigned char> chunk = planes_of(walk(10'000, 9));
  for (const int level : {4, 9}) {
    ChunkDeflater deflater(level);
    const Deflated d = deflate_chunk(deflater, chunk, 8, 0);
    REQUIRE(d.status == 0);
    CHECK(inflate_stream(d.stream, chunk.size()) == chunk);
  }
  ChunkDeflater whole(1);
  const Deflated one_plane = deflate_chunk(whole, chunk, 1, 0);  // not shuffled: deflated whole
  REQUIRE(one_plane.status == 0);
  CHECK(inflate_stream(one_plane.stream, chunk.size()) == chunk);
}

TEST_CASE("noise longer than a stored block is split into blocks of at most 65,535 bytes") {
  // 8 planes of 100,000 bytes of noise: one run of 800,000 bytes stored, in 13 blocks; zlib checks every length.
  std::mt19937_64 random(17);
  std::vector<unsigned char> chunk(800'000);
  for (auto& b : chunk) b = static_cast<unsigned char>(random());
  ChunkDeflater deflater(1);
  const Deflated d = deflate_chunk(deflater, chunk, 8, 0);
  REQUIRE(d.status == 0);
  CHECK(d.stream.size() <= ChunkDeflater::bound(chunk.size(), 8));
  CHECK(d.stream.size() == 2 + chunk.size() + 5 * 13 + 4);  // header, 13 blocks of 5-byte headers, Adler-32
  CHECK(inflate_stream(d.stream, chunk.size()) == chunk);
}

TEST_CASE("plane layouts of every kind, runs deflated between stored ones, inflate back at levels 1, 4 and 9") {
  // Planes of n bytes, each noise (N), runs of one byte value in turn (S), zeros (Z) or 0xff (F), in orders that put
  // a deflated run before a stored one (the byte boundary of ISA-L's FULL_FLUSH), a stored run last, and 16 planes.
  const std::size_t n = 6'000;
  std::mt19937_64 random(23);
  const auto plane = [&](char kind) {
    std::vector<unsigned char> p(n);
    for (std::size_t i = 0; i < n; ++i) {
      switch (kind) {
        case 'N': p[i] = static_cast<unsigned char>(random()); break;
        case 'S': p[i] = static_cast<unsigned char>(i / 37); break;
        case 'Z': p[i] = 0; break;
        default: p[i] = 0xff; break;
      }
    }
    return p;
  };
  for (const std::string layout : {"SNSNNSNZ", "SN", "NS", "ZNFN", "NNNNNNNN", "SSSSSSSS", "SNZFNSNNFZSNSNNN"}) {
    std::vector<unsigned char> chunk;
    std::size_t noise = 0;
    for (const char kind : layout) {
      const std::vector<unsigned char> p = plane(kind);
      chunk.insert(chunk.end(), p.begin(), p.end());
      noise += kind == 'N';
    }
    for (std::size_t j = 0; j < layout.size(); ++j) {
      CHECK(looks_like_noise(chunk.data() + j * n, n, 0) == (layout[j] == 'N'));
    }
    for (const int level : {1, 4, 9}) {
      INFO(layout << " at level " << level);
      ChunkDeflater deflater(level);
      const Deflated d = deflate_chunk(deflater, chunk, layout.size(), 0);
      REQUIRE(d.status == 0);
      CHECK(d.stream.size() <= ChunkDeflater::bound(chunk.size(), layout.size()));
      CHECK(inflate_stream(d.stream, chunk.size()) == chunk);
      CHECK(d.stream.size() >= noise * n);                   // the noise kept whole
      CHECK(d.stream.size() < noise * n + 1'000 * layout.size());  // the rest shrank to little
    }
  }
}

TEST_CASE("a deflater used before gives a fresh one's stream, at levels 1, 4 and 9") {
  // ISA-L's level buffer is kept from chunk to chunk (zeroed once at levels 2-3): what it held must not show.
  const std::vector<unsigned char> a = planes_of(walk(10'000, 31)), b = planes_of(walk(10'000, 32));
  std::vector<unsigned char> ramp(80'000);
  for (std::size_t i = 0; i < ramp.size(); ++i) ramp[i] = static_cast<unsigned char>(i / 300);
  for (const int level : {1, 4, 9}) {
    INFO("level " << level);
    ChunkDeflater used(level);
    (void)deflate_chunk(used, a, 8, 0);
    (void)deflate_chunk(used, ramp, 1, 0);
    ChunkDeflater fresh(level), fresh_ramp(level);
    CHECK(deflate_chunk(used, b, 8, 0).stream == deflate_chunk(fresh, b, 8, 0).stream);
    CHECK(deflate_chunk(used, ramp, 8, 0).stream == deflate_chunk(fresh_ramp, ramp, 8, 0).stream);
  }
}

TEST_CASE("the deflater refuses room under its bound") {
  ChunkDeflater deflater(1);
  std::vector<unsigned char> chunk(10'000, 1), out(ChunkDeflater::bound(chunk.size(), 8) - 1);
  int status = 0;
  CHECK_THROWS_AS(deflater.deflate(chunk.data(), chunk.size(), 8, 0, out.data(), out.size(), &status), std::logic_error);
}

TEST_CASE("plane codes made from one chunk code any chunk's structured planes: zlib inflates them back") {
  const std::size_t n = 10'000;
  const std::vector<unsigned char> first = planes_of(walk(n, 11));
  // The structured planes are the planes that are not noise, one after the other; none for a chunk without noise
  // or all noise.
  std::size_t noise_planes = 0;
  for (std::size_t j = 0; j < 8; ++j) noise_planes += looks_like_noise(first.data() + j * n, n, 0);
  const std::vector<unsigned char> sample = structured_planes(first.data(), first.size(), 8, 0);
  REQUIRE(sample.size() == (8 - noise_planes) * n);
  CHECK(std::equal(sample.end() - static_cast<std::ptrdiff_t>(n), sample.end(), first.end() - static_cast<std::ptrdiff_t>(n)));
  const std::vector<unsigned char> constant(8 * n, 0x40);
  CHECK(structured_planes(constant.data(), constant.size(), 8, 0).empty());
  std::mt19937_64 random(5);
  std::vector<unsigned char> noise(8 * n);
  for (auto& b : noise) b = static_cast<unsigned char>(random());
  CHECK(structured_planes(noise.data(), noise.size(), 8, 0).empty());

  const PlaneCodes codes(sample.data(), sample.size());
  ChunkDeflater deflater(1);
  // Chunks other than the sample: a later frame of the walk, and a crowd a million metres away whose high bytes
  // never occur in the sample (every symbol has a code).
  std::vector<double> far = walk(n, 12);
  for (double& v : far) v = -1.0e6 - v;
  for (const std::vector<unsigned char>& chunk : {first, planes_of(walk(n, 12)), planes_of(far)}) {
    Deflated coded;
    coded.stream.resize(ChunkDeflater::bound(chunk.size(), 8));
    const std::size_t made = deflater.deflate(chunk.data(), chunk.size(), 8, 0, coded.stream.data(),
                                              coded.stream.size(), &coded.status, &codes);
    REQUIRE(coded.status == 0);
    REQUIRE(made > 0);
    coded.stream.resize(made);
    CHECK(inflate_stream(coded.stream, chunk.size()) == chunk);
    // Not the stream of the dataset's level (the codes were used), of about its length, and the same again from
    // another deflater.
    const Deflated plain = deflate_chunk(deflater, chunk, 8, 0);
    CHECK(coded.stream != plain.stream);
    CHECK(coded.stream.size() < plain.stream.size() * 11 / 10);
    ChunkDeflater other(1);
    std::vector<unsigned char> again(ChunkDeflater::bound(chunk.size(), 8));
    int status = 0;
    again.resize(other.deflate(chunk.data(), chunk.size(), 8, 0, again.data(), again.size(), &status, &codes));
    CHECK(again == coded.stream);
  }
  // A chunk without noise is deflated whole at the dataset's level, codes or not.
  Deflated whole;
  whole.stream.resize(ChunkDeflater::bound(constant.size(), 8));
  whole.stream.resize(deflater.deflate(constant.data(), constant.size(), 8, 0, whole.stream.data(), whole.stream.size(),
                                       &whole.status, &codes));
  CHECK(whole.stream == deflate_chunk(deflater, constant, 8, 0).stream);
}
