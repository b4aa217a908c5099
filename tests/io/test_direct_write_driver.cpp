// throng's file driver (io/src/direct_write_driver.h): large raw-data writes from aligned buffers go straight to
// the disk, and the file is byte for byte what libhdf5's own POSIX driver (sec2) writes with the same alignment,
// whatever path each write took: aligned and unaligned buffers, chunks with tails that are not whole blocks,
// small datasets and attributes, a file system that refuses O_DIRECT. Whole crowd files read back equal.
#include <throng/io/crowd_file.h>
#include <throng/io/hdf5.h>

#include "direct_write_driver.h"
#include "direct_writes.h"

#include <catch2/catch.hpp>

#include <hdf5.h>

#include <atomic>
#include <cerrno>
#include <cstdarg>
#include <cstdint>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <new>
#include <random>
#include <string>
#include <dlfcn.h>
#include <sys/types.h>
#include <unistd.h>
#include <vector>

#include "test_paths.h"

using namespace throng;
using h5::detail::direct_write_block;
using h5::detail::direct_write_minimum;

namespace {

// A file system that takes an O_DIRECT open and then refuses the writes with EINVAL (some network and FUSE file
// systems, or blocks larger than the driver's), played on any file system: while `refuse_direct_writes` is set, an
// open asking O_DIRECT opens without it and its descriptor is remembered, and every pwrite through that descriptor
// fails so, and is counted, until it is closed. The open, pwrite and close below stand in for the C library's in
// this test program (the driver, linked in statically, calls them); they pass everything else on.
std::atomic<bool> refuse_direct_writes{false};
std::atomic<int> pretended_direct_fd{-1};
std::atomic<int> refused_direct_writes{0};

template <class Function>
Function next_definition(const char* name) {
  return reinterpret_cast<Function>(::dlsym(RTLD_NEXT, name));
}

}  // namespace

extern "C" int open(const char* path, int flags, ...) {
  static const auto real = next_definition<int (*)(const char*, int, ...)>("open");
  mode_t mode = 0;
  if ((flags & O_CREAT) != 0 || (flags & O_TMPFILE) == O_TMPFILE) {
    va_list rest;
    va_start(rest, flags);
    mode = va_arg(rest, mode_t);
    va_end(rest);
  }
  if (!refuse_direct_writes.load() || (flags & O_DIRECT) == 0) return real(path, flags, mode);
  const int fd = real(path, flags & ~O_DIRECT, mode);
  if (fd >= 0) pretended_direct_fd = fd;
  return fd;
}

extern "C" ssize_t pwrite(int fd, const void* bytes, size_t size, off_t offset) {
  static const auto real = next_definition<ssize_t (*)(int, const void*, size_t, off_t)>("pwrite");
  if (refuse_direct_writes.load() && fd == pretended_direct_fd.load()) {
    refused_direct_writes.fetch_add(1);
    errno = EINVAL;
    return -1;
  }
  return real(fd, bytes, size, offset);
}

extern "C" int close(int fd) {
  static const auto real = next_definition<int (*)(int)>("close");
  int expected = fd;
  pretended_direct_fd.compare_exchange_strong(expected, -1);
  return real(fd);
}

