#include "global_heap_check.h"

#include <throng/core/errors.h>
#include <throng/io/checked_numbers.h>
#include <throng/io/read_limits.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

namespace throng::h5 {
namespace {

constexpr std::string_view signature{"GCOL\1", 5};
// A collection larger than this is refused rather than walked in memory (libhdf5 makes new collections of 4 KiB
// to 64 KiB; one is larger only to hold one object that is).
constexpr std::uint64_t max_collection_bytes = std::uint64_t{256} << 20;

struct Descriptor {
  int fd = -1;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

// Reads exactly `size` bytes at `offset` (false on a short read).
bool read_at(int fd, std::uint64_t offset, char* out, std::size_t size) {
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = ::pread(fd, out + done, size - done, static_cast<off_t>(offset + done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

std::uint64_t decode_length(const char* p, std::size_t length_size) {
  std::uint64_t v = 0;
  for (std::size_t i = length_size; i-- > 0;) v = (v << 8) | static_cast<unsigned char>(p[i]);
  return v;
}

std::uint64_t align8(std::uint64_t v) { return (v + 7) & ~std::uint64_t{7}; }

[[noreturn]] void refuse(const std::filesystem::path& path, std::uint64_t offset, const std::string& why) {
  throw InputError(path.string() + ": global heap collection at byte " + std::to_string(offset) + " is damaged (" + why +
                   "); refused before libhdf5 reads it");
}

// Walks the collection at `offset` as libhdf5 does; returns the bytes of its objects.
std::uint64_t walk_collection(int fd, const std::filesystem::path& path, std::uint64_t offset, std::uint64_t file_size,
                              std::size_t length_size) {
  const std::uint64_t header = 8 + length_size;      // signature, version, reserved, collection size
  const std::uint64_t object_header = 8 + length_size;  // index, references, reserved, object size
  if (offset + header > file_size) refuse(path, offset, "its header runs past the end of the file");
  std::vector<char> head(header);
  if (!read_at(fd, offset, head.data(), head.size())) refuse(path, offset, "cannot read its header");
  const std::uint64_t size = decode_length(head.data() + 8, length_size);
  if (size < header) refuse(path, offset, "its size " + std::to_string(size) + " is smaller than its header");
  if (size > file_size - offset) refuse(path, offset, "its size " + std::to_string(size) + " runs past the end of the file");
  if (size > max_collection_bytes) refuse(path, offset, "it is " + format_bytes(size) + ", more than throng walks");
  std::vector<char> chunk(size);
  if (!read_at(fd, offset, chunk.data(), chunk.size())) refuse(path, offset, "cannot read it");
  std::uint64_t p = header, objects = 0;
  while (p < size) {
    if (p + object_header > size) break;  // a tail too small for an object header is free space
    const auto index = static_cast<unsigned>(static_cast<unsigned char>(chunk[p])) |
                       (static_cast<unsigned>(static_cast<unsigned char>(chunk[p + 1])) << 8);
    const std::uint64_t object = decode_length(chunk.data() + p + 8, length_size);
    std::uint64_t need = 0;
    if (index > 0) {
      if (object > size) refuse(path, offset, "object " + std::to_string(index) + " claims " + std::to_string(object) + " bytes");
      need = object_header + align8(object);
      objects += object;
    } else {
      need = object;  // free space: its size includes its header
      if (need < object_header) refuse(path, offset, "its free space claims " + std::to_string(object) + " bytes, less than its own header");
    }
    if (need > size - p) refuse(path, offset, "an object at byte " + std::to_string(p) + " runs past the collection's end");
    p += need;
  }
  if (p != size && p + object_header <= size) refuse(path, offset, "its objects do not end at its end");
  return objects;
}

}  // namespace

std::uint64_t check_global_heaps(const std::filesystem::path& path, std::uint64_t file_size, std::size_t length_size) {
  if (length_size != 2 && length_size != 4 && length_size != 8) {
    throw InputError(path.string() + ": has " + std::to_string(length_size) + "-byte lengths (HDF5 allows 2, 4 or 8)");
  }
  Descriptor file{::open(path.c_str(), O_RDONLY | O_CLOEXEC)};
  if (file.fd < 0) throw IoError(path.string() + ": cannot be opened for reading (" + std::strerror(errno) + ")");
  constexpr std::size_t block = 1 << 20;
  std::vector<char> buffer(block + signature.size() - 1);
  std::uint64_t total = 0;
  std::size_t carried = 0;  // bytes kept from the previous block (a signature may straddle two blocks)
  for (std::uint64_t at = 0; at < file_size;) {
    const std::size_t want = static_cast<std::size_t>(std::min<std::uint64_t>(block, file_size - at));
    if (!read_at(file.fd, at, buffer.data() + carried, want)) throw IoError(path.string() + ": read failed while checking it");
    const std::string_view text(buffer.data(), carried + want);
    const std::uint64_t base = at - carried;
    for (std::size_t hit = text.find(signature); hit != std::string_view::npos; hit = text.find(signature, hit + 1)) {
      const auto sum = checked_sum(total, walk_collection(file.fd, path, base + hit, file_size, length_size));
      total = sum.value_or(UINT64_MAX);
    }
    at += want;
    carried = std::min<std::size_t>(signature.size() - 1, text.size());
    std::memmove(buffer.data(), buffer.data() + text.size() - carried, carried);
  }
  return total;
}

}  // namespace throng::h5
