// Running the `throng` program as a user would, for the CLI tests (tests/cli): one copy of what every CLI test
// file needs.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace throng::test {

/// The shell command line `throng <args>` (the program built with the tests).
[[nodiscard]] std::string command(const std::string& args);

/// Runs `throng <args>` (args as on a shell command line, redirections included); returns its exit status and
/// fills `output` with its stdout and stderr.
int run(const std::string& args, std::string* output = nullptr);

/// The shipped example job configs/<name>.
[[nodiscard]] std::string config(const std::string& name);

/// Writes `text` to `path` (replacing it) and returns the path.
std::filesystem::path write_file(const std::filesystem::path& path, const std::string& text);

/// Starts `throng <args>` in `folder` (stdout and stderr to folder/log.txt) with SIGINT and SIGTERM at their
/// defaults (a test started in the background inherits SIGINT ignored, and throng keeps an ignored signal
/// ignored), `environment` ("NAME=value ...") added to its environment; returns its process id for the caller
/// to signal and wait for. Fails the test when it cannot be started.
int spawn(const std::filesystem::path& folder, const std::string& args, const std::string& environment = "");

/// A wait status as a shell reports it: the exit code, or 128 + n when signal n ended the process.
[[nodiscard]] int exit_status(int status);

/// True when both hold the same bits (a determinism check).
[[nodiscard]] bool same_bits(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace throng::test
