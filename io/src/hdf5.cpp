#include <throng/core/errors.h>
#include <throng/io/hdf5.h>

#include <hdf5.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <mutex>

namespace throng::h5 {
namespace {

static_assert(sizeof(hid_t) == sizeof(Id), "hid_t must be 64-bit (HDF5 ≥ 1.10)");

// HDF5 prints its error stack to stderr by default; we report our own messages instead.
void silence_hdf5() {
  static std::once_flag once;
  std::call_once(once, [] { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); });
}

// The innermost messages of HDF5's current error stack, for "why" in our messages.
std::string hdf5_reason() {
  std::string text;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_DOWNWARD,
      [](unsigned, const H5E_error2_t* e, void* data) -> herr_t {
        auto& s = *static_cast<std::string*>(data);
        if (e->desc && *e->desc) {
          if (!s.empty()) s += "; ";
          s += e->desc;
        }
        return 0;
      },
      &text);
  H5Eclear2(H5E_DEFAULT);
  return text.empty() ? std::string("unknown HDF5 error") : text;
}

Handle checked(hid_t id, const std::string& what) {
  if (id < 0) throw IoError(what + ": " + hdf5_reason());
  return Handle(id);
}

void check(herr_t status, const std::string& what) {
  if (status < 0) throw IoError(what + ": " + hdf5_reason());
}

Handle string_type() {
  Handle t(H5Tcopy(H5T_C_S1));
  H5Tset_size(t.id(), H5T_VARIABLE);
  H5Tset_cset(t.id(), H5T_CSET_UTF8);
  return t;
}

Handle simple_space(const std::vector<std::uint64_t>& shape) {
  std::vector<hsize_t> dims(shape.begin(), shape.end());
  return Handle(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr));
}

Handle untimed_group_properties() {
  Handle p(H5Pcreate(H5P_GROUP_CREATE));
  H5Pset_obj_track_times(p.id(), false);
  return p;
}

Handle dataset_properties(const std::vector<std::uint64_t>& shape, std::size_t element_size, Layout layout) {
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
    H5Pset_chunk(p.id(), static_cast<int>(chunk.size()), chunk.data());
    H5Pset_shuffle(p.id());
    H5Pset_deflate(p.id(), 4);
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
  Handle props = dataset_properties(shape, sizeof(T), layout);
  Handle set = checked(H5Dcreate2(g.id(), name.c_str(), file_type, space.id(), H5P_DEFAULT, props.id(), H5P_DEFAULT),
                       "cannot create dataset " + g.where(name));
  if (count > 0) check(H5Dwrite(set.id(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), "cannot write " + g.where(name));
}

template <class T>
Array<T> read_numeric(const Group& g, const std::string& name, int expected_rank, hid_t memory_type) {
  if (!g.has(name)) throw InputError(g.where(name) + ": missing dataset");
  Handle set(H5Dopen2(g.id(), name.c_str(), H5P_DEFAULT));
  if (!set.valid()) throw InputError(g.where(name) + ": cannot open dataset (" + hdf5_reason() + ")");
  Handle type(H5Dget_type(set.id()));
  const H5T_class_t cls = H5Tget_class(type.id());
  if (cls != H5T_INTEGER && cls != H5T_FLOAT) throw InputError(g.where(name) + ": is not a numeric dataset");
  Handle space(H5Dget_space(set.id()));
  const int rank = H5Sget_simple_extent_ndims(space.id());
  if (expected_rank >= 0 && rank != expected_rank) {
    throw InputError(g.where(name) + ": has rank " + std::to_string(rank) + ", expected " + std::to_string(expected_rank));
  }
  std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 0)));
  H5Sget_simple_extent_dims(space.id(), dims.data(), nullptr);
  Array<T> out;
  out.shape.assign(dims.begin(), dims.end());
  std::uint64_t count = 1;
  for (auto d : dims) count *= d;
  out.values.resize(count);
  if (count > 0 && H5Dread(set.id(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.values.data()) < 0) {
    throw InputError(g.where(name) + ": cannot read (" + hdf5_reason() + "); is the file truncated or damaged?");
  }
  return out;
}