namespace {

// The sample's chunk: just above the direct minimum, with a tail of one byte past whole blocks.
constexpr std::size_t sample_chunk = direct_write_minimum + 1;

std::string bytes_of(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Whether `folder`'s file system takes O_DIRECT writes, warning where it does not.
bool takes_direct_io(const std::filesystem::path& folder) {
  const bool written = test::takes_direct_writes(folder);
  if (!written) WARN(folder.string() << ": its file system refuses O_DIRECT writes; only the page-cache path is checked here");
  return written;
}

enum class Driver { direct, direct_refused, sec2 };

// Three chunks of sample_chunk bytes, written raw with H5Dwrite_chunk: chunk 0 and 2 from a
// block-aligned buffer, chunk 1 from one a byte past it; then a small contiguous dataset and an attribute. Through
// throng's driver (direct_refused: as on a file system without O_DIRECT), or sec2 with the same alignment.
// Modification times are not stored (as File::create does), so two files written at different seconds compare.
void write_sample(const std::filesystem::path& path, Driver driver) {
  const hid_t access = H5Pcreate(H5P_FILE_ACCESS);
  if (driver != Driver::sec2) {
    h5::detail::use_direct_write_driver(access, driver == Driver::direct);
  } else {
    REQUIRE(H5Pset_fapl_sec2(access) >= 0);
    REQUIRE(H5Pset_alignment(access, direct_write_minimum, direct_write_block) >= 0);
  }
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access);
  REQUIRE(file >= 0);
  constexpr hsize_t chunk = sample_chunk;
  const hsize_t dims[1] = {3 * chunk};
  const hid_t space = H5Screate_simple(1, dims, nullptr);
  const hid_t create = H5Pcreate(H5P_DATASET_CREATE);
  REQUIRE(H5Pset_chunk(create, 1, &chunk) >= 0);
  REQUIRE(H5Pset_obj_track_times(create, false) >= 0);
  const hid_t plain = H5Pcreate(H5P_DATASET_CREATE);
  REQUIRE(H5Pset_obj_track_times(plain, false) >= 0);
  const hid_t set = H5Dcreate2(file, "raw", H5T_NATIVE_UINT8, space, H5P_DEFAULT, create, H5P_DEFAULT);
  REQUIRE(set >= 0);
  const h5::detail::AlignedBytes buffer = h5::detail::aligned_bytes(chunk + direct_write_block);
  for (hsize_t c = 0; c < 3; ++c) {
    unsigned char* bytes = buffer.get() + (c == 1 ? 1 : 0);
    for (hsize_t i = 0; i < chunk; ++i) bytes[i] = static_cast<unsigned char>((i * 31 + c * 7) % 251);
    const hsize_t offset[1] = {c * chunk};
    REQUIRE(H5Dwrite_chunk(set, H5P_DEFAULT, 0, offset, chunk, bytes) >= 0);
  }
  const std::vector<double> small{1.5, -2.25, 3.0};
  const hsize_t small_dims[1] = {small.size()};
  const hid_t small_space = H5Screate_simple(1, small_dims, nullptr);
  const hid_t small_set = H5Dcreate2(file, "small", H5T_IEEE_F64LE, small_space, H5P_DEFAULT, plain, H5P_DEFAULT);
  REQUIRE(H5Dwrite(small_set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, small.data()) >= 0);
  const int version = 7;
  const hid_t scalar = H5Screate(H5S_SCALAR);
  const hid_t attribute = H5Acreate2(file, "version", H5T_STD_I32LE, scalar, H5P_DEFAULT, H5P_DEFAULT);
  REQUIRE(H5Awrite(attribute, H5T_NATIVE_INT, &version) >= 0);
  H5Aclose(attribute);
  H5Sclose(scalar);
  H5Dclose(small_set);
  H5Sclose(small_space);
  H5Dclose(set);
  H5Pclose(create);
  H5Pclose(plain);
  H5Sclose(space);
  REQUIRE(H5Fclose(file) >= 0);
  H5Pclose(access);
}

// The sample's chunks read back through libhdf5's default driver.
std::vector<unsigned char> raw_values(const std::filesystem::path& path) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(file >= 0);
  const hid_t set = H5Dopen2(file, "raw", H5P_DEFAULT);
  REQUIRE(set >= 0);
  std::vector<unsigned char> values(3 * sample_chunk);
  REQUIRE(H5Dread(set, H5T_NATIVE_UINT8, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) >= 0);
  H5Dclose(set);
  H5Fclose(file);
  return values;
}

}  // namespace

TEST_CASE("the direct-write driver writes the bytes sec2 writes, aligned chunks straight to the disk", "[io][direct]") {
  const auto dir = test::scratch_dir("direct_write_driver");
  const bool direct_io = takes_direct_io(dir);
  INFO("the scratch folder's file system takes O_DIRECT: " << direct_io);
  const std::size_t before = h5::detail::direct_write_bytes();
  write_sample(dir / "direct.h5", Driver::direct);
  const std::size_t written_direct = h5::detail::direct_write_bytes() - before;
  write_sample(dir / "sec2.h5", Driver::sec2);

  const std::string direct = bytes_of(dir / "direct.h5"), sec2 = bytes_of(dir / "sec2.h5");
  REQUIRE(direct.size() == sec2.size());
  CHECK(direct == sec2);
  // Chunks 0 and 2 (aligned buffers at aligned addresses) went straight to the disk, their whole blocks only;
  // chunk 1 (a buffer one byte off its address's alignment) through the page cache.
  const std::size_t whole_blocks = sample_chunk / direct_write_block * direct_write_block;
  if (direct_io) CHECK(written_direct == 2 * whole_blocks);
  else CHECK(written_direct == 0);

  const std::vector<unsigned char> values = raw_values(dir / "direct.h5");
  for (std::size_t c = 0; c < 3; ++c) {
    for (std::size_t i = 0; i < sample_chunk; i += 997) {
      INFO("chunk " << c << " byte " << i);
      REQUIRE(values[c * sample_chunk + i] == static_cast<unsigned char>((i * 31 + c * 7) % 251));
    }
  }
}

