// libhdf5's deflate filter as throng registers it (io/src/deflate_filter.h): what libhdf5 compresses itself comes
// out as zlib's compress2 makes it (libhdf5 1.10's own filter), every chunk is inflated back through ISA-L, and a
// damaged stream fails the read instead of giving wrong values.
#include "deflate_filter.h"
#include "check_throws.h"
#include "test_paths.h"

#include <throng/core/errors.h>
#include <throng/io/hdf5.h>

#include <catch2/catch.hpp>
#include <hdf5.h>
#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

using namespace throng;
using throng::h5::detail::isal_inflated_chunks;
using throng::h5::detail::use_isal_inflate;

namespace {

// A file with one chunked dataset of `n` doubles in chunks of `chunk` (shuffle first when `shuffle`, then deflate at
// `level`); closes everything on destruction.
struct OneDataset {
  hid_t file = -1, dataset = -1;
  OneDataset(const std::filesystem::path& path, std::size_t n, std::size_t chunk, bool shuffle, unsigned level) {
    file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    const hsize_t dims = n, chunk_dims = chunk;
    const hid_t space = H5Screate_simple(1, &dims, nullptr);
    const hid_t create = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(create, 1, &chunk_dims);
    if (shuffle) H5Pset_shuffle(create);
    H5Pset_deflate(create, level);
    dataset = H5Dcreate2(file, "values", H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, create, H5P_DEFAULT);
    H5Pclose(create);
    H5Sclose(space);
  }
  ~OneDataset() {
    if (dataset >= 0) H5Dclose(dataset);
    if (file >= 0) H5Fclose(file);
  }
  OneDataset(const OneDataset&) = delete;
  OneDataset& operator=(const OneDataset&) = delete;

  [[nodiscard]] std::vector<double> read(std::size_t n, herr_t* status) const {
    std::vector<double> out(n, -1.0);
    *status = H5Dread(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data());
    return out;
  }
  // The stored bytes of chunk `index` and its filter mask.
  [[nodiscard]] std::vector<unsigned char> raw_chunk(std::size_t index, std::size_t chunk, std::uint32_t* mask) const {
    const hsize_t offset = index * chunk;
    hsize_t bytes = 0;
    REQUIRE(H5Dget_chunk_storage_size(dataset, &offset, &bytes) >= 0);
    std::vector<unsigned char> out(bytes);
    REQUIRE(H5Dread_chunk(dataset, H5P_DEFAULT, &offset, mask, out.data()) >= 0);
    return out;
  }
};

std::vector<unsigned char> shuffled(const double* values, std::size_t n) {
  std::vector<unsigned char> out(8 * n);
  for (std::size_t i = 0; i < n; ++i) {
    unsigned char b[8];
    std::memcpy(b, values + i, 8);
    for (std::size_t j = 0; j < 8; ++j) out[j * n + i] = b[j];
  }
  return out;
}

std::vector<unsigned char> zlib_compressed(const unsigned char* bytes, std::size_t n, int level) {
  uLongf room = compressBound(static_cast<uLong>(n));
  std::vector<unsigned char> out(room);
  REQUIRE(compress2(out.data(), &room, bytes, static_cast<uLong>(n), level) == Z_OK);
  out.resize(room);
  return out;
}

}  // namespace

TEST_CASE("libhdf5's own deflating gives zlib's bytes, and every chunk is inflated back through ISA-L") {
  use_isal_inflate();
  const auto dir = test::scratch_dir("io_deflate_filter");
  constexpr std::size_t n = 20000, chunk = 4096;  // 4 full chunks and an edge one
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> uniform(-50.0, 50.0);
  std::vector<std::pair<std::string, std::vector<double>>> kinds(3);
  kinds[0].first = "noise";
  kinds[1].first = "a smooth walk";
  kinds[2].first = "zeros";
  for (std::size_t i = 0; i < n; ++i) {
    kinds[0].second.push_back(uniform(random));
    kinds[1].second.push_back(10.0 * std::sin(0.001 * static_cast<double>(i)));
    kinds[2].second.push_back(0.0);
  }
  for (const auto& [name, values] : kinds) {
    for (const bool shuffle : {false, true}) {
      for (const unsigned level : {1U, 6U, 9U}) {
        INFO(name << (shuffle ? ", shuffled" : "") << ", level " << level);
        OneDataset d(dir / "values.h5", n, chunk, shuffle, level);
        REQUIRE(H5Dwrite(d.dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) >= 0);
        REQUIRE(H5Fflush(d.file, H5F_SCOPE_GLOBAL) >= 0);
        // The second chunk as stored: what zlib makes of it (after the shuffle's planes when shuffled).
        std::uint32_t mask = 99;
        const std::vector<unsigned char> stored = d.raw_chunk(1, chunk, &mask);
        CHECK(mask == 0);
        const double* second = values.data() + chunk;
        const std::vector<unsigned char> filtered =
            shuffle ? shuffled(second, chunk) : std::vector<unsigned char>(reinterpret_cast<const unsigned char*>(second),
                                                                           reinterpret_cast<const unsigned char*>(second + chunk));
        CHECK(stored == zlib_compressed(filtered.data(), filtered.size(), static_cast<int>(level)));
        // Read back exactly, every chunk through ISA-L.
        H5Dclose(d.dataset);
        d.dataset = H5Dopen2(d.file, "values", H5P_DEFAULT);
        const std::size_t before = isal_inflated_chunks();
        herr_t status = -1;
        const std::vector<double> back = d.read(n, &status);
        REQUIRE(status >= 0);
        CHECK(std::memcmp(back.data(), values.data(), n * sizeof(double)) == 0);
        CHECK(isal_inflated_chunks() - before == 5);
      }
    }
  }
}

