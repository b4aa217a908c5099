#include "rank_outcome.h"

#include <yaml-cpp/exceptions.h>

#include <algorithm>
#include <new>
#include <stdexcept>

namespace throng::cli {

ErrorOutcome outcome_of(const std::exception_ptr& error) {
  try {
    std::rethrow_exception(error);
  } catch (const Error& e) {
    return {e.exit_code(), e.what()};
  } catch (const YAML::Exception& e) {
    return {ExitCode::usage, std::string("in a job file: ") + e.what()};
  } catch (const std::bad_alloc&) {
    return {ExitCode::internal, "out of memory"};
  } catch (const std::exception& e) {
    return {ExitCode::internal, std::string("internal error: ") + e.what()};
  }
}

void throw_as(ExitCode code, const std::string& message) {
  switch (code) {
    case ExitCode::usage: throw ConfigError(message);
    case ExitCode::invalid_input: throw InputError(message);
    case ExitCode::io: throw IoError(message);
    case ExitCode::not_converged: throw NumericalError(message);
    default: throw std::runtime_error(message);  // internal (70)
  }
}

std::vector<std::byte> bytes_of(const std::string& text) {
  std::vector<std::byte> out(text.size());
  std::transform(text.begin(), text.end(), out.begin(), [](char c) { return static_cast<std::byte>(c); });
  return out;
}

std::string text_of(const std::vector<std::byte>& bytes) {
  std::string out(bytes.size(), '\0');
  std::transform(bytes.begin(), bytes.end(), out.begin(), [](std::byte b) { return static_cast<char>(b); });
  return out;
}

}  // namespace throng::cli