TEST_CASE("the direct-write driver writes through the page cache where O_DIRECT is refused", "[io][direct]") {
  // The path of a file system without O_DIRECT: no descriptor opened with it, every write as sec2's.
  const auto dir = test::scratch_dir("direct_write_refused");
  const std::size_t before = h5::detail::direct_write_bytes();
  write_sample(dir / "refused.h5", Driver::direct_refused);
  CHECK(h5::detail::direct_write_bytes() == before);
  write_sample(dir / "sec2.h5", Driver::sec2);
  CHECK(bytes_of(dir / "refused.h5") == bytes_of(dir / "sec2.h5"));
}

TEST_CASE("the direct-write driver falls back to the page cache when the file system refuses a direct write", "[io][direct]") {
  // The O_DIRECT open succeeds (the open above, whatever the scratch folder's file system), the first direct write
  // fails with EINVAL (the pwrite above): that write and every later one go through the page cache, and the file is
  // still sec2's byte for byte.
  const auto dir = test::scratch_dir("direct_write_einval");
  const std::size_t before = h5::detail::direct_write_bytes();
  refused_direct_writes = 0;
  refuse_direct_writes = true;
  write_sample(dir / "einval.h5", Driver::direct);
  refuse_direct_writes = false;
  CHECK(refused_direct_writes.load() == 1);  // the first chunk's; the driver then closed its O_DIRECT descriptor
  CHECK(h5::detail::direct_write_bytes() == before);
  write_sample(dir / "sec2.h5", Driver::sec2);
  CHECK(bytes_of(dir / "einval.h5") == bytes_of(dir / "sec2.h5"));
  CHECK(raw_values(dir / "einval.h5") == raw_values(dir / "sec2.h5"));
}

TEST_CASE("the direct-write driver splits a write into a page-cache head, whole direct blocks and a tail", "[io][direct]") {
  // Through libhdf5's driver interface itself: `big` bytes at address 100 from a buffer 100 bytes into a block
  // (a head of 3,996 bytes, whole blocks direct, a tail), then `big` bytes at an address one byte past a block
  // from an aligned buffer (address and buffer disagree: all through the page cache), then 5,000 bytes through the
  // page cache inside the first write's direct blocks. The file holds exactly what was written, read back through
  // the driver and from the disk.
  constexpr std::size_t big = direct_write_minimum + 300000;
  constexpr haddr_t second_address = 2 * big + 1 - (2 * big) % direct_write_block;
  constexpr haddr_t end = second_address + big;
  const auto dir = test::scratch_dir("direct_write_split");
  const auto path = dir / "split.bin";
  const bool direct_io = takes_direct_io(dir);
  const hid_t access = H5Pcreate(H5P_FILE_ACCESS);
  h5::detail::use_direct_write_driver(access);
  H5FD_t* file = H5FDopen(path.c_str(), H5F_ACC_RDWR | H5F_ACC_CREAT | H5F_ACC_TRUNC, access, haddr_t{1} << 40);
  REQUIRE(file != nullptr);
  REQUIRE(H5FDset_eoa(file, H5FD_MEM_DRAW, end) >= 0);
  const h5::detail::AlignedBytes buffer = h5::detail::aligned_bytes(big + direct_write_block);
  std::string expected(end, '\0');
  const auto put = [&](haddr_t address, std::size_t size, std::size_t buffer_offset, unsigned seed) {
    unsigned char* bytes = buffer.get() + buffer_offset;
    for (std::size_t i = 0; i < size; ++i) bytes[i] = static_cast<unsigned char>((i * 131 + seed) % 253);
    REQUIRE(H5FDwrite(file, H5FD_MEM_DRAW, H5P_DEFAULT, address, size, bytes) >= 0);
    std::memcpy(expected.data() + address, bytes, size);
  };
  const std::size_t before = h5::detail::direct_write_bytes();
  put(100, big, 100, 1);
  const std::size_t first = h5::detail::direct_write_bytes() - before;
  put(second_address, big, 0, 2);
  const std::size_t second = h5::detail::direct_write_bytes() - before - first;
  put(150000, 5000, 7, 3);
  if (direct_io) CHECK(first == (big - 3996) / direct_write_block * direct_write_block);
  else CHECK(first == 0);
  CHECK(second == 0);
  std::string back(end, '\0');
  REQUIRE(H5FDread(file, H5FD_MEM_DRAW, H5P_DEFAULT, 0, back.size(), back.data()) >= 0);
  CHECK(back == expected);
  REQUIRE(H5FDclose(file) >= 0);
  H5Pclose(access);
  CHECK(bytes_of(path) == expected);
}

