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

/// True when both hold the same bits (a determinism check).
[[nodiscard]] bool same_bits(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace throng::test