TEST_CASE("a damaged deflate stream fails the read, and a chunk that inflates a thousandfold reads back whole") {
  use_isal_inflate();
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // the failing reads' error stacks are expected
  const auto dir = test::scratch_dir("io_deflate_filter_damaged");
  constexpr std::size_t chunk = 131072;  // 1 MiB of doubles a chunk
  std::vector<double> values(chunk);
  for (std::size_t i = 0; i < chunk; ++i) values[i] = i < chunk / 2 ? 0.0 : 1.5;
  const auto* bytes = reinterpret_cast<const unsigned char*>(values.data());
  const std::vector<unsigned char> good = zlib_compressed(bytes, chunk * sizeof(double), 9);
  REQUIRE(good.size() * 500 < chunk * sizeof(double));  // the buffer grows from twice the stored size many times

  struct Case {
    const char* name;
    std::vector<unsigned char> stream;
    bool reads;
  };
  std::vector<Case> cases{{"the stream as zlib made it", good, true}};
  cases.push_back({"its Adler-32 changed", good, false});
  cases.back().stream.back() ^= 0x01;
  cases.push_back({"cut short", std::vector<unsigned char>(good.begin(), good.end() - 6), false});
  for (int cut = 1; cut <= 4; ++cut) {  // into the Adler-32 only: every deflate block is there
    cases.push_back({"its Adler-32 cut short", std::vector<unsigned char>(good.begin(), good.end() - cut), false});
  }
  {  // a stream that needs a preset dictionary (zlib's FDICT), which no HDF5 chunk has
    z_stream z{};
    REQUIRE(deflateInit(&z, 6) == Z_OK);
    const unsigned char dictionary[] = "throng";
    REQUIRE(deflateSetDictionary(&z, dictionary, sizeof dictionary) == Z_OK);
    std::vector<unsigned char> out(compressBound(chunk * sizeof(double)) + 64);
    z.next_in = const_cast<unsigned char*>(bytes);
    z.avail_in = static_cast<uInt>(chunk * sizeof(double));
    z.next_out = out.data();
    z.avail_out = static_cast<uInt>(out.size());
    REQUIRE(deflate(&z, Z_FINISH) == Z_STREAM_END);
    out.resize(z.total_out);
    deflateEnd(&z);
    cases.push_back({"a stream that needs a preset dictionary", out, false});
  }
  cases.push_back({"a wrong zlib header", good, false});
  cases.back().stream[1] ^= 0x01;  // the header's check bits no longer a multiple of 31
  cases.push_back({"bytes that are not deflate", std::vector<unsigned char>(good.size(), 0xA5), false});
  for (const Case& c : cases) {
    INFO(c.name << " (" << c.stream.size() << " bytes)");
    OneDataset d(dir / "damaged.h5", chunk, chunk, false, 6);
    const hsize_t offset = 0;
    REQUIRE(H5Dwrite_chunk(d.dataset, H5P_DEFAULT, 0, &offset, c.stream.size(), c.stream.data()) >= 0);
    H5Dclose(d.dataset);
    d.dataset = H5Dopen2(d.file, "values", H5P_DEFAULT);
    herr_t status = 0;
    const std::vector<double> back = d.read(chunk, &status);
    if (c.reads) {
      REQUIRE(status >= 0);
      CHECK(std::memcmp(back.data(), values.data(), chunk * sizeof(double)) == 0);
    } else {
      CHECK(status < 0);
    }
  }
}

TEST_CASE("a stream that inflates beyond its chunk fails the read once the reader has said the chunk's size") {
  use_isal_inflate();
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const auto dir = test::scratch_dir("io_deflate_filter_beyond");
  constexpr std::size_t chunk = 1024;  // 8 KB of doubles a chunk, but a stream of 64 KB of zeros
  const std::vector<unsigned char> zeros(64 * 1024, 0);
  const std::vector<unsigned char> stream = zlib_compressed(zeros.data(), zeros.size(), 6);
  {
    OneDataset d(dir / "beyond.h5", chunk, chunk, false, 6);
    const hsize_t offset = 0;
    REQUIRE(H5Dwrite_chunk(d.dataset, H5P_DEFAULT, 0, &offset, stream.size(), stream.data()) >= 0);
    H5Dclose(d.dataset);
    d.dataset = H5Dopen2(d.file, "values", H5P_DEFAULT);
    herr_t status = 0;
    {
      const throng::h5::detail::DecodedChunkBytes told(chunk * sizeof(double));
      (void)d.read(chunk, &status);
      CHECK(status < 0);
      // An honest chunk of the same dataset still reads under the same bound.
    }
  }
  {
    OneDataset d(dir / "beyond.h5", chunk, chunk, false, 6);
    std::vector<double> values(chunk, 2.5);
    REQUIRE(H5Dwrite(d.dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) >= 0);
    const throng::h5::detail::DecodedChunkBytes told(chunk * sizeof(double));
    herr_t status = -1;
    CHECK(d.read(chunk, &status) == values);
    CHECK(status >= 0);
  }
  // Through throng's reader, which tells the filter the chunk's size itself: the read is refused with the dataset
  // named, not grown to what the stream holds.
  {
    OneDataset d(dir / "beyond.h5", chunk, chunk, false, 6);
    const hsize_t offset = 0;
    REQUIRE(H5Dwrite_chunk(d.dataset, H5P_DEFAULT, 0, &offset, stream.size(), stream.data()) >= 0);
  }
  const h5::File file = h5::File::open(dir / "beyond.h5");
  CHECK_THROWS_AS_WITH(file.root().read_doubles("values", 1), InputError, Catch::Matchers::Contains("beyond.h5:/values"));
}
