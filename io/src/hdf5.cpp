#include <throng/core/errors.h>
#include <throng/io/checked_numbers.h>
#include <throng/io/hdf5.h>
#include <throng/io/input_crash.h>
#include <throng/io/input_file.h>

#include "address_space_cap.h"
#include "deflate_filter.h"
#include "direct_write_driver.h"
#include "filtered_chunks.h"
#include "global_heap_check.h"
#include "hdf5_detail.h"

#include <hdf5.h>
#include <H5PLpublic.h>

#include <algorithm>
#include <memory>
#include <cstring>
#include <mutex>
#include <type_traits>

namespace throng::h5 {

// Per-file state of a file opened for reading (see hdf5.h's header comment). A file created for writing has a
// context too, unbounded by a file size (bounded = false), so reading back what was just written still goes
// through the same element-count and memory checks.
struct ReadContext {
  ReadContext(std::filesystem::path file, std::uint64_t size, bool is_bounded, const ReadLimits& limits)
      : path(std::move(file)), file_size(size), bounded(is_bounded), budget(limits) {}
  std::filesystem::path path;
  std::uint64_t file_size = 0;
  bool bounded = false;
  MemoryBudget budget;
  bool heaps_checked = false;
  std::uint64_t heap_bytes = 0;  ///< total size of the objects of every global heap collection (vlen data)
  Handle link_access, group_access, dataset_access;  ///< refuse traversing external links
  Handle transfer;  ///< dataset reads: a value out of range of the type read is an error, not clamped
  std::unique_ptr<ReadingInput> reading;  ///< an input: a crash inside libhdf5 is reported as its damage (input_crash.h)
};

namespace {

static_assert(sizeof(hid_t) == sizeof(Id), "hid_t must be 64-bit (HDF5 ≥ 1.10)");

// Refuses every external link traversal (the callback runs before the other file is opened).
herr_t refuse_external_link(const char*, const char*, const char*, const char*, unsigned*, hid_t, void*) { return -1; }

// A conversion that would change a value (out of range, NaN or infinity to an integer) fails the read: libhdf5
// would otherwise clamp it silently (2^40 species becomes 2^31 − 1).
H5T_conv_ret_t refuse_lossy_conversion(H5T_conv_except_t kind, hid_t, hid_t, void*, void*, void*) {
  return kind == H5T_CONV_EXCEPT_PRECISION ? H5T_CONV_UNHANDLED : H5T_CONV_ABORT;
}

Handle access_properties(hid_t property_class) {
  Handle p(H5Pcreate(property_class));
  H5Pset_elink_cb(p.id(), refuse_external_link, nullptr);
  return p;
}

// Largest expansion of deflate (zlib): 1032 output bytes per input byte at most.
constexpr std::uint64_t deflate_max_ratio = 1032;
// A dataset may declare this many bytes beyond what its storage bounds (unwritten datasets read as fill values).
constexpr std::uint64_t storage_slack_bytes = 64 * 1024;

}  // namespace

namespace detail {

// Why HDF5 failed, for our messages: the outermost and the innermost descriptions of its current error stack (the
// steps between repeat them); a system error is given by its text alone ("No space left on device"), not by
// HDF5's report of the call, which names descriptors and buffer addresses.
std::string hdf5_reason() {
  std::vector<std::string> descriptions;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_DOWNWARD,
      [](unsigned, const H5E_error2_t* e, void* data) -> herr_t {
        if (e->desc && *e->desc) static_cast<std::vector<std::string>*>(data)->emplace_back(e->desc);
        return 0;
      },
      &descriptions);
  H5Eclear2(H5E_DEFAULT);
  if (descriptions.empty()) return "unknown HDF5 error";
  std::string inner = descriptions.back();
  if (const auto at = inner.find("error message = '"); at != std::string::npos) {
    const auto start = at + 17;
    inner = inner.substr(start, inner.find('\'', start) - start);
  }
  if (descriptions.size() == 1 || descriptions.front() == inner) return inner;
  return descriptions.front() + ": " + inner;
}

Handle checked(hid_t id, const std::string& what) {
  if (id < 0) throw IoError(what + ": " + hdf5_reason());
  return Handle(id);
}

void check(herr_t status, const std::string& what) {
  if (status < 0) throw IoError(what + ": " + hdf5_reason());
}


Handle simple_space(const std::vector<std::uint64_t>& shape) {
  std::vector<hsize_t> dims(shape.begin(), shape.end());
  return Handle(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr));
}

// HDF5 prints its error stack to stderr by default; we report our own messages instead. Filter plugins are never
// loaded: a file could otherwise name a plugin that HDF5_PLUGIN_PATH resolves to code run on its data.
//
// libhdf5 is never shut down at exit (H5dont_atexit, before its first call): when a write fails (a full disk),
// H5Fclose fails too and leaves the file's identifier pointing at a half-freed file, which libhdf5 1.10's exit
// handler (H5F_term_package → H5F__close_cb) then dereferences: the segfault (exit 139) after "disk full" of issue
// 18. Every file we write is closed explicitly and only committed when that succeeded, so nothing is lost.
//
// Chunks are inflated with ISA-L instead of zlib (deflate_filter.h).
void silence_hdf5() {
  static std::once_flag once;
  std::call_once(once, [] {
    H5dont_atexit();
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    H5PLset_loading_state(0);
    use_isal_inflate();
  });
}

}  // namespace detail

