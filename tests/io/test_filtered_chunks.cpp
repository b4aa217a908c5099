// Compressed datasets are written chunk by chunk, shuffled and deflated in parallel (io/src/filtered_chunks.h):
// what any HDF5 reader gets back is what was written, edge chunks included, and the file's bytes do not depend on
// the thread count.
#include <throng/core/errors.h>
#include <throng/core/parallel.h>
#include <throng/io/hdf5.h>

#include "filtered_chunks.h"

#include <catch2/catch.hpp>
#include <hdf5.h>
#include <zlib.h>

#if defined(__x86_64__)
#include <cpuid.h>
#endif

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "test_paths.h"

using namespace throng;

namespace {

// Rows of 3 values that compress (a slow ramp, as positions are) but are all different.
std::vector<double> ramp(std::uint64_t rows) {
  std::vector<double> v(rows * 3);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = 0.001 * static_cast<double>(i) + (i % 3 == 0 ? 0.5 : 0.0);
  return v;
}

// 8 frames × 5,000 agents × (x, y, z): a walk with noise in its low mantissa bytes, z = 0.
std::vector<double> walk() {
  std::mt19937_64 random(41);
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);
  std::vector<double> v(8 * 5000 * 3, 0.0);
  for (std::size_t t = 0; t < 8; ++t) {
    for (std::size_t a = 0; a < 5000; ++a) {
      v[(t * 5000 + a) * 3] = 12.0 + 0.4 * static_cast<double>(t) + 0.002 * static_cast<double>(a) + jitter(random);
      v[(t * 5000 + a) * 3 + 1] = -30.0 + 0.001 * static_cast<double>(a) + jitter(random);
    }
  }
  return v;
}

