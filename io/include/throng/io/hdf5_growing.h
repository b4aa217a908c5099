// Datasets that grow as a long run goes on: a crowd written window by window (io/tiling's streamed tiling file)
// appends frames, slots, agents and tiling rows to datasets created empty, each written as its part becomes
// final, so the program never holds the whole file's data.
//
// Every such dataset is chunked with unlimited extent on every axis, compressed as the layer's other datasets are
// (shuffle + deflate) so that a reader's storage bound (hdf5.h) holds, and has a fill value: what a reader sees
// where nothing was written (NaN for an absent position, −1 for an empty slot's id). A dataset may also shrink: a
// resumed stream cuts back what an interrupted run wrote after its last complete record.
#pragma once

#include <throng/io/hdf5.h>

#include <cstdint>
#include <string>
#include <vector>

namespace throng::h5 {

/// The number type of a growing dataset (stored little-endian).
enum class Number { float64, int64, int32 };

class GrowingDataset {
 public:
  /// Creates `name` in `group`: `type`, shape `shape` (may hold zeros), chunks `chunk` (same rank, each side ≥ 1),
  /// filled with `fill` where nothing is written. IoError naming the dataset.
  static GrowingDataset create(const Group& group, const std::string& name, Number type,
                               const std::vector<std::uint64_t>& shape, const std::vector<std::uint64_t>& chunk,
                               double fill);
  /// Opens a growing dataset of a file opened with File::open_for_update. InputError when it is missing or not
  /// of `type` and `rank` (a damaged or foreign file).
  static GrowingDataset open(const Group& group, const std::string& name, Number type, std::size_t rank);

  [[nodiscard]] std::vector<std::uint64_t> shape() const;
  /// Sets the extent (grows or shrinks). IoError on failure.
  void resize(const std::vector<std::uint64_t>& shape);
  /// Writes the block at `offset` of `count` (row-major values of the dataset's type), which must lie within the
  /// current extent. IoError on failure.
  void write(const std::vector<std::uint64_t>& offset, const std::vector<std::uint64_t>& count, const void* values);
  /// Grows the first axis by `rows` (the other axes as they are) and writes them.
  void append(std::uint64_t rows, const void* values);

  [[nodiscard]] const std::string& where() const noexcept { return where_; }

 private:
  GrowingDataset(Handle set, Number type, std::string where) : set_(std::move(set)), type_(type), where_(std::move(where)) {}
  Handle set_;
  Number type_;
  std::string where_;
};

}  // namespace throng::h5
