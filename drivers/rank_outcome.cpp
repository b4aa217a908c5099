#include "rank_outcome.h"

#include <yaml-cpp/exceptions.h>

#include <algorithm>
#include <new>
#include <span>
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

void on_every_rank(const std::function<void()>& work, const Communicator& ranks) {
  std::exception_ptr failure;
  try {
    work();
  } catch (...) {
    failure = std::current_exception();
  }
  if (ranks.size() == 1) {
    if (failure) std::rethrow_exception(failure);
    return;
  }
  const double mine = failure ? 1.0 : 0.0;
  const auto failed = ranks.all_gather(std::span<const double>(&mine, 1));
  int first = -1;
  for (int r = 0; r < ranks.size() && first < 0; ++r) {
    if (failed[static_cast<std::size_t>(r)].front() != 0.0) first = r;
  }
  if (first < 0) return;
  std::vector<std::byte> outcome;
  if (ranks.rank() == first) outcome = encoded_outcome(failure);
  ranks.broadcast(outcome, first);
  if (ranks.rank() == first) std::rethrow_exception(failure);
  throw_encoded(outcome);
}

std::vector<std::byte> encoded_outcome(const std::exception_ptr& error) {
  const ErrorOutcome e = outcome_of(error);
  return bytes_of(std::string(1, static_cast<char>(static_cast<int>(e.code))) + e.message);
}

void throw_encoded(const std::vector<std::byte>& outcome) {
  const std::string text = text_of(outcome);
  throw_as(static_cast<ExitCode>(static_cast<unsigned char>(text.at(0))), text.substr(1));
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
