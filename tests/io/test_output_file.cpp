// The exports' output file (io/export/src/output_file.h): bytes written in pieces of any size, through the
// staging buffer, straight to the disk where the file system allows (full buffers) and through the page cache
// otherwise (the tail, or Direct::never: a file system that refuses O_DIRECT), come back exactly; the target is
// replaced only by commit.
#include "direct_writes.h"
#include "output_file.h"
#include "test_paths.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

using namespace throng;

namespace {

std::string read_all(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// Bytes no two offsets of which repeat in a short period (a misplaced or repeated piece shows).
std::string pattern(std::size_t size) {
  std::string bytes(size, '\0');
  std::uint64_t state = 88172645463325252ull;
  for (char& c : bytes) {
    state ^= state << 13, state ^= state >> 7, state ^= state << 17;
    c = static_cast<char>(state);
  }
  return bytes;
}

}  // namespace

TEST_CASE("an output file gets back exactly the bytes written in pieces of any size, directly or through the page cache") {
  const auto dir = test::scratch_dir("io_output_file");
  // 2.5 staging buffers' worth and a tail, in pieces that straddle the buffer's end in every way.
  const std::string bytes = pattern((20 << 20) + 12345);
  const std::vector<std::size_t> pieces{1, 4095, 4096, 4097, (8 << 20) - 1, 3, 8 << 20, 100000};
  const bool direct_possible = test::takes_direct_writes(dir);
  if (!direct_possible) WARN("the scratch folder's file system refuses O_DIRECT: both cases take the page cache path");
  for (const auto direct : {detail::OutputFile::Direct::when_allowed, detail::OutputFile::Direct::never}) {
    const bool when_allowed = direct == detail::OutputFile::Direct::when_allowed;
    INFO((when_allowed ? "direct when allowed" : "never direct"));
    const auto target = dir / "out.bin";
    std::ofstream(target) << "previous";
    detail::OutputFile file(target, direct);
    std::size_t at = 0;
    for (std::size_t k = 0; at < bytes.size(); ++k) {
      const std::size_t size = std::min(pieces[k % pieces.size()], bytes.size() - at);
      file.write(bytes.data() + at, size);
      at += size;
    }
    CHECK(read_all(target) == "previous");  // nothing replaced before commit
    // Two full buffers went straight to the disk, where the file system takes O_DIRECT; never otherwise.
    CHECK(file.direct_bytes() == (when_allowed && direct_possible ? std::size_t(16) << 20 : 0));
    file.commit();
    const std::string back = read_all(target);
    CHECK(back.size() == bytes.size());
    CHECK(back == bytes);
    CHECK(std::distance(std::filesystem::directory_iterator(dir), {}) == 1);  // no temporary left
  }
}

TEST_CASE("a small output file is written at commit, through the page cache") {
  const auto dir = test::scratch_dir("io_output_file_small");
  detail::OutputFile file(dir / "small.txt");
  file.write("a line\n");
  file.write(std::string(5000, 'x'));
  CHECK(file.direct_bytes() == 0);
  CHECK_FALSE(std::filesystem::exists(dir / "small.txt"));
  file.commit();
  CHECK(read_all(dir / "small.txt") == "a line\n" + std::string(5000, 'x'));
}
