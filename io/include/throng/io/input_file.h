// Opening an input file as every reader must: the path names an existing regular file (not a folder, device,
// pipe or socket: `/dev/zero` given as a file would never end), and its size is known before anything is read.
#pragma once

#include <throng/io/read_limits.h>

#include <cstdint>
#include <filesystem>
#include <string>

namespace throng {

/// The size in bytes of the regular file `path`. IoError (exit 4) naming the path otherwise: "no such file",
/// "is a folder, expected <expected>", "is not a regular file (a device, pipe or socket), expected <expected>",
/// or the system's reason it cannot be read.
std::uint64_t check_input_file(const std::filesystem::path& path, const std::string& expected = "a file");

/// The whole content of the regular file `path` (check_input_file's errors), its size charged to `budget` first.
[[nodiscard]] std::string read_text_file(const std::filesystem::path& path, MemoryBudget& budget,
                                         const std::string& expected = "a file");

}  // namespace throng