namespace {

using namespace detail;

Handle string_type() {
  Handle t(H5Tcopy(H5T_C_S1));
  H5Tset_size(t.id(), H5T_VARIABLE);
  H5Tset_cset(t.id(), H5T_CSET_UTF8);
  return t;
}


Handle untimed_group_properties() {
  Handle p(H5Pcreate(H5P_GROUP_CREATE));
  H5Pset_obj_track_times(p.id(), false);
  return p;
}

// A new dataset's creation properties; `chunked` (when given) receives its chunking when it is compressed
// (chunk_rows 0 otherwise).
Handle dataset_properties(const std::vector<std::uint64_t>& shape, std::size_t element_size, Layout layout,
                          detail::ChunkedLayout* chunked = nullptr) {
  Handle p(H5Pcreate(H5P_DATASET_CREATE));
  H5Pset_obj_track_times(p.id(), false);
  const bool nonempty = !shape.empty() && std::all_of(shape.begin(), shape.end(), [](auto d) { return d > 0; });
  if (layout.compress && nonempty) {
    std::uint64_t row = element_size;
    for (std::size_t i = 1; i < shape.size(); ++i) row *= shape[i];
    std::uint64_t rows = layout.chunk_rows;
    if (rows == 0) rows = std::max<std::uint64_t>(1, (256 * 1024) / std::max<std::uint64_t>(1, row));
    rows = std::min<std::uint64_t>(rows, shape[0]);
    std::vector<hsize_t> chunk(shape.begin(), shape.end());
    chunk[0] = rows;
    // Rank 3 or more ([frames][agents][components]): one component per chunk (ChunkedLayout::components), the
    // chunk's frames chosen for the whole row as before, so reading a frame decodes the same bytes.
    const std::uint64_t components = shape.size() >= 3 ? shape.back() : 1;
    if (components > 1) chunk.back() = 1;
    H5Pset_chunk(p.id(), static_cast<int>(chunk.size()), chunk.data());
    // Exactly these two filters, in this order: filter_chunks (filtered_chunks.h) applies the same pipeline.
    H5Pset_shuffle(p.id());
    H5Pset_deflate(p.id(), deflate_level);
    if (chunked) *chunked = {shape[0], row, rows, element_size, deflate_level, components};
  }
  return p;
}

template <class T>
void write_numeric(const Group& g, const std::string& name, const std::vector<T>& values,
                   const std::vector<std::uint64_t>& shape, Layout layout, hid_t memory_type, hid_t file_type) {
  std::uint64_t count = 1;
  for (auto d : shape) count *= d;
  if (count != values.size()) throw IoError(g.where(name) + ": internal shape mismatch when writing");
  Handle space = simple_space(shape);
  detail::ChunkedLayout chunked;
  Handle props = dataset_properties(shape, sizeof(T), layout, &chunked);
  Handle set = checked(H5Dcreate2(g.id(), name.c_str(), file_type, space.id(), H5P_DEFAULT, props.id(), H5P_DEFAULT),
                       "cannot create dataset " + g.where(name));
  if (count == 0) return;
  // Compressed, and the memory type is the file's (no conversion): the chunks are filtered in parallel.
  if (chunked.chunk_rows > 0 && H5Tequal(memory_type, file_type) > 0) {
    std::vector<hsize_t> offset(shape.size(), 0);
    detail::filter_chunks(reinterpret_cast<const std::byte*>(values.data()), chunked, g.where(name),
                          [&](std::uint64_t first_row, std::uint64_t component, const unsigned char* bytes, std::size_t size) {
                            offset[0] = first_row;
                            if (chunked.components > 1) offset.back() = component;
                            // Filter mask 0: every filter of the dataset (shuffle, then deflate) was applied.
                            check(H5Dwrite_chunk(set.id(), H5P_DEFAULT, 0, offset.data(), size, bytes),
                                  "cannot write " + g.where(name));
                          });
    return;
  }
  check(H5Dwrite(set.id(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), "cannot write " + g.where(name));
}

std::string shape_text(const std::vector<std::uint64_t>& dims) {
  if (dims.empty()) return "a single value";
  std::string text;
  for (auto d : dims) text += "[" + std::to_string(d) + "]";
  return text;
}

// A dataspace's extent: dims (empty for a scalar) and element count (overflow-checked).
struct Extent {
  std::vector<std::uint64_t> dims;
  std::uint64_t count = 0;
};

Extent extent_of(hid_t space, const std::string& where) {
  Extent e;
  const H5S_class_t kind = H5Sget_simple_extent_type(space);
  if (kind == H5S_NULL) return e;
  if (kind == H5S_SCALAR) {
    e.count = 1;
    return e;
  }
  const int rank = H5Sget_simple_extent_ndims(space);
  if (kind != H5S_SIMPLE || rank < 0) throw InputError(where + ": has an unreadable shape (damaged file?)");
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  if (rank > 0 && H5Sget_simple_extent_dims(space, dims.data(), nullptr) < 0) {
    throw InputError(where + ": has an unreadable shape (damaged file?)");
  }
  e.dims.assign(dims.begin(), dims.end());
  const auto count = checked_product(std::span<const std::uint64_t>(e.dims));
  if (!count) throw InputError(where + ": shape " + shape_text(e.dims) + " holds more elements than a 64-bit count (damaged file?)");
  e.count = *count;
  return e;
}

// A number type libhdf5 converts safely: integers of 1, 2, 4 or 8 whole bytes and IEEE 754 single and double
// precision floats, in either byte order. libhdf5 1.10 converts what a type's fields state: a crafted float type
// (fields wider than a machine word or past its bytes) smashed the stack in H5T__bit_get_d (found by fuzz_import),
// so every other layout is refused before a conversion sees it. InputError naming `where`.
void check_number_layout(hid_t type, const std::string& where) {
  const std::size_t size = H5Tget_size(type);
  const H5T_order_t order = H5Tget_order(type);
  bool standard = (order == H5T_ORDER_LE || order == H5T_ORDER_BE || (order == H5T_ORDER_NONE && size == 1)) &&
                  H5Tget_offset(type) == 0 && H5Tget_precision(type) == 8 * size;
  if (H5Tget_class(type) == H5T_FLOAT) {
    std::size_t spos = 0, epos = 0, esize = 0, mpos = 0, msize = 0;
    standard = standard && H5Tget_fields(type, &spos, &epos, &esize, &mpos, &msize) >= 0 && mpos == 0 &&
               H5Tget_norm(type) == H5T_NORM_IMPLIED &&
               ((size == 4 && spos == 31 && epos == 23 && esize == 8 && msize == 23 && H5Tget_ebias(type) == 127) ||
                (size == 8 && spos == 63 && epos == 52 && esize == 11 && msize == 52 && H5Tget_ebias(type) == 1023));
  } else {
    standard = standard && (size == 1 || size == 2 || size == 4 || size == 8);
  }
  if (!standard) {
    throw InputError(where + ": stores " + std::to_string(size) + "-byte numbers in a layout throng does not read (damaged or hostile " +
                     "file?); throng reads 1-, 2-, 4- and 8-byte integers and IEEE 754 single and double precision");
  }
}

// What reading a dataset needs besides the caller's buffer: libhdf5's working memory (require_working_memory checks
// it), and the bytes one of its filtered chunks decodes to (0: not filtered, or not known).
struct StorageNeeds {
  std::uint64_t working_bytes = 0;
  std::uint64_t decoded_chunk_bytes = 0;
};

// What the file holds of a dataset, checked: no external files, no virtual layout, known filters; the declared
// bytes (`file_bytes`) within what the storage can expand to. Throws InputError naming the dataset.
StorageNeeds check_dataset_storage(hid_t set, const std::string& where, const Extent& e, std::uint64_t file_element_size,
                                    const ReadContext& context) {
  const Handle dcpl(H5Dget_create_plist(set));
  if (!dcpl.valid()) throw InputError(where + ": cannot read its storage properties (damaged file?)");
  const H5D_layout_t layout = H5Pget_layout(dcpl.id());
  if (layout == H5D_VIRTUAL) {
    throw InputError(where + ": is a virtual dataset (its data lives in other files); throng reads only data stored in the file itself");
  }
  if (H5Pget_external_count(dcpl.id()) != 0) {
    throw InputError(where + ": stores its data in external files; throng reads only data stored in the file itself");
  }
  std::uint64_t ratio = 1;
  const int filters = H5Pget_nfilters(dcpl.id());
  for (int i = 0; i < filters; ++i) {
    unsigned flags = 0, config = 0;
    std::size_t values = 0;
    char name[64] = {};
    const H5Z_filter_t f = H5Pget_filter2(dcpl.id(), static_cast<unsigned>(i), &flags, &values, nullptr, sizeof name, name, &config);
    if (f == H5Z_FILTER_DEFLATE) ratio = deflate_max_ratio;
    else if (f != H5Z_FILTER_SHUFFLE && f != H5Z_FILTER_FLETCHER32) {
      throw InputError(where + ": is compressed with HDF5 filter " + std::to_string(f) + (name[0] ? std::string(" (") + name + ")" : "") +
                       "; throng reads deflate, shuffle and fletcher32 only");
    }
  }
  const auto file_bytes = checked_product(e.count, file_element_size);
  if (!file_bytes) throw InputError(where + ": shape " + shape_text(e.dims) + " holds more bytes than a 64-bit count (damaged file?)");
  if (!context.bounded || *file_bytes == 0) return {};

  const std::uint64_t stored = H5Dget_storage_size(set);
  if (stored > context.file_size) {
    throw InputError(where + ": claims " + format_bytes(stored) + " of storage in a file of " + format_bytes(context.file_size) + " (damaged file)");
  }
  if (layout == H5D_CONTIGUOUS) {
    const haddr_t offset = H5Dget_offset(set);
    if (offset != HADDR_UNDEF) {
      const auto end = checked_sum(offset, *file_bytes);
      if (!end || *end > context.file_size) {
        throw InputError(where + ": declares " + shape_text(e.dims) + " (" + format_bytes(*file_bytes) + ") but the file holds only " +
                         format_bytes(context.file_size) + ": truncated or damaged");
      }
    }
  }
  // Contiguous (allocated) and compact data are read as one block of the layout's stated size: a layout smaller
  // than the shape's bytes makes libhdf5 1.10 copy past its buffer (H5D__contig_readvv_sieve_cb, found by
  // fuzz_tiling_data), so the two must agree before anything is read.
  const bool one_block = layout == H5D_COMPACT || (layout == H5D_CONTIGUOUS && H5Dget_offset(set) != HADDR_UNDEF);
  if (one_block) {
    if (stored < *file_bytes) {
      throw InputError(where + ": declares " + shape_text(e.dims) + " (" + format_bytes(*file_bytes) + ") but its layout stores " +
                       format_bytes(stored) + ": damaged file");
    }
    if (layout == H5D_CONTIGUOUS) return {};
  }
  const auto bound = checked_sum(checked_product(stored, ratio).value_or(UINT64_MAX), storage_slack_bytes).value_or(UINT64_MAX);
  if (*file_bytes > bound) {
    throw InputError(where + ": declares " + shape_text(e.dims) + " (" + format_bytes(*file_bytes) + ") but stores " + format_bytes(stored) +
                     (ratio > 1 ? ", more than compression can expand to" : "") + ": damaged or hostile file, refused before reading");
  }
  if (layout == H5D_CHUNKED) {
    // libhdf5 allocates a whole chunk to read any part of it: the chunk too must fit the bound.
    const int rank = static_cast<int>(e.dims.size());
    std::vector<hsize_t> chunk(static_cast<std::size_t>(std::max(rank, 1)), 0);
    if (H5Pget_chunk(dcpl.id(), rank, chunk.data()) != rank) throw InputError(where + ": has an unreadable chunk shape (damaged file?)");
    std::vector<std::uint64_t> sides(chunk.begin(), chunk.begin() + rank);
    sides.push_back(file_element_size);
    const auto chunk_bytes = checked_product(std::span<const std::uint64_t>(sides));
    if (!chunk_bytes || *chunk_bytes > bound) {
      throw InputError(where + ": its chunks (" + (chunk_bytes ? format_bytes(*chunk_bytes) : std::string("beyond 2^64 bytes")) +
                       " each) are larger than the " + format_bytes(stored) + " it stores can expand to: damaged or hostile file, refused before reading");
    }
    // A filtered chunk is decoded in libhdf5's own buffer: deflate (deflate_filter.h) inflates into one buffer of the
    // chunk's size, told by DecodedChunkBytes, while the stored chunk is alive; the shuffle makes a chunk-sized copy.
    // Three chunks cover them. An unfiltered chunk larger than the chunk cache is read straight into the caller's
    // buffer.
    if (filters > 0) return {checked_product(*chunk_bytes, 3).value_or(UINT64_MAX), *chunk_bytes};
  }
  return {};
}

// The working memory check_dataset_storage returned, beside what the context's budget already holds (the
// caller's buffer charged first): a small file whose one chunk decodes to a gigabyte is refused here.
// Returns the deflate filter's bound on one chunk, for the read that follows (while it lives).
[[nodiscard]] DecodedChunkBytes require_working_memory(const ReadContext& context, const StorageNeeds& needs, const std::string& where) {
  if (needs.working_bytes > 0) context.budget.require(needs.working_bytes, where, "libhdf5's buffers to decode one compressed chunk");
  return DecodedChunkBytes(needs.decoded_chunk_bytes);
}

// Walks the file's global heap collections once, before the first variable-length read (see global_heap_check.h).
void check_heaps_once(hid_t file_or_object, ReadContext& context) {
  if (context.heaps_checked || !context.bounded) return;
  const Handle file(H5Iget_file_id(file_or_object));
  std::size_t length_size = 8;
  if (file.valid()) {
    const Handle fcpl(H5Fget_create_plist(file.id()));
    std::size_t address_size = 8;
    if (fcpl.valid()) H5Pget_sizes(fcpl.id(), &address_size, &length_size);
  }
  context.heap_bytes = check_global_heaps(context.path, context.file_size, length_size);
  context.heaps_checked = true;
}

ReadContext& context_of(const std::shared_ptr<ReadContext>& context) {
  if (!context) throw IoError("internal: HDF5 group without a file context");
  return *context;
}

template <class T>
Array<T> read_numeric(const Group& g, ReadContext& context, const std::string& name, int expected_rank, hid_t memory_type,
                      bool read_values) {
  if (!g.has(name)) throw InputError(g.where(name) + ": missing dataset");
  Handle set(H5Dopen2(g.id(), name.c_str(), context.dataset_access.id()));
  if (!set.valid()) throw InputError(g.where(name) + ": cannot open dataset (" + hdf5_reason() + ")");
  Handle type(H5Dget_type(set.id()));
  const H5T_class_t cls = H5Tget_class(type.id());
  if (cls != H5T_INTEGER && cls != H5T_FLOAT) throw InputError(g.where(name) + ": is not a numeric dataset");
  check_number_layout(type.id(), g.where(name));
  const std::size_t element = H5Tget_size(type.id());
  Handle space(H5Dget_space(set.id()));
  const Extent e = extent_of(space.id(), g.where(name));
  const int rank = static_cast<int>(e.dims.size());
  if (expected_rank >= 0 && rank != expected_rank) {
    throw InputError(g.where(name) + ": has rank " + std::to_string(rank) + ", expected " + std::to_string(expected_rank));
  }
  const StorageNeeds needs = check_dataset_storage(set.id(), g.where(name), e, element, context);
  Array<T> out;
  out.shape = e.dims;
  if (!read_values) return out;  // the working memory is checked when the values are read
  const auto bytes = checked_product(e.count, sizeof(T));
  context.budget.charge(bytes.value_or(UINT64_MAX), g.where(name), shape_text(e.dims) + " × " + std::to_string(sizeof(T)) + " bytes");
  const DecodedChunkBytes decoding = require_working_memory(context, needs, g.where(name));
  out.values.resize(e.count);
  if (e.count > 0 && H5Dread(set.id(), memory_type, H5S_ALL, H5S_ALL, context.transfer.id(), out.values.data()) < 0) {
    throw InputError(g.where(name) + ": cannot read (" + hdf5_reason() +
                     "); is a value out of range for " + (std::is_floating_point_v<T> ? "a double" : std::to_string(8 * sizeof(T)) + "-bit integers") +
                     ", or the file truncated or damaged?");
  }
  return out;
}

// Strings of a dataset or attribute, after bounding them: a fixed-length string's bytes must lie in the file; a
// variable-length string's characters live in the global heap, which is checked first and whose size bounds
// them. `stored_bytes`: what the file holds for the object (a dataset's checked storage, an attribute's size).
std::vector<std::string> read_string_data(hid_t object, bool attribute, const std::string& where, ReadContext& context) {
  Handle type(attribute ? H5Aget_type(object) : H5Dget_type(object));
  if (H5Tget_class(type.id()) != H5T_STRING) throw InputError(where + ": is not a string");
  Handle space(attribute ? H5Aget_space(object) : H5Dget_space(object));
  const Extent e = extent_of(space.id(), where);
  std::vector<std::string> out;
  if (e.count == 0) return out;
  const bool variable = H5Tis_variable_str(type.id()) > 0;
  const std::size_t size = variable ? 16 : H5Tget_size(type.id());  // a variable-length string's descriptor: 16 bytes
  if (size == 0) throw InputError(where + ": has 0-byte strings");
  if (attribute) {
    const auto bytes = checked_product(e.count, size);
    if (!bytes || (context.bounded && *bytes > context.file_size)) {
      throw InputError(where + ": declares " + shape_text(e.dims) + " strings, more than the file of " + format_bytes(context.file_size) + " holds");
    }
  }
  const StorageNeeds needs = attribute ? StorageNeeds{} : check_dataset_storage(object, where, e, size, context);
  if (variable) {
    check_heaps_once(object, context);
    const auto bytes = checked_sum(checked_product(e.count, sizeof(char*) + sizeof(std::string)).value_or(UINT64_MAX), context.heap_bytes);
    context.budget.charge(bytes.value_or(UINT64_MAX), where, shape_text(e.dims) + " strings");
    const DecodedChunkBytes decoding = require_working_memory(context, needs, where);
    Handle memory = string_type();
    std::vector<char*> raw(static_cast<std::size_t>(e.count), nullptr);
    herr_t status = -1;
    {
      // The conversion may ask for what a damaged descriptor states (see address_space_cap.h): room for the
      // heap's checked bytes twice over (conversion buffer and result) and libhdf5's own working memory.
      const std::uint64_t heap = context.bounded ? context.heap_bytes : 0;
      const AddressSpaceCap cap(checked_sum(checked_product(heap, 4).value_or(UINT64_MAX), 256ull << 20).value_or(UINT64_MAX));
      status = attribute ? H5Aread(object, memory.id(), raw.data())
                         : H5Dread(object, memory.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, raw.data());
    }
    if (status < 0) throw InputError(where + ": cannot read string (" + hdf5_reason() + ")");
    for (char* s : raw) out.emplace_back(s ? s : "");
    H5Dvlen_reclaim(memory.id(), space.id(), H5P_DEFAULT, raw.data());
  } else {
    const auto bytes = checked_product(e.count, size);
    context.budget.charge(checked_product(bytes.value_or(UINT64_MAX), 2).value_or(UINT64_MAX), where, shape_text(e.dims) + " strings of " + std::to_string(size) + " bytes");
    const DecodedChunkBytes decoding = require_working_memory(context, needs, where);
    std::vector<char> raw(static_cast<std::size_t>(*bytes), '\0');
    Handle memory(H5Tcopy(H5T_C_S1));
    H5Tset_size(memory.id(), size);
    const herr_t status = attribute ? H5Aread(object, memory.id(), raw.data())
                                    : H5Dread(object, memory.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, raw.data());
    if (status < 0) throw InputError(where + ": cannot read string (" + hdf5_reason() + ")");
    for (std::uint64_t i = 0; i < e.count; ++i) {
      const char* s = raw.data() + static_cast<std::size_t>(i) * size;
      out.emplace_back(s, strnlen(s, size));
    }
  }
  return out;
}

// An attribute's numbers: its class checked, its count bounded by the file and charged to the budget.
template <class T>
std::vector<T> read_number_attribute(const Group& g, ReadContext& context, const std::string& name, hid_t memory_type,
                                     bool integers_only) {
  const std::string where = g.where() + " attribute " + name;
  Handle attr(H5Aopen(g.id(), name.c_str(), H5P_DEFAULT));
  if (!attr.valid()) throw InputError(where + ": cannot open (" + hdf5_reason() + ")");
  Handle type(H5Aget_type(attr.id()));
  const H5T_class_t cls = H5Tget_class(type.id());
  if (cls != H5T_INTEGER && (integers_only || cls != H5T_FLOAT)) {
    throw InputError(where + ": is not " + (integers_only ? "an integer" : "a number"));
  }
  check_number_layout(type.id(), where);
  const std::size_t element = H5Tget_size(type.id());
  Handle space(H5Aget_space(attr.id()));
  const Extent e = extent_of(space.id(), where);
  const auto file_bytes = checked_product(e.count, element);
  if (!file_bytes || (context.bounded && *file_bytes > context.file_size)) {
    throw InputError(where + ": declares " + shape_text(e.dims) + " numbers, more than the file of " + format_bytes(context.file_size) + " holds");
  }
  context.budget.charge(checked_product(e.count, sizeof(T)).value_or(UINT64_MAX), where, shape_text(e.dims) + " numbers");
  std::vector<T> out(static_cast<std::size_t>(e.count));
  if (!out.empty() && H5Aread(attr.id(), memory_type, out.data()) < 0) {
    throw InputError(where + ": cannot read (" + hdf5_reason() + ")");
  }
  return out;
}

void write_string_attribute(hid_t object, const std::string& name, const std::vector<std::string>& values, bool scalar,
                            const std::string& where) {
  Handle type = string_type();
  Handle space = scalar ? Handle(H5Screate(H5S_SCALAR)) : simple_space({values.size()});
  if (H5Aexists(object, name.c_str()) > 0) H5Adelete(object, name.c_str());
  Handle attr = checked(H5Acreate2(object, name.c_str(), type.id(), space.id(), H5P_DEFAULT, H5P_DEFAULT),
                        "cannot create attribute " + name + " on " + where);
  std::vector<const char*> raw;
  for (const auto& v : values) raw.push_back(v.c_str());
  if (!raw.empty()) check(H5Awrite(attr.id(), type.id(), raw.data()), "cannot write attribute " + name + " on " + where);
}

}  // namespace

Handle& Handle::operator=(Handle&& other) noexcept {
  if (this != &other) {
    Handle old(id_);
    id_ = other.id_;
    other.id_ = -1;
  }
  return *this;
}

Handle::~Handle() {
  if (id_ < 0) return;
  switch (H5Iget_type(id_)) {
    case H5I_FILE: H5Fclose(id_); break;
    case H5I_GROUP: H5Gclose(id_); break;
    case H5I_DATASET: H5Dclose(id_); break;
    case H5I_DATASPACE: H5Sclose(id_); break;
    case H5I_DATATYPE: H5Tclose(id_); break;
    case H5I_ATTR: H5Aclose(id_); break;
    case H5I_GENPROP_LST: H5Pclose(id_); break;
    default: break;
  }
}

MemoryBudget& Group::budget() const { return context_of(context_).budget; }

std::string Group::where(const std::string& name) const {
  std::string p = path_;
  if (!name.empty()) p = (p == "/" ? "" : p) + "/" + name;
  return file_ + ":" + p;
}

bool Group::has(const std::string& name) const {
  // Check each path component so that a missing intermediate group is "absent", not an error, and so that no
  // component is a link to another file (the link access list refuses those too, for soft links that lead there).
  const ReadContext& context = context_of(context_);
  std::string prefix;
  std::size_t start = 0;
  while (start <= name.size()) {
    const std::size_t slash = name.find('/', start);
    prefix = name.substr(0, slash);
    if (H5Lexists(id(), prefix.c_str(), context.link_access.id()) <= 0) return false;
    H5L_info_t info{};
    if (H5Lget_info(id(), prefix.c_str(), &info, context.link_access.id()) < 0) return false;
    if (info.type != H5L_TYPE_HARD && info.type != H5L_TYPE_SOFT) {
      throw InputError(where(prefix) + ": is a " + (info.type == H5L_TYPE_EXTERNAL ? "link to another file (external link)" : "user-defined link") +
                       "; throng reads only data stored in the file itself");
    }
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  return H5Oexists_by_name(id(), name.c_str(), context.link_access.id()) > 0;
}

bool Group::has_group(const std::string& name) const {
  if (!has(name)) return false;
  H5O_info_t info{};
  if (H5Oget_info_by_name(id(), name.c_str(), &info, context_of(context_).link_access.id()) < 0) return false;
  return info.type == H5O_TYPE_GROUP;
}

Group Group::create_group(const std::string& name) const {
  Handle props = untimed_group_properties();
  Handle g = checked(H5Gcreate2(id(), name.c_str(), H5P_DEFAULT, props.id(), H5P_DEFAULT), "cannot create group " + where(name));
  return Group(std::move(g), file_, where(name).substr(file_.size() + 1), context_);
}

Group Group::open_group(const std::string& name) const {
  if (!has_group(name)) throw InputError(where(name) + (has(name) ? ": is not a group" : ": missing group"));
  Handle g(H5Gopen2(id(), name.c_str(), context_of(context_).group_access.id()));
  if (!g.valid()) throw InputError(where(name) + ": cannot open group (" + hdf5_reason() + ")");
  return Group(std::move(g), file_, where(name).substr(file_.size() + 1), context_);
}

void Group::write(const std::string& name, const std::vector<double>& values, const std::vector<std::uint64_t>& shape, Layout layout) const {
  write_numeric(*this, name, values, shape, layout, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE);
}
void Group::write(const std::string& name, const std::vector<std::int64_t>& values, const std::vector<std::uint64_t>& shape, Layout layout) const {
  write_numeric(*this, name, values, shape, layout, H5T_NATIVE_INT64, H5T_STD_I64LE);
}
void Group::write(const std::string& name, const std::vector<std::int32_t>& values, const std::vector<std::uint64_t>& shape, Layout layout) const {
  write_numeric(*this, name, values, shape, layout, H5T_NATIVE_INT32, H5T_STD_I32LE);
}

void Group::write(const std::string& name, const std::vector<std::string>& values) const {
  Handle type = string_type();
  Handle space = simple_space({values.size()});
  Handle props = dataset_properties({values.size()}, sizeof(char*), {});
  Handle set = checked(H5Dcreate2(id(), name.c_str(), type.id(), space.id(), H5P_DEFAULT, props.id(), H5P_DEFAULT),
                       "cannot create dataset " + where(name));
  std::vector<const char*> raw;
  for (const auto& v : values) raw.push_back(v.c_str());
  if (!raw.empty()) check(H5Dwrite(set.id(), type.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, raw.data()), "cannot write " + where(name));
}

void Group::write_scalar(const std::string& name, const std::string& value) const {
  Handle type = string_type();
  Handle space(H5Screate(H5S_SCALAR));
  Handle props = dataset_properties({}, sizeof(char*), {});
  Handle set = checked(H5Dcreate2(id(), name.c_str(), type.id(), space.id(), H5P_DEFAULT, props.id(), H5P_DEFAULT),
                       "cannot create dataset " + where(name));
  const char* raw = value.c_str();
  check(H5Dwrite(set.id(), type.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, &raw), "cannot write " + where(name));
}

std::vector<std::uint64_t> Group::shape(const std::string& name) const {
  return read_numeric<double>(*this, context_of(context_), name, -1, H5T_NATIVE_DOUBLE, false).shape;
}

Array<double> Group::read_doubles(const std::string& name, int expected_rank) const {
  return read_numeric<double>(*this, context_of(context_), name, expected_rank, H5T_NATIVE_DOUBLE, true);
}
Array<std::int64_t> Group::read_int64(const std::string& name, int expected_rank) const {
  return read_numeric<std::int64_t>(*this, context_of(context_), name, expected_rank, H5T_NATIVE_INT64, true);
}
Array<std::int32_t> Group::read_int32(const std::string& name, int expected_rank) const {
  return read_numeric<std::int32_t>(*this, context_of(context_), name, expected_rank, H5T_NATIVE_INT32, true);
}

namespace {

// Every member of a file's compound type inside its row: libhdf5 1.10 converts rows by the members' stored offsets
// without checking them against the row's size (a damaged file with a member past the row makes H5Dread read
// past its own buffer), so the layout is checked before any read.
void check_compound_layout(hid_t type, const std::string& where) {
  const std::size_t row = H5Tget_size(type);
  const int count = H5Tget_nmembers(type);
  if (row == 0 || count < 0) throw InputError(where + ": has a damaged table type (" + hdf5_reason() + ")");
  for (int i = 0; i < count; ++i) {
    const auto u = static_cast<unsigned>(i);
    Handle member_type(H5Tget_member_type(type, u));
    const std::size_t offset = H5Tget_member_offset(type, u);
    const std::size_t size = member_type.valid() ? H5Tget_size(member_type.id()) : 0;
    if (size == 0 || offset > row || size > row - offset) {
      throw InputError(where + ": column " + std::to_string(i) + " lies at bytes " + std::to_string(offset) + "+" +
                       std::to_string(size) + " of a " + std::to_string(row) + "-byte row; truncated or damaged file?");
    }
  }
}

}  // namespace

Array<double> Group::read_compound_member(const std::string& name, const std::string& member) const {
  ReadContext& context = context_of(context_);
  if (!has(name)) throw InputError(where(name) + ": missing dataset");
  Handle set(H5Dopen2(id(), name.c_str(), context.dataset_access.id()));
  if (!set.valid()) throw InputError(where(name) + ": cannot open dataset (" + hdf5_reason() + ")");
  Handle type(H5Dget_type(set.id()));
  if (H5Tget_class(type.id()) != H5T_COMPOUND) throw InputError(where(name) + ": is not a compound dataset (a table of named columns)");
  check_compound_layout(type.id(), where(name));
  const int index = H5Tget_member_index(type.id(), member.c_str());
  if (index < 0) throw InputError(where(name) + ": has no member '" + member + "'");
  Handle member_type(H5Tget_member_type(type.id(), static_cast<unsigned>(index)));
  const H5T_class_t cls = H5Tget_class(member_type.id());
  if (cls != H5T_INTEGER && cls != H5T_FLOAT) throw InputError(where(name) + ": member '" + member + "' is not numeric");
  check_number_layout(member_type.id(), where(name) + " member '" + member + "'");
  Handle space(H5Dget_space(set.id()));
  const Extent e = extent_of(space.id(), where(name));
  if (e.dims.size() != 1) throw InputError(where(name) + ": has rank " + std::to_string(e.dims.size()) + ", expected 1 (a table of rows)");
  const StorageNeeds needs = check_dataset_storage(set.id(), where(name), e, H5Tget_size(type.id()), context);
  Array<double> out;
  out.shape = e.dims;
  context.budget.charge(checked_product(e.count, sizeof(double)).value_or(UINT64_MAX), where(name) + " member " + member,
                        shape_text(e.dims) + " × 8 bytes");
  const DecodedChunkBytes decoding = require_working_memory(context, needs, where(name));
  out.values.resize(e.count);
  Handle memory(H5Tcreate(H5T_COMPOUND, sizeof(double)));
  if (!memory.valid() || H5Tinsert(memory.id(), member.c_str(), 0, H5T_NATIVE_DOUBLE) < 0) {
    throw InputError(where(name) + ": cannot describe member '" + member + "' (" + hdf5_reason() + ")");
  }
  if (e.count > 0 && H5Dread(set.id(), memory.id(), H5S_ALL, H5S_ALL, context.transfer.id(), out.values.data()) < 0) {
    throw InputError(where(name) + ": cannot read member '" + member + "' (" + hdf5_reason() + "); truncated or damaged file?");
  }
  return out;
}

std::vector<std::string> Group::compound_members(const std::string& name) const {
  ReadContext& context = context_of(context_);
  if (!has(name)) return {};
  Handle set(H5Dopen2(id(), name.c_str(), context.dataset_access.id()));
  if (!set.valid()) return {};
  Handle type(H5Dget_type(set.id()));
  if (H5Tget_class(type.id()) != H5T_COMPOUND) return {};
  std::vector<std::string> out;
  const int count = H5Tget_nmembers(type.id());
  for (int i = 0; i < count && i < 1024; ++i) {
    char* member = H5Tget_member_name(type.id(), static_cast<unsigned>(i));
    if (!member) continue;
    out.emplace_back(member);
    H5free_memory(member);
  }
  return out;
}

std::vector<std::string> Group::read_strings(const std::string& name) const {
  if (!has(name)) throw InputError(where(name) + ": missing dataset");
  ReadContext& context = context_of(context_);
  Handle set(H5Dopen2(id(), name.c_str(), context.dataset_access.id()));
  if (!set.valid()) throw InputError(where(name) + ": cannot open dataset");
  return read_string_data(set.id(), false, where(name), context);
}

std::string Group::read_scalar_string(const std::string& name) const {
  auto v = read_strings(name);
  if (v.size() != 1) throw InputError(where(name) + ": expected one string, found " + std::to_string(v.size()));
  return v.front();
}

void Group::link(const std::string& name, const std::string& target) const {
  check(H5Lcreate_hard(id(), target.c_str(), id(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT), "cannot link " + where(name));
}

void Group::set_attribute(const std::string& name, const std::string& value) const {
  write_string_attribute(id(), name, {value}, true, where());
}
void Group::set_attribute(const std::string& name, const std::vector<std::string>& values) const {
  write_string_attribute(id(), name, values, false, where());
}
void Group::set_attribute(const std::string& name, const std::vector<std::int32_t>& values) const {
  Handle space = simple_space({values.size()});
  if (H5Aexists(id(), name.c_str()) > 0) H5Adelete(id(), name.c_str());
  Handle attr = checked(H5Acreate2(id(), name.c_str(), H5T_STD_I32LE, space.id(), H5P_DEFAULT, H5P_DEFAULT),
                        "cannot create attribute " + name + " on " + where());
  check(H5Awrite(attr.id(), H5T_NATIVE_INT32, values.data()), "cannot write attribute " + name);
}
void Group::set_attribute(const std::string& name, std::int64_t value) const {
  Handle space(H5Screate(H5S_SCALAR));
  if (H5Aexists(id(), name.c_str()) > 0) H5Adelete(id(), name.c_str());
  Handle attr = checked(H5Acreate2(id(), name.c_str(), H5T_STD_I64LE, space.id(), H5P_DEFAULT, H5P_DEFAULT),
                        "cannot create attribute " + name + " on " + where());
  check(H5Awrite(attr.id(), H5T_NATIVE_INT64, &value), "cannot write attribute " + name);
}
void Group::set_attribute(const std::string& name, std::uint64_t value) const {
  Handle space(H5Screate(H5S_SCALAR));
  if (H5Aexists(id(), name.c_str()) > 0) H5Adelete(id(), name.c_str());
  Handle attr = checked(H5Acreate2(id(), name.c_str(), H5T_STD_U64LE, space.id(), H5P_DEFAULT, H5P_DEFAULT),
                        "cannot create attribute " + name + " on " + where());
  check(H5Awrite(attr.id(), H5T_NATIVE_UINT64, &value), "cannot write attribute " + name);
}
void Group::set_attribute(const std::string& name, double value) const {
  Handle space(H5Screate(H5S_SCALAR));
  if (H5Aexists(id(), name.c_str()) > 0) H5Adelete(id(), name.c_str());
  Handle attr = checked(H5Acreate2(id(), name.c_str(), H5T_IEEE_F64LE, space.id(), H5P_DEFAULT, H5P_DEFAULT),
                        "cannot create attribute " + name + " on " + where());
  check(H5Awrite(attr.id(), H5T_NATIVE_DOUBLE, &value), "cannot write attribute " + name);
}

bool Group::has_attribute(const std::string& name) const { return H5Aexists(id(), name.c_str()) > 0; }

std::optional<std::string> Group::string_attribute(const std::string& name) const {
  if (!has_attribute(name)) return std::nullopt;
  Handle attr(H5Aopen(id(), name.c_str(), H5P_DEFAULT));
  if (!attr.valid()) throw InputError(where() + " attribute " + name + ": cannot open (" + hdf5_reason() + ")");
  auto v = read_string_data(attr.id(), true, where() + " attribute " + name, context_of(context_));
  if (v.empty()) return std::string{};
  return v.front();
}

std::vector<std::string> Group::string_array_attribute(const std::string& name) const {
  if (!has_attribute(name)) return {};
  Handle attr(H5Aopen(id(), name.c_str(), H5P_DEFAULT));
  if (!attr.valid()) throw InputError(where() + " attribute " + name + ": cannot open (" + hdf5_reason() + ")");
  return read_string_data(attr.id(), true, where() + " attribute " + name, context_of(context_));
}

std::vector<std::int64_t> Group::int_attribute(const std::string& name) const {
  if (!has_attribute(name)) return {};
  return read_number_attribute<std::int64_t>(*this, context_of(context_), name, H5T_NATIVE_INT64, true);
}

std::optional<std::uint64_t> Group::unsigned_attribute(const std::string& name) const {
  if (!has_attribute(name)) return std::nullopt;
  Handle attr(H5Aopen(id(), name.c_str(), H5P_DEFAULT));
  Handle type(H5Aget_type(attr.id()));
  const bool is_unsigned = H5Tget_class(type.id()) == H5T_INTEGER && H5Tget_sign(type.id()) == H5T_SGN_NONE;
  const std::vector<std::uint64_t> v = is_unsigned
      ? read_number_attribute<std::uint64_t>(*this, context_of(context_), name, H5T_NATIVE_UINT64, true)
      : [&] {
          std::vector<std::uint64_t> bits;
          for (std::int64_t i : read_number_attribute<std::int64_t>(*this, context_of(context_), name, H5T_NATIVE_INT64, true)) {
            bits.push_back(static_cast<std::uint64_t>(i));
          }
          return bits;
        }();
  if (v.size() != 1) {
    throw InputError(where() + " attribute " + name + ": holds " + std::to_string(v.size()) + " values, expected one integer");
  }
  return v.front();
}

std::optional<double> Group::double_attribute(const std::string& name) const {
  if (!has_attribute(name)) return std::nullopt;
  const std::vector<double> v = read_number_attribute<double>(*this, context_of(context_), name, H5T_NATIVE_DOUBLE, false);
  if (v.size() != 1) {
    throw InputError(where() + " attribute " + name + ": holds " + std::to_string(v.size()) + " values, expected one number");
  }
  return v.front();
}

std::optional<double> Group::double_attribute_on(const std::string& object, const std::string& name) const {
  if (!has(object)) throw InputError(where(object) + ": missing");
  // H5Oopen gives a group or dataset identifier; the object seen as a Group shares this file's read context.
  Handle handle(H5Oopen(id(), object.c_str(), H5P_DEFAULT));
  if (!handle.valid()) throw InputError(where(object) + ": cannot open (" + hdf5_reason() + ")");
  const Group o(std::move(handle), file_, (path_ == "/" ? "" : path_) + "/" + object, context_);
  return o.double_attribute(name);
}

void Group::set_attribute_on(const std::string& object, const std::string& name, const std::string& value) const {
  // H5Oopen gives a group or dataset identifier, which Handle closes by its type.
  Handle o = checked(H5Oopen(id(), object.c_str(), H5P_DEFAULT), "cannot open " + where(object));
  write_string_attribute(o.id(), name, {value}, true, where(object));
}

void Group::set_reference_attribute_on(const std::string& object, const std::string& name, const std::string& target) const {
  Handle o = checked(H5Oopen(id(), object.c_str(), H5P_DEFAULT), "cannot open " + where(object));
  hobj_ref_t ref{};
  check(H5Rcreate(&ref, id(), target.c_str(), H5R_OBJECT, -1), "cannot reference " + where(target));
  Handle space(H5Screate(H5S_SCALAR));
  Handle attr = checked(H5Acreate2(o.id(), name.c_str(), H5T_STD_REF_OBJ, space.id(), H5P_DEFAULT, H5P_DEFAULT),
                        "cannot create attribute " + name + " on " + where(object));
  check(H5Awrite(attr.id(), H5T_STD_REF_OBJ, &ref), "cannot write reference attribute " + name + " on " + where(object));
}

namespace {

std::shared_ptr<ReadContext> make_context(const std::filesystem::path& path, std::uint64_t size, bool bounded, const ReadLimits& limits) {
  auto context = std::make_shared<ReadContext>(path, size, bounded, limits);
  context->link_access = access_properties(H5P_LINK_ACCESS);
  context->group_access = access_properties(H5P_GROUP_ACCESS);
  context->dataset_access = access_properties(H5P_DATASET_ACCESS);
  context->transfer = Handle(H5Pcreate(H5P_DATASET_XFER));
  H5Pset_type_conv_cb(context->transfer.id(), refuse_lossy_conversion, nullptr);
  return context;
}

}  // namespace

File File::create(const std::filesystem::path& path, const std::string& display_name) {
  silence_hdf5();
  Handle props(H5Pcreate(H5P_FILE_CREATE));
  H5Pset_obj_track_times(props.id(), false);
  Handle access(H5Pcreate(H5P_FILE_ACCESS));
  use_direct_write_driver(access.id());  // large raw-data writes straight to the disk (direct_write_driver.h)
  hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, props.id(), access.id());
  const std::string name = display_name.empty() ? path.filename().string() : display_name;
  if (f < 0) throw IoError(name + ": cannot create HDF5 file (" + hdf5_reason() + ")");
  return File(Handle(f), name, make_context(path, 0, false, ReadLimits{}));
}

File File::open(const std::filesystem::path& path, const ReadLimits& limits) {
  silence_hdf5();
  const std::uint64_t size = check_input_file(path, "an HDF5 file");
  auto reading = std::make_unique<ReadingInput>(path);  // from libhdf5's first look at the file
  const htri_t is_hdf5 = H5Fis_hdf5(path.c_str());
  if (is_hdf5 <= 0) throw InputError(path.string() + ": is not an HDF5 file");
  // Closing the file closes everything of it still open (an error path may leave a dataset handle behind).
  Handle access(H5Pcreate(H5P_FILE_ACCESS));
  H5Pset_fclose_degree(access.id(), H5F_CLOSE_STRONG);
  hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, access.id());
  if (f < 0) throw InputError(path.string() + ": cannot open as HDF5 (" + hdf5_reason() + "); is the file truncated or damaged?");
  auto context = make_context(path, size, true, limits);
  context->reading = std::move(reading);
  return File(Handle(f), path.filename().string(), std::move(context));
}

File File::open_for_update(const std::filesystem::path& path, const std::string& display_name) {
  silence_hdf5();
  const std::string name = display_name.empty() ? path.filename().string() : display_name;
  (void)check_input_file(path, "an HDF5 file");
  auto reading = std::make_unique<ReadingInput>(path);  // a file to resume may be damaged (a power loss)
  if (H5Fis_hdf5(path.c_str()) <= 0) throw InputError(name + ": is not an HDF5 file");
  Handle access(H5Pcreate(H5P_FILE_ACCESS));
  H5Pset_fclose_degree(access.id(), H5F_CLOSE_STRONG);
  hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, access.id());
  if (f < 0) throw InputError(name + ": cannot open for writing (" + hdf5_reason() + "); is the file damaged?");
  auto context = make_context(path, 0, false, ReadLimits{});
  context->reading = std::move(reading);
  return File(Handle(f), name, std::move(context));
}

void File::flush() const {
  if (H5Fflush(handle_.id(), H5F_SCOPE_GLOBAL) < 0) throw IoError(name_ + ": cannot flush (" + hdf5_reason() + ")");
}

Group File::root() const {
  hid_t g = H5Gopen2(handle_.id(), "/", H5P_DEFAULT);
  if (g < 0) throw IoError(name_ + ": cannot open root group (" + hdf5_reason() + ")");
  return Group(Handle(g), name_, "/", context_);
}

void File::close() {
  if (!handle_.valid()) return;
  if (H5Fflush(handle_.id(), H5F_SCOPE_GLOBAL) < 0) throw IoError(name_ + ": cannot flush (" + hdf5_reason() + ")");
  handle_ = Handle();  // closes the file; a write failure was already surfaced by the flush above
}

}  // namespace throng::h5
