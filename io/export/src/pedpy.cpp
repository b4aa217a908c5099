#include "agent_poses.h"
#include "agent_ranges.h"
#include "frame_rate.h"
#include "walkable_area.h"

#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>
#include <throng/io/export/pedpy.h>
#include <throng/io/hdf5.h>

#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace throng {
namespace {

// One /trajectory row, laid out as the HDF5 compound type below describes it.
struct Row {
  std::int64_t frame;
  std::int64_t id;
  double x, y, z, ox, oy;
};

constexpr hsize_t chunk_rows = 1 << 16;  // rows per chunk and per write (3.5 MiB)

h5::Handle row_type() {
  h5::Handle type(H5Tcreate(H5T_COMPOUND, sizeof(Row)));
  H5Tinsert(type.id(), "frame", HOFFSET(Row, frame), H5T_STD_I64LE);
  H5Tinsert(type.id(), "id", HOFFSET(Row, id), H5T_STD_I64LE);
  H5Tinsert(type.id(), "x", HOFFSET(Row, x), H5T_IEEE_F64LE);
  H5Tinsert(type.id(), "y", HOFFSET(Row, y), H5T_IEEE_F64LE);
  H5Tinsert(type.id(), "z", HOFFSET(Row, z), H5T_IEEE_F64LE);
  H5Tinsert(type.id(), "ox", HOFFSET(Row, ox), H5T_IEEE_F64LE);
  H5Tinsert(type.id(), "oy", HOFFSET(Row, oy), H5T_IEEE_F64LE);
  return type;
}

// Appends rows to an extendible 1-D dataset.
class RowWriter {
 public:
  RowWriter(const h5::Group& root, const std::string& where) : where_(where), type_(row_type()) {
    const hsize_t zero = 0, unlimited = H5S_UNLIMITED;
    h5::Handle space(H5Screate_simple(1, &zero, &unlimited));
    h5::Handle properties(H5Pcreate(H5P_DATASET_CREATE));
    H5Pset_chunk(properties.id(), 1, &chunk_rows);
    H5Pset_obj_track_times(properties.id(), 0);
    dataset_ = h5::Handle(H5Dcreate2(root.id(), "trajectory", type_.id(), space.id(), H5P_DEFAULT, properties.id(), H5P_DEFAULT));
    if (!dataset_.valid()) throw IoError(where_ + ": cannot create dataset /trajectory");
  }

  void append(const Row* rows, std::size_t row_count) {
    if (row_count == 0) return;
    const hsize_t count = row_count, size = written_ + count;
    if (H5Dset_extent(dataset_.id(), &size) < 0) throw IoError(where_ + ": cannot extend /trajectory");
    h5::Handle file_space(H5Dget_space(dataset_.id()));
    H5Sselect_hyperslab(file_space.id(), H5S_SELECT_SET, &written_, nullptr, &count, nullptr);
    h5::Handle memory_space(H5Screate_simple(1, &count, nullptr));
    if (H5Dwrite(dataset_.id(), type_.id(), memory_space.id(), file_space.id(), H5P_DEFAULT, rows) < 0) {
      throw IoError(where_ + ": write of /trajectory failed (is the disk full?)");
    }
    written_ = size;
  }

  void set_attribute(const std::string& name, double value) const {
    h5::Handle space(H5Screate(H5S_SCALAR));
    h5::Handle attribute(H5Acreate2(dataset_.id(), name.c_str(), H5T_IEEE_F64LE, space.id(), H5P_DEFAULT, H5P_DEFAULT));
    if (!attribute.valid() || H5Awrite(attribute.id(), H5T_NATIVE_DOUBLE, &value) < 0) {
      throw IoError(where_ + ": cannot write attribute " + name + " of /trajectory");
    }
  }