std::string bytes_of(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Writes the three numeric kinds, compressed, in chunks of 1,000 rows (the last chunk partial) under `threads`.
void write_all(const std::filesystem::path& path, std::size_t threads) {
  const ThreadLimit limit(threads);
  h5::File f = h5::File::create(path);
  const std::uint64_t rows = 10'500;
  f.root().write("doubles", ramp(rows), {rows, 3}, h5::Layout{true, 1000});
  std::vector<std::int64_t> i64(rows);
  std::vector<std::int32_t> i32(rows);
  for (std::size_t i = 0; i < rows; ++i) {
    i64[i] = static_cast<std::int64_t>(i * i) - 7;
    i32[i] = static_cast<std::int32_t>(i % 977) - 300;
  }
  f.root().write("int64", i64, {rows}, h5::Layout{true, 1000});
  f.root().write("int32", i32, {rows}, h5::Layout{true, 1000});
  f.root().write("one_row", std::vector<double>{1, 2, 3}, {1, 3}, h5::Layout{true});  // one chunk, one row
  // [frames][agents][3], as positions are: chunks of one component (100 frames × 10 agents × 1), the last partial.
  f.root().write("frames", ramp(1050 * 10), {1050, 10, 3}, h5::Layout{true, 100});
  // Frames of 5,000 agents walking (chunks of one frame's component, 5,000 elements: planes long enough to be
  // told noise, chunk_deflate.h): x and y's low bytes noise, stored; their high bytes deflated; z zeros. And the
  // same values unfiltered, for h5py to compare.
  f.root().write("walk", walk(), {8, 5000, 3}, h5::Layout{true, 1});
  f.root().write("walk_plain", walk(), {8, 5000, 3});
  f.close();
}

// The first chunk whose stored bytes differ between the files at a and b in the datasets write_all makes: its
// dataset, offset, lengths, first differing byte, and whether both inflate to the same bytes (a different stream of
// the same chunk, or different data); when every chunk is the same, says so. For the byte test's failure message:
// an intermittent difference (seen in CI only, 7 December 2026) was one chunk's ISA-L stream missing a match that the
// other had, both inflating to the same bytes; 7,521 runs of the test under load here did not bring it back.
std::string first_chunk_difference(const std::filesystem::path& a, const std::filesystem::path& b) {
  const hid_t fa = H5Fopen(a.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), fb = H5Fopen(b.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  std::ostringstream found;
  for (const char* name : {"doubles", "int64", "int32", "one_row", "frames", "walk", "walk_plain"}) {
    const hid_t da = H5Dopen2(fa, name, H5P_DEFAULT), db = H5Dopen2(fb, name, H5P_DEFAULT);
    const hid_t space = H5Dget_space(da);
    hsize_t chunks = 0;
    H5Dget_num_chunks(da, space, &chunks);
    for (hsize_t k = 0; k < chunks && found.tellp() == 0; ++k) {
      hsize_t offset[3] = {0, 0, 0};
      unsigned mask = 0;
      haddr_t address = 0;
      hsize_t size_a = 0, size_b = 0;
      H5Dget_chunk_info(da, space, k, offset, &mask, &address, &size_a);
      H5Dget_chunk_storage_size(db, offset, &size_b);
      std::vector<unsigned char> bytes_a(size_a), bytes_b(size_b);
      std::uint32_t mask_a = 0, mask_b = 0;
      H5Dread_chunk(da, H5P_DEFAULT, offset, &mask_a, bytes_a.data());
      H5Dread_chunk(db, H5P_DEFAULT, offset, &mask_b, bytes_b.data());
      if (bytes_a == bytes_b) continue;
      const auto at = std::mismatch(bytes_a.begin(), bytes_a.end(), bytes_b.begin(), bytes_b.end()).first - bytes_a.begin();
      // Deflated chunks: inflated with zlib, to tell a different stream of the same bytes from different bytes.
      const auto inflated = [](const std::vector<unsigned char>& in) {
        std::vector<unsigned char> out(1 << 22);
        uLongf length = out.size();
        if (uncompress(out.data(), &length, in.data(), in.size()) != Z_OK) return std::vector<unsigned char>{};
        out.resize(length);
        return out;
      };
      const auto ia = inflated(bytes_a), ib = inflated(bytes_b);
      found << name << " chunk at (" << offset[0] << ", " << offset[1] << ", " << offset[2] << "): " << size_a
            << " against " << size_b << " bytes, first different byte " << at << "; "
            << (ia.empty() || ib.empty() ? "not both inflated" : ia == ib ? "both inflate to the same bytes" : "they inflate to different bytes");
    }
    H5Sclose(space);
    H5Dclose(da);
    H5Dclose(db);
    if (found.tellp() != 0) break;
  }
  H5Fclose(fa);
  H5Fclose(fb);
  return found.tellp() != 0 ? found.str() : "every chunk the same: the difference is in the file's other bytes";
}

#if defined(__x86_64__)
// XINUSE (XGETBV with ECX = 1): the register states the processor holds as in use. Bit 2: the upper halves of
// ymm0-15; bit 6: the upper halves of zmm0-15. Empty when the processor cannot report it.
std::optional<std::uint64_t> vector_state_in_use() {
  unsigned a = 0, b = 0, c = 0, d = 0;
  // XGETBV needs OSXSAVE (CPUID 1, ECX bit 27); its ECX = 1 form, CPUID 0xD sub-leaf 1, EAX bit 2.
  if (!__get_cpuid(1, &a, &b, &c, &d) || (c & (1u << 27)) == 0) return std::nullopt;
  if (!__get_cpuid_count(0xD, 1, &a, &b, &c, &d) || (a & 4u) == 0) return std::nullopt;
  std::uint32_t low = 0, high = 0;
  asm volatile("xgetbv" : "=a"(low), "=d"(high) : "c"(1));
  return (static_cast<std::uint64_t>(high) << 32) | low;
}
#endif

}  // namespace

TEST_CASE("compressed datasets read back exactly, edge chunk included, and their bytes do not depend on the thread count") {
  const auto dir = test::scratch_dir("io_filtered_chunks");
  write_all(dir / "one.h5", 1);
  write_all(dir / "two.h5", 2);
  const bool same = bytes_of(dir / "one.h5") == bytes_of(dir / "two.h5");
  INFO("1 thread against 2: " << (same ? std::string("the same") : first_chunk_difference(dir / "one.h5", dir / "two.h5")));
  CHECK(same);
  const h5::File f = h5::File::open(dir / "two.h5");
  const auto doubles = f.root().read_doubles("doubles", 2);
  CHECK(doubles.shape == std::vector<std::uint64_t>{10'500, 3});
  CHECK(doubles.values == ramp(10'500));
  const auto i64 = f.root().read_int64("int64", 1);
  const auto i32 = f.root().read_int32("int32", 1);
  REQUIRE(i64.values.size() == 10'500);
  REQUIRE(i32.values.size() == 10'500);
  for (std::size_t i = 0; i < 10'500; ++i) {
    REQUIRE(i64.values[i] == static_cast<std::int64_t>(i * i) - 7);
    REQUIRE(i32.values[i] == static_cast<std::int32_t>(i % 977) - 300);
  }
  CHECK(f.root().read_doubles("one_row", 2).values == std::vector<double>{1, 2, 3});
  const auto frames = f.root().read_doubles("frames", 3);
  CHECK(frames.shape == std::vector<std::uint64_t>{1050, 10, 3});
  CHECK(frames.values == ramp(1050 * 10));
  CHECK(f.root().read_doubles("walk", 3).values == walk());
  // Compressed: the ramp's 252 KB take far less; the walk's 960 KB about half (a third of it zeros, three
  // quarters of the rest noise kept whole), beside its 960 KB unfiltered.
  CHECK(std::filesystem::file_size(dir / "two.h5") < 200'000 + 960'000 + 600'000);
}

TEST_CASE("h5py reads a dataset written by the parallel chunk writer as libhdf5's own filters would") {
  // An independent reader (h5py over Debian's libhdf5): the filters are shuffle then gzip, every value back.
  const auto dir = test::scratch_dir("io_filtered_chunks_h5py");
  write_all(dir / "f.h5", 2);
  const std::string script =
      "import h5py, numpy as np, sys\n"
      "f = h5py.File(sys.argv[1], 'r')\n"
      "d = f['doubles']\n"
      "assert d.compression == 'gzip' and d.shuffle and d.chunks == (1000, 3), (d.compression, d.shuffle, d.chunks)\n"
      "i = np.arange(10500 * 3)\n"
      "want = (0.001 * i + np.where(i % 3 == 0, 0.5, 0.0)).reshape(10500, 3)\n"
      "assert np.array_equal(d[()], want)\n"
      "assert np.array_equal(f['int32'][()], (np.arange(10500) % 977) - 300)\n"
      "p = f['frames']\n"
      "assert p.compression == 'gzip' and p.shuffle and p.chunks == (100, 10, 1), (p.compression, p.shuffle, p.chunks)\n"
      "i = np.arange(1050 * 10 * 3)\n"
      "want = (0.001 * i + np.where(i % 3 == 0, 0.5, 0.0)).reshape(1050, 10, 3)\n"
      "assert np.array_equal(p[()], want)\n"
      "assert np.array_equal(p[1049, :, 2], want[1049, :, 2])  # one component of the edge chunk\n"
      "w = f['walk']\n"
      "assert w.compression == 'gzip' and w.shuffle and w.chunks == (1, 5000, 1), (w.compression, w.chunks)\n"
      "assert np.array_equal(w[()], f['walk_plain'][()]) and np.all(w[:, :, 2] == 0) and np.all(w[:, :, 0] > 10)\n"
      "print('ok')\n";
  std::ofstream(dir / "check.py") << script;
  std::string out;
  const int code = test::run_command("/usr/bin/python3 " + (dir / "check.py").string() + " " + (dir / "f.h5").string(), &out);
  INFO(out);
  CHECK(code == 0);
  CHECK(out.find("ok") != std::string::npos);
}

TEST_CASE("chunks that do not compress are stored and read back exactly") {
  // Random bits in every byte plane: deflate cannot shrink them, so ISA-L falls back to stored blocks within the
  // bound it was given (filtered_chunks.cpp), and the file holds at least every byte.
  const auto dir = test::scratch_dir("io_filtered_chunks_random");
  std::mt19937_64 random(7);
  std::vector<std::int64_t> noise(20'000 * 3);
  for (std::int64_t& v : noise) v = static_cast<std::int64_t>(random());
  {
    h5::File f = h5::File::create(dir / "noise.h5");
    f.root().write("noise", noise, {20'000, 3}, h5::Layout{true, 4096});
    f.close();
  }
  CHECK(std::filesystem::file_size(dir / "noise.h5") >= noise.size() * sizeof(std::int64_t));
  CHECK(h5::File::open(dir / "noise.h5").root().read_int64("noise", 2).values == noise);
}

#if defined(__x86_64__)
TEST_CASE("writing compressed chunks leaves the upper halves of the vector registers clean") {
  // ISA-L's AVX2 and AVX-512 deflate return with them dirty; SSE code on that thread then ran 3.6x slower until a
  // vzeroupper (filtered_chunks.cpp). One thread: the chunks are compressed on this one. (Where the C library's
  // copies clear them anyway, as its AVX2 memmove does, this passes without the vzeroupper too.)
  const auto before = vector_state_in_use();
  if (!before) {
    SUCCEED("this processor does not report the registers in use (XINUSE)");
    return;
  }
  const ThreadLimit limit(1);
  const auto dir = test::scratch_dir("io_filtered_chunks_vector_state");
  h5::File f = h5::File::create(dir / "f.h5");
  f.root().write("doubles", ramp(10'500), {10'500, 3}, h5::Layout{true, 1000});
  const std::uint64_t after = *vector_state_in_use();
  INFO("XINUSE after writing: 0x" << std::hex << after);
  CHECK((after & ((1u << 2) | (1u << 6))) == 0);
  f.close();
}
#endif

TEST_CASE("a write that fails stops the chunk writer: its error comes back, nothing is written after it") {
  // The failure is carried out of the pipeline (filtered_chunks.cpp), not thrown through it, which leaked the group
  // being written (AddressSanitizer's leak check in scripts/run-sanitizers runs this test).
  const std::vector<double> values = walk();
  const h5::detail::ChunkedLayout layout{8, 5000 * 3 * sizeof(double), 1, sizeof(double), 1, 3};
  for (const std::size_t threads : {1, 2}) {
    const ThreadLimit limit(threads);
    std::vector<std::pair<std::uint64_t, std::uint64_t>> written;
    std::size_t calls = 0;
    // (Called from the pipeline's threads, one call at a time: no Catch assertion in it.)
    const auto write = [&](std::uint64_t row, std::uint64_t component, const unsigned char*, std::size_t) {
      if (++calls == 6) throw IoError("the disk is full");
      written.emplace_back(row, component);
    };
    CHECK_THROWS_WITH(h5::detail::filter_chunks(reinterpret_cast<const std::byte*>(values.data()), layout, "test", write),
                      "the disk is full");
    // The chunks before the failure, in order (rows, then components), and no call after the failing one.
    CHECK(calls == 6);
    REQUIRE(written.size() == 5);
    for (std::size_t k = 0; k < 5; ++k) CHECK(written[k] == std::make_pair<std::uint64_t, std::uint64_t>(k / 3, k % 3));
  }
  // And all 24 chunks, in order, when nothing fails.
  std::vector<std::pair<std::uint64_t, std::uint64_t>> all;
  h5::detail::filter_chunks(reinterpret_cast<const std::byte*>(values.data()), layout, "test",
                            [&](std::uint64_t row, std::uint64_t component, const unsigned char*, std::size_t) {
                              all.emplace_back(row, component);
                            });
  REQUIRE(all.size() == 24);
  for (std::size_t k = 0; k < 24; ++k) CHECK(all[k] == std::make_pair<std::uint64_t, std::uint64_t>(k / 3, k % 3));
}

TEST_CASE("chunks equal to the one before and components of zeros read back exactly, whatever the thread count") {
  // Two shortcuts of the chunk writer: a single-component chunk equal to the last one a thread compressed takes its
  // stream again, and a component that is all zeros is not gathered. Each is given chunks that differ from the ones
  // it would take them for by one element only, at either end.
  constexpr std::uint64_t agents = 5000;
  std::vector<std::int64_t> ids(12 * agents);
  for (std::uint64_t t = 0; t < 12; ++t) {
    for (std::uint64_t a = 0; a < agents; ++a) ids[t * agents + a] = static_cast<std::int64_t>(a * 7 + 3);
  }
  ids[4 * agents + agents - 1] = -1;  // frames 4-7: frame 0's ids but the last
  for (std::uint64_t t = 5; t < 8; ++t) ids[t * agents + agents - 1] = -1;
  ids[9 * agents] = 99;  // frame 9: frame 0's but the first
  for (std::uint64_t a = 0; a < agents; ++a) ids[10 * agents + a] = static_cast<std::int64_t>(a * a);
  std::mt19937_64 random(8);
  std::uniform_real_distribution<double> place(-40.0, 40.0);
  std::vector<double> positions(6 * agents * 3, 0.0);
  for (std::uint64_t t = 0; t < 6; ++t) {
    for (std::uint64_t a = 0; a < agents; ++a) {
      positions[(t * agents + a) * 3] = place(random);
      positions[(t * agents + a) * 3 + 1] = place(random);
    }
  }
  positions[(3 * agents + agents - 1) * 3 + 2] = 0.25;  // z zero in every frame but 3 (its last agent) and 4 (its first)
  positions[(4 * agents) * 3 + 2] = -1e-300;
  const auto dir = test::scratch_dir("io_filtered_chunks_shortcuts");
  for (const std::size_t threads : {1, 2}) {
    const ThreadLimit limit(threads);
    h5::File f = h5::File::create(dir / ("shortcuts" + std::to_string(threads) + ".h5"));
    f.root().write("ids", ids, {12, agents}, h5::Layout{true, 1});
    f.root().write("positions", positions, {6, agents, 3}, h5::Layout{true, 1});
    // The ids' bytes again as int32 pairs: the same chunks' bytes, not the same stream (4-byte planes).
    std::vector<std::int32_t> halves(2 * ids.size());
    std::memcpy(halves.data(), ids.data(), ids.size() * sizeof(std::int64_t));
    f.root().write("halves", halves, {12, 2 * agents}, h5::Layout{true, 1});
    f.close();
  }
  CHECK(bytes_of(dir / "shortcuts1.h5") == bytes_of(dir / "shortcuts2.h5"));
  const h5::File f = h5::File::open(dir / "shortcuts2.h5");
  CHECK(f.root().read_int64("ids", 2).values == ids);
  CHECK(f.root().read_doubles("positions", 3).values == positions);
  std::vector<std::int32_t> halves(2 * ids.size());
  std::memcpy(halves.data(), ids.data(), ids.size() * sizeof(std::int64_t));
  CHECK(f.root().read_int32("halves", 2).values == halves);
}

TEST_CASE("a dataset filtered block by block with its codes kept is the dataset filtered in one call, byte for byte") {
  // Positions (8 frames × 5,000 agents × 3, chunks of one frame's component): the structured planes of x and y are
  // coded with codes made from frame 0 (filtered_chunks.h's DatasetCodes). A streamed file (crowd_stream.cpp)
  // writes them in blocks and keeps the codes from its first block: its chunks are then those of one call.
  const std::vector<double> values = walk();
  const std::uint64_t row_bytes = 5000 * 3 * sizeof(double);
  using Chunks = std::vector<std::pair<std::pair<std::uint64_t, std::uint64_t>, std::vector<unsigned char>>>;
  const auto filter = [&](std::uint64_t first_row, std::uint64_t rows, h5::detail::DatasetCodes* codes, Chunks& out) {
    const h5::detail::ChunkedLayout layout{rows, row_bytes, 1, sizeof(double), 1, 3, codes};
    h5::detail::filter_chunks(reinterpret_cast<const std::byte*>(values.data() + first_row * 5000 * 3), layout, "test",
                              [&](std::uint64_t row, std::uint64_t component, const unsigned char* bytes, std::size_t size) {
                                out.push_back({{first_row + row, component}, std::vector<unsigned char>(bytes, bytes + size)});
                              });
  };
  Chunks whole, blocks, fresh;
  filter(0, 8, nullptr, whole);
  h5::detail::DatasetCodes kept;
  filter(0, 0, &kept, blocks);  // an empty block first: nothing to make the codes from, so none are made yet
  CHECK_FALSE(kept.made);
  filter(0, 3, &kept, blocks);
  filter(3, 5, &kept, blocks);
  REQUIRE(whole.size() == 24);
  CHECK(blocks == whole);
  CHECK(kept.made);
  REQUIRE(kept.by_component.size() == 3);
  CHECK(kept.by_component[0] != nullptr);
  CHECK(kept.by_component[1] != nullptr);
  CHECK(kept.by_component[2] == nullptr);  // z: zeros
  // Codes made again from the second block's first frame code its chunks otherwise: the codes are what is kept.
  filter(0, 3, nullptr, fresh);
  filter(3, 5, nullptr, fresh);
  CHECK(fresh != whole);
  CHECK(std::equal(fresh.begin(), fresh.begin() + 9, whole.begin()));
}

TEST_CASE("chunks compressed into buffers that held other streams are the bytes they were the first time") {
  // The compressed chunks' buffers are kept from call to call (filtered_chunks.cpp's PackedPool): a second call
  // compresses into buffers that held the first call's streams. Here noise (streams as long as their chunks) is
  // filtered between two filterings of a walk, on 1 and 2 threads: the walk's chunks come back the same bytes.
  const std::vector<double> walk_values = walk();
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> any(-1e6, 1e6);
  std::vector<double> noise(walk_values.size());
  for (double& v : noise) v = any(random);
  const h5::detail::ChunkedLayout layout{8, 5000 * 3 * sizeof(double), 1, sizeof(double), 1, 3};
  using Chunks = std::vector<std::pair<std::pair<std::uint64_t, std::uint64_t>, std::vector<unsigned char>>>;
  const auto filter = [&](const std::vector<double>& values) {
    Chunks out;
    h5::detail::filter_chunks(reinterpret_cast<const std::byte*>(values.data()), layout, "test",
                              [&](std::uint64_t row, std::uint64_t component, const unsigned char* bytes, std::size_t size) {
                                out.push_back({{row, component}, std::vector<unsigned char>(bytes, bytes + size)});
                              });
    return out;
  };
  const Chunks first = filter(walk_values);
  REQUIRE(first.size() == 24);
  for (const std::size_t threads : {1, 2}) {
    const ThreadLimit limit(threads);
    const Chunks between = filter(noise);
    REQUIRE(between.size() == 24);
    CHECK(between[0].second.size() > first[0].second.size());  // longer streams went through the buffers
    CHECK(filter(walk_values) == first);
  }
}
