// Typed errors a user can cause, and the program's exit codes.
//
// Two tiers (see STYLE.md): what a user can cause (a bad file, a bad option, a solve that cannot meet its
// constraints) is thrown as one of the types below, with a message naming the dataset, key or parameter, the
// value found and what was expected; internal invariants use assert. The program maps each type to one exit
// code in one place (drivers/main.cpp), documented in the README.
#pragma once

#include <stdexcept>
#include <string>

namespace throng {

/// Process exit codes (README "Exit codes").
enum class ExitCode : int {
  success = 0,
  usage = 2,          ///< bad command line, bad or unknown config key, impossible option value
  invalid_input = 3,  ///< input data is malformed or inconsistent (shape, NaN, times, version, ...)
  io = 4,             ///< a file cannot be opened, read or written
  not_converged = 5,  ///< a solver did not converge or could not meet a constraint
  internal = 70,      ///< a bug: an internal invariant failed
  interrupted = 130,  ///< SIGINT or SIGTERM: stopped, temporary output removed
};

/// Base of every error a user can cause. `what()` is the full message shown to the user.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
  [[nodiscard]] virtual ExitCode exit_code() const noexcept = 0;
};

/// A command-line flag, config key or option value is wrong (unknown key, out of range, contradictory).
class ConfigError : public Error {
 public:
  using Error::Error;
  [[nodiscard]] ExitCode exit_code() const noexcept override { return ExitCode::usage; }
};

/// Input data is malformed or inconsistent: wrong shape, NaN where an agent is present, times not increasing.
class InputError : public Error {
 public:
  using Error::Error;
  [[nodiscard]] ExitCode exit_code() const noexcept override { return ExitCode::invalid_input; }
};

/// A file cannot be found, opened, read or written.
class IoError : public Error {
 public:
  using Error::Error;
  [[nodiscard]] ExitCode exit_code() const noexcept override { return ExitCode::io; }
};

/// A numerical method failed: singular system, contradictory constraints, no convergence within its cap.
class NumericalError : public Error {
 public:
  using Error::Error;
  [[nodiscard]] ExitCode exit_code() const noexcept override { return ExitCode::not_converged; }
};

}  // namespace throng
