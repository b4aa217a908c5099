// A thin RAII layer over HDF5's C API: handles that close themselves, typed whole-dataset reads and writes with
// shape checks, and string/number attributes. Every failure throws IoError or InputError naming the file and the
// object path, never an HDF5 error stack on stderr.
//
// Reading is bounded: a file opened for reading hands libhdf5 nothing it has not checked first.
//  - Before a dataset or attribute is read, its element count is computed with overflow checks, its declared size
//    is compared with what the file stores (contiguous data must lie inside the file; chunked data may expand at
//    most by deflate's largest ratio, 1032:1; a chunk must fit the same bound), and the memory it needs is charged
//    to the file's MemoryBudget (ReadLimits): InputError with the estimate when any of these fails.
//  - Data stored outside the file is refused: external storage, external (and user-defined) links, virtual
//    datasets; filters other than deflate, shuffle and fletcher32 are refused and HDF5 filter plugins are never
//    loaded.
//  - Before the first variable-length string is read, the file's global heap collections are walked as libhdf5
//    1.10 walks them, and a collection whose object sizes do not add up refuses the file (libhdf5 would loop
//    forever or read past the collection).
//
// Objects are created without modification times, so the same data gives the same file bytes.
#pragma once

#include <throng/io/read_limits.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace throng::h5 {

/// HDF5 object identifier (hid_t is int64_t in HDF5 ≥ 1.10).
using Id = std::int64_t;

/// Owns one HDF5 identifier and closes it (file, group, dataset, dataspace, type, property list).
class Handle {
 public:
  Handle() = default;
  explicit Handle(Id id) noexcept : id_(id) {}
  Handle(Handle&& other) noexcept : id_(other.id_) { other.id_ = -1; }
  Handle& operator=(Handle&& other) noexcept;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle();

  [[nodiscard]] Id id() const noexcept { return id_; }
  [[nodiscard]] bool valid() const noexcept { return id_ >= 0; }

 private:
  Id id_ = -1;
};

/// A dataset's contents and shape (row-major).
template <class T>
struct Array {
  std::vector<T> values;
  std::vector<std::uint64_t> shape;
};

/// Layout of a new dataset: compressed datasets are chunked along their first axis; of rank 3 or more, also one
/// index of the last axis (a component) per chunk, which the shuffle and deflate filters compress better and faster.
struct Layout {
  bool compress = false;             ///< shuffle + deflate
  std::uint64_t chunk_rows = 0;      ///< rows of the first axis per chunk; 0 = choose (~256 KiB of rows; of rank 3
                                     ///< or more, each of the last axis's components a chunk of its own)
};

/// What a file opened for reading checks against: its size, its memory budget, its link access rules (defined in
/// hdf5.cpp). Shared by the file and its groups.
struct ReadContext;

/// A group (or the file's root group) of an open file; knows the file name and its own path for messages.
class Group {
 public:
  Group(Handle handle, std::string file, std::string path, std::shared_ptr<ReadContext> context)
      : handle_(std::move(handle)), file_(std::move(file)), path_(std::move(path)), context_(std::move(context)) {}

  [[nodiscard]] Id id() const noexcept { return handle_.id(); }
  [[nodiscard]] const std::string& path() const noexcept { return path_; }
  [[nodiscard]] const std::string& file() const noexcept { return file_; }
  /// "file.h5:/particles/trajectory/name", for messages.
  [[nodiscard]] std::string where(const std::string& name = {}) const;
  /// The memory budget of the file this group belongs to (one per opened file): every array read through it is
  /// charged there, and a reader charges what it builds from those arrays there too, so one limit bounds the
  /// whole read.
  [[nodiscard]] MemoryBudget& budget() const;

  [[nodiscard]] bool has(const std::string& name) const;
  /// True when `name` exists and is a group (not a dataset).
  [[nodiscard]] bool has_group(const std::string& name) const;
  [[nodiscard]] Group create_group(const std::string& name) const;
  /// Opens a subgroup; throws InputError "missing group" when absent.
  [[nodiscard]] Group open_group(const std::string& name) const;

  void write(const std::string& name, const std::vector<double>& values, const std::vector<std::uint64_t>& shape, Layout layout = {}) const;
  void write(const std::string& name, const std::vector<std::int64_t>& values, const std::vector<std::uint64_t>& shape, Layout layout = {}) const;
  void write(const std::string& name, const std::vector<std::int32_t>& values, const std::vector<std::uint64_t>& shape, Layout layout = {}) const;
  void write(const std::string& name, const std::vector<std::string>& values) const;  ///< 1-D variable-length UTF-8 strings
  void write_scalar(const std::string& name, const std::string& value) const;          ///< scalar variable-length string

  /// A numeric dataset's shape, checked as a read would check it (storage, size, memory) but not read: lets a
  /// reader estimate what a whole file needs before it reads the first large array.
  [[nodiscard]] std::vector<std::uint64_t> shape(const std::string& name) const;

