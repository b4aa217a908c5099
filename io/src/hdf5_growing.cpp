#include <throng/core/errors.h>
#include <throng/io/hdf5_growing.h>

#include "hdf5_detail.h"

#include <cstdint>

namespace throng::h5 {

using namespace detail;

namespace {

hid_t memory_type(Number type) {
  switch (type) {
    case Number::float64: return H5T_NATIVE_DOUBLE;
    case Number::int64: return H5T_NATIVE_INT64;
    case Number::int32: return H5T_NATIVE_INT32;
  }
  return H5T_NATIVE_DOUBLE;
}

hid_t file_type(Number type) {
  switch (type) {
    case Number::float64: return H5T_IEEE_F64LE;
    case Number::int64: return H5T_STD_I64LE;
    case Number::int32: return H5T_STD_I32LE;
  }
  return H5T_IEEE_F64LE;
}

std::vector<hsize_t> dims(const std::vector<std::uint64_t>& v) { return {v.begin(), v.end()}; }

}  // namespace

GrowingDataset GrowingDataset::create(const Group& group, const std::string& name, Number type,
                                      const std::vector<std::uint64_t>& shape, const std::vector<std::uint64_t>& chunk,
                                      double fill) {
  const std::string where = group.where(name);
  if (shape.empty() || chunk.size() != shape.size()) throw std::logic_error(where + ": growing dataset needs a chunk per axis");
  const std::vector<hsize_t> unlimited(shape.size(), H5S_UNLIMITED);
  const std::vector<hsize_t> current = dims(shape);
  const Handle space = checked(H5Screate_simple(static_cast<int>(shape.size()), current.data(), unlimited.data()),
                               "cannot make the dataspace of " + where);
  const Handle props = checked(H5Pcreate(H5P_DATASET_CREATE), "cannot make the properties of " + where);
  H5Pset_obj_track_times(props.id(), false);
  const std::vector<hsize_t> sides = dims(chunk);
  check(H5Pset_chunk(props.id(), static_cast<int>(sides.size()), sides.data()), "cannot chunk " + where);
  check(H5Pset_shuffle(props.id()), "cannot set the shuffle filter of " + where);
  check(H5Pset_deflate(props.id(), deflate_level), "cannot set deflate on " + where);
  const std::int64_t fill64 = static_cast<std::int64_t>(fill);
  const std::int32_t fill32 = static_cast<std::int32_t>(fill);
  const void* fill_value = type == Number::float64 ? static_cast<const void*>(&fill)
                           : type == Number::int64 ? static_cast<const void*>(&fill64)
                                                   : static_cast<const void*>(&fill32);
  check(H5Pset_fill_value(props.id(), memory_type(type), fill_value), "cannot set the fill value of " + where);
  Handle set = checked(H5Dcreate2(group.id(), name.c_str(), file_type(type), space.id(), H5P_DEFAULT, props.id(), H5P_DEFAULT),
                       "cannot create dataset " + where);
  return GrowingDataset(std::move(set), type, where);
}

GrowingDataset GrowingDataset::open(const Group& group, const std::string& name, Number type, std::size_t rank) {
  const std::string where = group.where(name);
  if (!group.has(name)) throw InputError(where + ": missing dataset");
  Handle set(H5Dopen2(group.id(), name.c_str(), H5P_DEFAULT));
  if (!set.valid()) throw InputError(where + ": cannot open (" + hdf5_reason() + ")");
  const Handle stored(H5Dget_type(set.id()));
  const Handle space(H5Dget_space(set.id()));
  if (!stored.valid() || !space.valid() || H5Tequal(stored.id(), file_type(type)) <= 0 ||
      H5Sget_simple_extent_ndims(space.id()) != static_cast<int>(rank)) {
    throw InputError(where + ": not the dataset a throng stream writes (type or rank differs)");
  }
  return GrowingDataset(std::move(set), type, where);
}

std::vector<std::uint64_t> GrowingDataset::shape() const {
  const Handle space = checked(H5Dget_space(set_.id()), "cannot read the shape of " + where_);
  const int rank = H5Sget_simple_extent_ndims(space.id());
  std::vector<hsize_t> d(static_cast<std::size_t>(std::max(rank, 0)));
  H5Sget_simple_extent_dims(space.id(), d.data(), nullptr);
  return {d.begin(), d.end()};
}

void GrowingDataset::resize(const std::vector<std::uint64_t>& shape) {
  const std::vector<hsize_t> d = dims(shape);
  check(H5Dset_extent(set_.id(), d.data()), "cannot resize " + where_);
}

void GrowingDataset::write(const std::vector<std::uint64_t>& offset, const std::vector<std::uint64_t>& count, const void* values) {
  std::uint64_t elements = 1;
  for (const std::uint64_t c : count) elements *= c;
  if (elements == 0) return;
  const Handle file_space = checked(H5Dget_space(set_.id()), "cannot read the shape of " + where_);
  const std::vector<hsize_t> start = dims(offset), block = dims(count);
  check(H5Sselect_hyperslab(file_space.id(), H5S_SELECT_SET, start.data(), nullptr, block.data(), nullptr),
        "cannot select a block of " + where_);
  const Handle memory_space = simple_space(count);
  check(H5Dwrite(set_.id(), memory_type(type_), memory_space.id(), file_space.id(), H5P_DEFAULT, values), "cannot write " + where_);
}

void GrowingDataset::append(std::uint64_t rows, const void* values) {
  std::vector<std::uint64_t> extent = shape();
  std::vector<std::uint64_t> offset(extent.size(), 0), count = extent;
  offset[0] = extent[0];
  count[0] = rows;
  extent[0] += rows;
  resize(extent);
  write(offset, count, values);
}

}  // namespace throng::h5