std::vector<std::string> read_string_data(hid_t object, bool attribute, const std::string& where) {
  Handle type(attribute ? H5Aget_type(object) : H5Dget_type(object));
  if (H5Tget_class(type.id()) != H5T_STRING) throw InputError(where + ": is not a string");
  Handle space(attribute ? H5Aget_space(object) : H5Dget_space(object));
  const hssize_t count = H5Sget_simple_extent_npoints(space.id());
  std::vector<std::string> out;
  if (count <= 0) return out;
  if (H5Tis_variable_str(type.id()) > 0) {
    Handle memory = string_type();
    std::vector<char*> raw(static_cast<std::size_t>(count), nullptr);
    const herr_t status = attribute ? H5Aread(object, memory.id(), raw.data())
                                    : H5Dread(object, memory.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, raw.data());
    if (status < 0) throw InputError(where + ": cannot read string (" + hdf5_reason() + ")");
    for (char* s : raw) out.emplace_back(s ? s : "");
    H5Dvlen_reclaim(memory.id(), space.id(), H5P_DEFAULT, raw.data());
  } else {
    const std::size_t size = H5Tget_size(type.id());
    std::vector<char> raw(size * static_cast<std::size_t>(count), '\0');
    Handle memory(H5Tcopy(H5T_C_S1));
    H5Tset_size(memory.id(), size);
    const herr_t status = attribute ? H5Aread(object, memory.id(), raw.data())
                                    : H5Dread(object, memory.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, raw.data());
    if (status < 0) throw InputError(where + ": cannot read string (" + hdf5_reason() + ")");
    for (hssize_t i = 0; i < count; ++i) {
      const char* s = raw.data() + static_cast<std::size_t>(i) * size;
      out.emplace_back(s, strnlen(s, size));
    }
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

std::string Group::where(const std::string& name) const {
  std::string p = path_;
  if (!name.empty()) p = (p == "/" ? "" : p) + "/" + name;
  return file_ + ":" + p;
}

bool Group::has(const std::string& name) const {
  // Check each path component so that a missing intermediate group is "absent", not an error.
  std::string prefix;
  std::size_t start = 0;
  while (start <= name.size()) {
    const std::size_t slash = name.find('/', start);
    prefix = name.substr(0, slash);
    if (H5Lexists(id(), prefix.c_str(), H5P_DEFAULT) <= 0) return false;
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  return H5Oexists_by_name(id(), name.c_str(), H5P_DEFAULT) > 0;
}

bool Group::has_group(const std::string& name) const {
  if (!has(name)) return false;
  const Handle g(H5Gopen2(id(), name.c_str(), H5P_DEFAULT));  // fails (silently) on a dataset
  return g.valid();
}

Group Group::create_group(const std::string& name) const {
  Handle props = untimed_group_properties();
  Handle g = checked(H5Gcreate2(id(), name.c_str(), H5P_DEFAULT, props.id(), H5P_DEFAULT), "cannot create group " + where(name));
  return Group(std::move(g), file_, where(name).substr(file_.size() + 1));
}

Group Group::open_group(const std::string& name) const {
  if (!has(name)) throw InputError(where(name) + ": missing group");
  Handle g(H5Gopen2(id(), name.c_str(), H5P_DEFAULT));
  if (!g.valid()) throw InputError(where(name) + ": is not a group");
  return Group(std::move(g), file_, where(name).substr(file_.size() + 1));
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

Array<double> Group::read_doubles(const std::string& name, int expected_rank) const {
  return read_numeric<double>(*this, name, expected_rank, H5T_NATIVE_DOUBLE);
}
Array<std::int64_t> Group::read_int64(const std::string& name, int expected_rank) const {
  return read_numeric<std::int64_t>(*this, name, expected_rank, H5T_NATIVE_INT64);
}
Array<std::int32_t> Group::read_int32(const std::string& name, int expected_rank) const {
  return read_numeric<std::int32_t>(*this, name, expected_rank, H5T_NATIVE_INT32);
}

std::vector<std::string> Group::read_strings(const std::string& name) const {
  if (!has(name)) throw InputError(where(name) + ": missing dataset");
  Handle set(H5Dopen2(id(), name.c_str(), H5P_DEFAULT));
  if (!set.valid()) throw InputError(where(name) + ": cannot open dataset");
  return read_string_data(set.id(), false, where(name));
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
  auto v = read_string_data(attr.id(), true, where() + " attribute " + name);
  if (v.empty()) return std::string{};
  return v.front();
}

std::vector<std::string> Group::string_array_attribute(const std::string& name) const {
  if (!has_attribute(name)) return {};
  Handle attr(H5Aopen(id(), name.c_str(), H5P_DEFAULT));
  return read_string_data(attr.id(), true, where() + " attribute " + name);
}

std::vector<std::int64_t> Group::int_attribute(const std::string& name) const {
  if (!has_attribute(name)) return {};
  Handle attr(H5Aopen(id(), name.c_str(), H5P_DEFAULT));
  Handle type(H5Aget_type(attr.id()));
  if (H5Tget_class(type.id()) != H5T_INTEGER) throw InputError(where() + " attribute " + name + ": is not an integer");
  Handle space(H5Aget_space(attr.id()));
  const hssize_t count = H5Sget_simple_extent_npoints(space.id());
  std::vector<std::int64_t> out(static_cast<std::size_t>(std::max<hssize_t>(count, 0)));
  if (!out.empty() && H5Aread(attr.id(), H5T_NATIVE_INT64, out.data()) < 0) {
    throw InputError(where() + " attribute " + name + ": cannot read");
  }
  return out;
}

std::optional<double> Group::double_attribute(const std::string& name) const {
  if (!has_attribute(name)) return std::nullopt;
  Handle attr(H5Aopen(id(), name.c_str(), H5P_DEFAULT));
  double v = 0;
  if (H5Aread(attr.id(), H5T_NATIVE_DOUBLE, &v) < 0) throw InputError(where() + " attribute " + name + ": cannot read as a number");
  return v;
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

File File::create(const std::filesystem::path& path, const std::string& display_name) {
  silence_hdf5();
  Handle props(H5Pcreate(H5P_FILE_CREATE));
  H5Pset_obj_track_times(props.id(), false);
  hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, props.id(), H5P_DEFAULT);
  const std::string name = display_name.empty() ? path.filename().string() : display_name;
  if (f < 0) throw IoError(name + ": cannot create HDF5 file (" + hdf5_reason() + ")");
  return File(Handle(f), name);
}

File File::open(const std::filesystem::path& path) {
  silence_hdf5();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw IoError(path.string() + ": no such file");
  if (std::filesystem::is_directory(path, ec)) throw IoError(path.string() + ": is a folder, expected an HDF5 file");
  if (!std::ifstream(path, std::ios::binary)) throw IoError(path.string() + ": cannot be opened for reading");
  const htri_t is_hdf5 = H5Fis_hdf5(path.c_str());
  if (is_hdf5 <= 0) throw InputError(path.string() + ": is not an HDF5 file");
  hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) throw InputError(path.string() + ": cannot open as HDF5 (" + hdf5_reason() + "); is the file truncated or damaged?");
  return File(Handle(f), path.filename().string());
}

Group File::root() const {
  hid_t g = H5Gopen2(handle_.id(), "/", H5P_DEFAULT);
  if (g < 0) throw IoError(name_ + ": cannot open root group (" + hdf5_reason() + ")");
  return Group(Handle(g), name_, "/");
}

void File::close() {
  if (!handle_.valid()) return;
  if (H5Fflush(handle_.id(), H5F_SCOPE_GLOBAL) < 0) throw IoError(name_ + ": cannot flush (" + hdf5_reason() + ")");
  handle_ = Handle();  // closes the file; a write failure was already surfaced by the flush above
}

}  // namespace throng::h5