TEST_CASE("a crowd file written through the direct-write driver reads back equal", "[io][direct]") {
  // 200,000 agents × 3 frames at random places (they barely compress): a chunk holds one component of one frame,
  // 1.6 MB before compression, above the direct minimum after it.
  const auto dir = test::scratch_dir("direct_write_crowd");
  CrowdFile crowd;
  crowd.motion = CrowdMotion::with_shape(3, 200000);
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> place(-50.0, 50.0);
  for (std::size_t t = 0; t < 3; ++t) {
    for (std::size_t a = 0; a < 200000; ++a) {
      crowd.motion.positions[crowd.motion.index(t, a)] = place(random);
      crowd.motion.positions[crowd.motion.index(t, a) + 1] = place(random);
      crowd.motion.positions[crowd.motion.index(t, a) + 2] = 0.0;
    }
  }
  const std::size_t before = h5::detail::direct_write_bytes();
  write_crowd_file(dir / "crowd.h5", crowd);
  if (takes_direct_io(dir)) CHECK(h5::detail::direct_write_bytes() > before);
  const CrowdFile back = read_crowd_file(dir / "crowd.h5");
  REQUIRE(back.motion.agent_count() == crowd.motion.agent_count());
  REQUIRE(back.motion.frame_count() == crowd.motion.frame_count());
  CHECK(back.motion.positions == crowd.motion.positions);
}

TEST_CASE("the direct-write driver gathers small raw-data writes that follow one another into runs", "[io][direct]") {
  // Through libhdf5's driver interface: 700 raw writes of 3,000 bytes one after the other, a read that meets them
  // (it must see them: the run is written first), 1,500 more (beyond one run's 4 MiB: a second run, a third
  // begun), a metadata write elsewhere (it leaves the run alone), a raw write over bytes of the open run (written
  // after it, so that it wins), a metadata write inside that new run (the run written first, so that the metadata
  // wins), one more raw write and a close without a flush (the last run written there). Five runs in all; the
  // file holds exactly what was written.
  constexpr std::size_t piece = 3000, first_pieces = 700, more_pieces = 1500;
  constexpr haddr_t start = 5, metadata_address = start + (first_pieces + more_pieces) * piece + 10000;
  constexpr haddr_t end = metadata_address + 512;
  const auto dir = test::scratch_dir("direct_write_staged");
  const auto path = dir / "staged.bin";
  const hid_t access = H5Pcreate(H5P_FILE_ACCESS);
  h5::detail::use_direct_write_driver(access);
  H5FD_t* file = H5FDopen(path.c_str(), H5F_ACC_RDWR | H5F_ACC_CREAT | H5F_ACC_TRUNC, access, haddr_t{1} << 40);
  REQUIRE(file != nullptr);
  REQUIRE(H5FDset_eoa(file, H5FD_MEM_DRAW, end) >= 0);
  std::string expected(end, '\0');
  std::vector<unsigned char> bytes(piece);
  const auto put = [&](H5FD_mem_t type, haddr_t address, std::size_t size, unsigned seed) {
    for (std::size_t i = 0; i < size; ++i) bytes[i] = static_cast<unsigned char>((i * 131 + seed) % 253);
    REQUIRE(H5FDwrite(file, type, H5P_DEFAULT, address, size, bytes.data()) >= 0);
    std::memcpy(expected.data() + address, bytes.data(), size);
  };
  const std::size_t runs_before = h5::detail::staged_runs_written();
  const auto runs = [&] { return h5::detail::staged_runs_written() - runs_before; };
  for (std::size_t k = 0; k < first_pieces; ++k) put(H5FD_MEM_DRAW, start + k * piece, piece, static_cast<unsigned>(k));
  CHECK(runs() == 0);
  std::string seen(100, '\0');
  REQUIRE(H5FDread(file, H5FD_MEM_DRAW, H5P_DEFAULT, start + 1000, seen.size(), seen.data()) >= 0);
  CHECK(seen == expected.substr(start + 1000, seen.size()));
  CHECK(runs() == 1);
  for (std::size_t k = first_pieces; k < first_pieces + more_pieces; ++k) {
    put(H5FD_MEM_DRAW, start + k * piece, piece, static_cast<unsigned>(k));
  }
  CHECK(runs() == 2);  // the second run ended at 4 MiB (1,398 pieces); the third holds the other 102
  put(H5FD_MEM_SUPER, metadata_address, 512, 77);
  CHECK(runs() == 2);
  const haddr_t overwrite = start + (first_pieces + more_pieces - 10) * piece + 7;
  put(H5FD_MEM_DRAW, overwrite, piece, 99);
  CHECK(runs() == 3);
  CHECK(H5FDget_eof(file, H5FD_MEM_DRAW) == end);  // staged bytes count as the file's
  put(H5FD_MEM_SUPER, overwrite + 100, 200, 55);  // a metadata write inside the open run: the run first
  CHECK(runs() == 4);
  put(H5FD_MEM_DRAW, overwrite + piece, piece, 101);  // a new run
  REQUIRE(H5FDclose(file) >= 0);
  H5Pclose(access);
  CHECK(runs() == 5);
  CHECK(bytes_of(path) == expected);
}