  /// Whole-dataset reads converting to the requested type (HDF5 converts numeric types). `expected_rank` ≥ 0 checks
  /// the rank; throws InputError "missing dataset" / "has rank r, expected k" naming the dataset, and the bounds
  /// of the header comment.
  [[nodiscard]] Array<double> read_doubles(const std::string& name, int expected_rank = -1) const;
  [[nodiscard]] Array<std::int64_t> read_int64(const std::string& name, int expected_rank = -1) const;
  [[nodiscard]] Array<std::int32_t> read_int32(const std::string& name, int expected_rank = -1) const;
  [[nodiscard]] std::vector<std::string> read_strings(const std::string& name) const;
  /// One numeric member (`member`) of a 1-D compound dataset as doubles (HDF5 converts; int64 frame numbers and
  /// ids are exact up to 2^53), with the same bounds as the numeric reads (the storage is checked for the whole
  /// compound element). InputError "missing dataset", "is not a compound dataset", "has no member".
  [[nodiscard]] Array<double> read_compound_member(const std::string& name, const std::string& member) const;
  /// The member names of a compound dataset (empty for any other dataset).
  [[nodiscard]] std::vector<std::string> compound_members(const std::string& name) const;
  [[nodiscard]] std::string read_scalar_string(const std::string& name) const;

  /// Hard link `target` (a path in this file) under `name` (H5MD shares step/time datasets between elements).
  void link(const std::string& name, const std::string& target) const;

  // Attributes on this group.
  void set_attribute(const std::string& name, const std::string& value) const;
  void set_attribute(const std::string& name, const std::vector<std::string>& values) const;
  void set_attribute(const std::string& name, const std::vector<std::int32_t>& values) const;
  void set_attribute(const std::string& name, std::int64_t value) const;
  void set_attribute(const std::string& name, std::uint64_t value) const;  ///< stored as an unsigned 64-bit integer
  void set_attribute(const std::string& name, double value) const;
  [[nodiscard]] bool has_attribute(const std::string& name) const;
  [[nodiscard]] std::optional<std::string> string_attribute(const std::string& name) const;  ///< first if an array
  [[nodiscard]] std::vector<std::string> string_array_attribute(const std::string& name) const;  ///< empty if absent
  [[nodiscard]] std::vector<std::int64_t> int_attribute(const std::string& name) const;  ///< scalar or 1-D
  /// A single unsigned 64-bit integer; a signed attribute is taken bit for bit (−1 is 2^64 − 1: how seeds of
  /// 2^63 and more were stored before they were stored unsigned).
  [[nodiscard]] std::optional<std::uint64_t> unsigned_attribute(const std::string& name) const;
  /// A single number (InputError when the attribute holds several values, none, or is not numeric).
  [[nodiscard]] std::optional<double> double_attribute(const std::string& name) const;
  /// The same for an attribute of the dataset or group `object` below this one.
  [[nodiscard]] std::optional<double> double_attribute_on(const std::string& object, const std::string& name) const;

  /// Attributes on a dataset or group below this one.
  void set_attribute_on(const std::string& object, const std::string& name, const std::string& value) const;
  /// Object reference attribute on `object` pointing to `target` (H5MD's connectivity "particles_group").
  void set_reference_attribute_on(const std::string& object, const std::string& name, const std::string& target) const;

 private:
  Handle handle_;
  std::string file_;
  std::string path_;
  std::shared_ptr<ReadContext> context_;
};

/// An HDF5 file, open for reading or newly created for writing.
class File {
 public:
  /// Creates (truncating) `path` for writing; messages call it `display_name` (default: its file name), so a
  /// temporary file is reported under the name of the file it becomes. Throws IoError.
  static File create(const std::filesystem::path& path, const std::string& display_name = {});
  /// Opens an existing file read-only. Throws IoError (missing, a folder, not a regular file, unreadable) or
  /// InputError (not HDF5, truncated). Every read through it is bounded by `limits` (one budget for the file).
  static File open(const std::filesystem::path& path, const ReadLimits& limits = {});
  /// Opens an existing file that this program wrote for reading and writing (a resumed stream: growing.h);
  /// messages call it `display_name`. IoError (missing, unreadable) or InputError (not HDF5, damaged).
  static File open_for_update(const std::filesystem::path& path, const std::string& display_name = {});

  [[nodiscard]] Group root() const;
  /// Writes everything libhdf5 holds for the file to it (a record a later run resumes from); IoError on failure.
  void flush() const;
  /// Flushes and closes; throws IoError if HDF5 reports a failure (a full disk shows here).
  void close();

 private:
  File(Handle handle, std::string name, std::shared_ptr<ReadContext> context)
      : context_(std::move(context)), handle_(std::move(handle)), name_(std::move(name)) {}
  // The context first: it is destroyed last, so an input's ReadingInput (input_crash.h) still guards its close.
  std::shared_ptr<ReadContext> context_;
  Handle handle_;
  std::string name_;
};

}  // namespace throng::h5
