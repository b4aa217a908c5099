// Bytes of a chain's result, to send the best chain from the rank that ran it to every other rank.
// Same-architecture MPI only (raw doubles and integers in host byte order), like the rest of the MPI layer.
#pragma once

#include "phases.h"

#include <cstddef>
#include <vector>

namespace throng::tiling {

[[nodiscard]] std::vector<std::byte> to_bytes(const ChainResult& result);
[[nodiscard]] ChainResult from_bytes(const std::vector<std::byte>& bytes);

}  // namespace throng::tiling
