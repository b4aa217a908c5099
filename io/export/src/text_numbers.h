// Numbers as text for the text formats: the shortest form that reads back to the same value (std::to_chars),
// so a reader gets back exactly the double or float that was written.
#pragma once

#include <charconv>
#include <cstdint>
#include <string>

namespace throng::detail {

template <class Number>
void append_number(std::string& out, Number value) {
  char buffer[32];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, r.ptr);
}

}  // namespace throng::detail
