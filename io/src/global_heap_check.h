// The walk libhdf5 1.10 makes over a global heap collection (H5HG__cache_heap_deserialize), done first with bounds.
//
// Variable-length data (our strings) lives in global heap collections: "GCOL", version 1, 3 reserved bytes, the
// collection's size, then objects: index (2 bytes), reference count (2), 4 reserved, size (a length), data
// padded to 8 bytes; index 0 is the free space, whose size includes its own header. libhdf5 1.10 walks the
// objects by their sizes without checking them: a size of 0 in the free-space object, or one that wraps the
// padded sum to 0, never advances (an endless loop, the `info` hang of issue 18), and a size past the
// collection's end makes it read beyond its buffer. Debian 12 ships 1.10.8, so we walk every collection first.
//
// The file is scanned for the signature (a collection libhdf5 loads must start with it, at any offset), and
// every candidate with version 1 is walked; a walk that does not end exactly at the collection's end refuses the
// file. A false candidate (the bytes "GCOL" and 1 inside data) that does not walk would refuse a good file;
// inside compressed chunks or text that takes an exact 5-byte match followed by a walk that fails, which we
// accept as the price of never handing libhdf5 a heap it cannot walk.
#pragma once

#include <cstdint>
#include <filesystem>

namespace throng::h5 {

/// Checks every global heap collection of `path` (`file_size` bytes; `length_size`: the file's size of lengths,
/// 8 unless the superblock says otherwise). Returns the total size of their objects (a bound on the bytes of
/// variable-length data). InputError naming the offset of the first collection that does not walk.
std::uint64_t check_global_heaps(const std::filesystem::path& path, std::uint64_t file_size, std::size_t length_size);

}  // namespace throng::h5
