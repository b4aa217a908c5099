// How the program passes an error between MPI ranks: an exception as its exit code and message, and back as an
// exception of the same kind on another rank; strings as the bytes mpi::broadcast and mpi::gather carry.
// Used by batches (drivers/batch.h: each job's outcome) and by pipeline steps run on rank 0 alone (run.cpp).
#pragma once

#include <throng/core/communicator.h>
#include <throng/core/errors.h>

#include <cstddef>
#include <exception>
#include <functional>
#include <string>
#include <vector>

namespace throng::cli {

/// What an error means to the program: the exit code it leaves with (ARCHITECTURE.md) and the message.
struct ErrorOutcome {
  ExitCode code = ExitCode::internal;
  std::string message;
};

/// The outcome of a caught exception (non-null): an Error its own code and message, a YAML error usage (2)
/// "in a job file: ...", out of memory and anything else internal (70).
[[nodiscard]] ErrorOutcome outcome_of(const std::exception_ptr& error);

/// Throws the error type of `code` (ConfigError, InputError, IoError, NumericalError; std::runtime_error for
/// internal) with `message`, so that a rank leaves with the same exit code as the rank that failed.
[[noreturn]] void throw_as(ExitCode code, const std::string& message);

/// Runs `work` on every rank of `ranks` (a collective: every rank calls it) and makes them agree on how it ended:
/// all return when it succeeded everywhere; otherwise every rank leaves with the error of the lowest failing rank
/// (that rank rethrows its own exception, the others throw one of the same exit code and message), so no rank goes
/// on to a collective the others left.
void on_every_rank(const std::function<void()>& work, const Communicator& ranks);

/// A caught exception (non-null) as the bytes one rank broadcasts to the others: its exit code, then its message.
[[nodiscard]] std::vector<std::byte> encoded_outcome(const std::exception_ptr& error);

/// Throws what encoded_outcome() encoded (non-empty), as throw_as() does.
[[noreturn]] void throw_encoded(const std::vector<std::byte>& outcome);

[[nodiscard]] std::vector<std::byte> bytes_of(const std::string& text);
[[nodiscard]] std::string text_of(const std::vector<std::byte>& bytes);

}  // namespace throng::cli