 private:
  std::string where_;
  h5::Handle type_;
  h5::Handle dataset_;
  hsize_t written_ = 0;
};

void write_pedpy(const CrowdFile& crowd, const std::filesystem::path& output, AtomicOutput& atomic,
                 const PedpyOptions& pedpy, const ExportOptions& options) {
  const CrowdMotion& m = crowd.motion;
  const std::string name = output.filename().string();
  const std::optional<double> fps = detail::uniform_frame_rate(m.times);
  if (!fps) {
    throw InputError(name + ": PedPy counts frames at a constant rate, but this crowd's " + std::to_string(m.frame_count()) +
                     " frames are " + (m.frame_count() < 2 ? "too few to have one" : "not evenly spaced (resample it first)"));
  }
  using WalkableArea = PedpyOptions::WalkableArea;
  std::string wkt;
  const bool has_static = std::any_of(crowd.scene.obstacles.begin(), crowd.scene.obstacles.end(), [](const Obstacle& o) { return !o.is_moving(); });
  if (pedpy.walkable_area == WalkableArea::required || (pedpy.walkable_area == WalkableArea::if_obstacles && has_static)) {
    wkt = detail::walkable_area_wkt(crowd);
  }

  h5::File file = h5::File::create(atomic.temporary(), name);
  {
    const h5::Group root = file.root();
    RowWriter trajectory(root, name);
    trajectory.set_attribute("fps", *fps);
    root.set_attribute_on("trajectory", "frame", "Frame this row belongs to, counted from 0 at fps");
    root.set_attribute_on("trajectory", "id", "Id of the agent");
    root.set_attribute_on("trajectory", "x", "X position of the agent [m], x/y the ground plane");
    root.set_attribute_on("trajectory", "y", "Y position of the agent [m], x/y the ground plane");
    root.set_attribute_on("trajectory", "z", "Z position of the agent [m], z up");
    root.set_attribute_on("trajectory", "ox", "X component of the unit vector the agent faces on the ground");
    root.set_attribute_on("trajectory", "oy", "Y component of the unit vector the agent faces on the ground");
    if (!wkt.empty()) root.set_attribute("wkt_geometry", wkt);
    root.set_attribute("producer", std::string("throng"));

    detail::AgentPoses poses(m, options.pose);
    std::vector<Row> rows;
    rows.reserve(chunk_rows);
    for (std::size_t t = 0; t < m.frame_count(); ++t) {
      detail::for_agent_ranges<std::vector<Row>>(m.agent_count(), [&](std::size_t n, std::vector<Row>& part) {
        if (!m.present(t, n)) return;
        const Eigen::Vector3d p = m.position(t, n);
        const double h = detail::heading(poses.facing(t, n));
        part.push_back({static_cast<std::int64_t>(t), m.ids[n], p.x(), p.y(), p.z(), std::cos(h), std::sin(h)});
      }, [&](const std::vector<Row>& part) { rows.insert(rows.end(), part.begin(), part.end()); });
      // Whole chunks at a time (a partial chunk would be read back and rewritten).
      std::size_t done = 0;
      for (; rows.size() - done >= chunk_rows; done += chunk_rows) trajectory.append(rows.data() + done, chunk_rows);
      rows.erase(rows.begin(), rows.begin() + static_cast<std::ptrdiff_t>(done));
    }
    trajectory.append(rows.data(), rows.size());
  }
  file.close();
}

}  // namespace

void export_pedpy(const CrowdFile& crowd, const std::filesystem::path& output, const PedpyOptions& pedpy, const ExportOptions& options) {
  AtomicOutput atomic(output);
  write_pedpy(crowd, output, atomic, pedpy, options);
  atomic.commit();
}

void export_pedpy(const std::filesystem::path& crowd, const std::filesystem::path& output, const PedpyOptions& pedpy,
                  const ExportOptions& options) {
  check_distinct(crowd, output);
  AtomicOutput atomic(output);
  write_pedpy(read_crowd_file(crowd), output, atomic, pedpy, options);
  atomic.commit();
}

}  // namespace throng
