// Raw bytes of trivially copyable values in host byte order (same-architecture only), vectors as a 64-bit count
// then their elements: the tiler's best chain sent between MPI ranks, the resumable state of a windowed tiling and
// the resume record of `throng tile` (drivers/commands/tile.cpp). Reading past the end, or a count larger than the
// bytes left, throws InputError: such bytes may come from a file.
#pragma once

#include <throng/core/errors.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace throng {

class ByteWriter {
 public:
  explicit ByteWriter(std::vector<std::byte>& out) : out_(out) {}
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* p = reinterpret_cast<const std::byte*>(&v);
    out_.insert(out_.end(), p, p + sizeof(T));
  }
  template <class T>
  void put_vector(const std::vector<T>& v) {
    put<std::uint64_t>(v.size());
    for (const T& x : v) put(x);
  }

 private:
  std::vector<std::byte>& out_;
};

class ByteReader {
 public:
  /// Reads `bytes` from `at` on; `what` names them in messages.
  ByteReader(const std::vector<std::byte>& bytes, std::size_t& at, std::string what)
      : bytes_(bytes), at_(at), what_(std::move(what)) {}
  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    if (at_ > bytes_.size() || bytes_.size() - at_ < sizeof(T)) fail();
    T v;
    std::memcpy(static_cast<void*>(&v), bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
  }
  /// A count of elements of `element_bytes` each, checked against the bytes left.
  std::size_t count(std::size_t element_bytes) {
    const auto n = get<std::uint64_t>();
    if (element_bytes > 0 && n > (bytes_.size() - at_) / element_bytes) fail();
    return static_cast<std::size_t>(n);
  }
  template <class T>
  std::vector<T> get_vector() {
    std::vector<T> v(count(sizeof(T)));
    for (T& x : v) x = get<T>();
    return v;
  }
  [[noreturn]] void fail() const { throw InputError(what_ + ": truncated or malformed (at byte " + std::to_string(at_) + ")"); }

 private:
  const std::vector<std::byte>& bytes_;
  std::size_t& at_;
  std::string what_;
};

}  // namespace throng
