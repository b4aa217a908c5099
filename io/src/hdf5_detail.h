// What hdf5.cpp shares with the other files of the HDF5 layer (hdf5_growing.cpp): libhdf5's setup, its error
// text in our messages, and the deflate level of every compressed dataset.
#pragma once

#include <throng/io/hdf5.h>

#include <hdf5.h>

#include <cstdint>
#include <string>
#include <vector>

namespace throng::h5::detail {

// Deflate's level for compressed datasets (after shuffle): ISA-L's where throng filters the chunks itself
// (filtered_chunks.h: every dataset written whole and the streamed frames), zlib's through libhdf5's own filter
// for the datasets that grow as they are written (hdf5_growing.cpp); both are zlib streams any reader decodes.
// The measurements below were made with zlib. Measured on `throng sketch configs/sketch-large.yaml --set
// agents.count=6000 --set duration=60` (601 frames, 2 cores, libhdf5 filtering on one thread, medians of 2):
// level 4 8.35 s and 122.9 MB, level 3 8.2 s, level 2 6.5 s, level 1 5.8 s and 124.4 MB (+1.3 %); without
// compression 2.9-3.3 s and 246 MB. Level 1: 30 % off the command for 1.3 % more bytes (formation-hierarchy-1260:
// 2.48 → 1.96 s). Every reader decodes any level. With the chunks filtered in parallel (filtered_chunks.h, then
// libdeflate) the same command took 4.20 s (median of 5); ISA-L's level 1 since (docs/commands/sketch.md).
constexpr int deflate_level = 1;

/// Once per process, before the first call into libhdf5: no error stack on stderr, no filter plugins, no exit
/// handler (see hdf5.cpp).
void silence_hdf5();

/// Why libhdf5 failed (its current error stack, cleared), for our messages.
[[nodiscard]] std::string hdf5_reason();

/// `id` as a Handle; IoError "<what>: <reason>" when it is negative.
[[nodiscard]] Handle checked(hid_t id, const std::string& what);

/// IoError "<what>: <reason>" when `status` is negative.
void check(herr_t status, const std::string& what);

/// A simple dataspace of `shape`.
[[nodiscard]] Handle simple_space(const std::vector<std::uint64_t>& shape);

}  // namespace throng::h5::detail
