// Numbers as text for the text formats: the shortest form that reads back to the same value (std::to_chars),
// so a reader gets back exactly the double or float that was written.
//
// Two ways to write them: append_number onto a std::string (headers, small tables), and put_number through a
// raw pointer into a TextBuffer (the rows of a large crowd: no per-value size check or reallocation; the caller
// reserves room for a whole row once). Both give the same characters.
#pragma once

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>

namespace throng::detail {

/// The most characters put_number writes for any value (a double's shortest form is at most 24).
constexpr std::size_t max_number_chars = 32;

/// Writes `value` at `out` (room for max_number_chars) and returns the end. 0 (positive zero) has a fast path:
/// derived facings of agents on the ground have x and y components exactly 0.
template <class Number>
char* put_number(char* out, Number value) {
  if constexpr (std::is_floating_point_v<Number>) {
    if (value == 0 && !std::signbit(value)) {
      *out = '0';
      return out + 1;
    }
  }
  return std::to_chars(out, out + max_number_chars, value).ptr;
}

inline char* put_text(char* out, std::string_view text) {
  std::memcpy(out, text.data(), text.size());
  return out + text.size();
}

template <class Number>
void append_number(std::string& out, Number value) {
  char buffer[max_number_chars];
  out.append(buffer, put_number(buffer, value));
}

/// A growable character buffer written through a pointer: room(k) makes room for k more characters and returns
/// where they go, advance(end) marks what was written. Capacity is kept across clear(), so a reused buffer
/// stops allocating (and touching fresh pages) after its first fill.
class TextBuffer {
 public:
  /// The first allocation of a buffer that gets text (it doubles from there).
  static constexpr std::size_t first_capacity = 4096;

  [[nodiscard]] char* room(std::size_t more) {
    if (size_ + more > capacity_) grow(size_ + more);
    return data_.get() + size_;
  }
  void advance(const char* end) noexcept { size_ = static_cast<std::size_t>(end - data_.get()); }
  void append(std::string_view text) { advance(put_text(room(text.size()), text)); }
  void clear() noexcept { size_ = 0; }
  [[nodiscard]] const char* data() const noexcept { return data_.get(); }
  [[nodiscard]] std::size_t size() const noexcept { return size_; }
  [[nodiscard]] std::string_view view() const noexcept { return {data_.get(), size_}; }

 private:
  void grow(std::size_t needed) {
    std::size_t capacity = capacity_ ? capacity_ : first_capacity;
    while (capacity < needed) capacity *= 2;
    std::unique_ptr<char[]> data(new char[capacity]);
    if (size_) std::memcpy(data.get(), data_.get(), size_);
    data_ = std::move(data);
    capacity_ = capacity;
  }
  std::unique_ptr<char[]> data_;
  std::size_t size_ = 0, capacity_ = 0;
};

}  // namespace throng::detail
