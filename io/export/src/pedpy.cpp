#include "agent_poses.h"
#include "agent_ranges.h"
#include "block_stream.h"
#include "direct_write_driver.h"
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
#include <utility>
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

// A chunk's rows, gathered in a buffer aligned as the file driver's direct writes need (io/src/direct_write_driver.h).
// The file's chunks of at least its minimum start on its block boundaries (h5::File::create uses that driver), so
// a whole chunk written from here goes straight to the disk (O_DIRECT) instead of through the page cache: the
// kernel's copy into new page-cache pages was 38 % of an export's samples, and on this virtual machine new pages
// are a first touch of guest memory each (an export of 10,000 agents × 1,000 frames took 0.63-0.70 s, or 1.6-2.3 s
// when those pages were slow; 0.38-0.43 s so; docs/commands/export.md).
constexpr std::size_t chunk_bytes = chunk_rows * sizeof(Row);
static_assert(chunk_bytes % h5::detail::direct_write_block == 0 && chunk_bytes >= h5::detail::direct_write_minimum,
              "a whole chunk is whole blocks of a direct write, and large enough to go direct");
struct ChunkRows {
  h5::detail::AlignedBytes bytes = h5::detail::aligned_bytes(chunk_bytes);
  std::size_t count = 0;
  [[nodiscard]] Row* rows() noexcept { return reinterpret_cast<Row*>(bytes.get()); }
};

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
    // No fill value written: every chunk is written whole but the last, whose rows past the end are outside the
    // dataset. With one, libhdf5 takes each new chunk through its chunk cache to fill it first, whatever the
    // cache's size (H5D__chunk_cacheable): a buffer of its own, filled, copied into and written from, so the
    // chunk never went straight to the disk from the aligned rows below.
    H5Pset_fill_time(properties.id(), H5D_FILL_TIME_NEVER);
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

// The unit vector on the ground an agent faces: its forward axis projected and normalised ((1, 0) when it faces
// straight up or down), without trigonometry. The forward axis q x̂ = (1 − 2(y² + z²), 2(xy + wz), ·) of the unit
// quaternion, its ground length by a square root (both components are at most 1 in size, so std::hypot's guard
// against overflow, several times slower, buys nothing; 10 million rows per 10,000 agents × 1,000 frames).
std::pair<double, double> ground_facing(const Eigen::Quaterniond& q) {
  const double fx = 1.0 - 2.0 * (q.y() * q.y() + q.z() * q.z()), fy = 2.0 * (q.x() * q.y() + q.w() * q.z());
  const double length = std::sqrt(fx * fx + fy * fy);
  if (!(length > 1e-150)) return {1.0, 0.0};
  return {fx / length, fy / length};
}

// The rows, frame-major: blocks of frames made in parallel over agent ranges (each range's rows of a frame in
// its own part, joined in range order: the same rows whatever the thread count) while the writer thread appends
// the block before (HDF5 is called from that thread alone while rows are made). Whole chunks at a time: a
// partial chunk would be read back and rewritten.
void stream_rows(const CrowdMotion& m, const ExportOptions& options, RowWriter& trajectory) {
  const std::size_t N = m.agent_count(), T = m.frame_count(), chunk = chunk_rows;
  constexpr std::size_t ranges = detail::agent_ranges;
  const std::size_t per_block = std::clamp<std::size_t>(chunk / std::max<std::size_t>(N, 1), 1, std::max<std::size_t>(T, 1));
  struct Block {
    std::vector<std::vector<Row>> parts;  // [frame in block][range]
    std::size_t frames = 0;
  };
  ChunkRows carry;  // the chunk being gathered: rows short of a whole chunk wait here for the next block
  detail::BlockStream<Block> stream([&](Block& block) {
    for (std::size_t k = 0; k < block.frames * ranges; ++k) {
      const std::vector<Row>& part = block.parts[k];
      std::size_t done = 0;
      while (done < part.size()) {
        const std::size_t take = std::min(chunk - carry.count, part.size() - done);
        std::copy_n(part.data() + done, take, carry.rows() + carry.count);
        carry.count += take;
        done += take;
        if (carry.count == chunk) {
          trajectory.append(carry.rows(), chunk);
          carry.count = 0;
        }
      }
    }
  });
  detail::AgentPoses poses(m, options.pose);
  for (std::size_t t0 = 0; t0 < T; t0 += per_block) {
    const std::size_t count = std::min(per_block, T - t0);
    Block& block = stream.next();
    block.frames = count;
    if (block.parts.size() < count * ranges) block.parts.resize(count * ranges);
    detail::for_agent_ranges(N, [&](std::size_t r, std::size_t n0, std::size_t n1) {
      std::vector<Eigen::Quaterniond> facing(n1 - n0);
      for (std::size_t f = 0; f < count; ++f) {
        std::vector<Row>& part = block.parts[f * ranges + r];
        part.clear();
        const std::size_t t = t0 + f;
        poses.facings(t, n0, n1, facing.data());  // every agent's, so that an agent's frames are asked in order
        for (std::size_t n = n0; n < n1; ++n) {
          if (!m.present(t, n)) continue;
          const Eigen::Vector3d p = m.position(t, n);
          const auto [ox, oy] = ground_facing(facing[n - n0]);
          part.push_back({static_cast<std::int64_t>(t), m.ids[n], p.x(), p.y(), p.z(), ox, oy});
        }
      }
    });
    stream.submit();
  }
  stream.finish();
  trajectory.append(carry.rows(), carry.count);
}

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

    stream_rows(m, options, trajectory);
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
