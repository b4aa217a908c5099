#include "crowd_file_pose.h"
#include "crowd_file_slots.h"

#include <throng/io/crowd_file_parts.h>

#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>
#include <throng/io/checked_numbers.h>
#include <throng/io/crowd_file.h>

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <variant>

namespace throng {
namespace {

constexpr const char* trajectory_path = "particles/trajectory";

void write_time_element(const h5::Group& trajectory, const std::string& name, const std::vector<double>& values,
                        std::uint64_t T, std::uint64_t N, std::uint64_t width, bool first, const h5::Layout& layout) {
  h5::Group element = trajectory.create_group(name);
  if (first) {
    std::vector<std::int64_t> step(T);
    for (std::uint64_t t = 0; t < T; ++t) step[t] = static_cast<std::int64_t>(t);
    element.write("step", step, {T});
  } else {
    element.link("step", "/particles/trajectory/position/step");
    element.link("time", "/particles/trajectory/position/time");
  }
  std::vector<std::uint64_t> shape{T, N};
  if (width > 1) shape.push_back(width);
  element.write("value", values, shape, layout);
}

// The H5MD box: `boundary` per spatial axis (x, y, z) is "periodic" where the scene's region wraps (its x and y
// flags; z never: crowds are planar), else "none". With a periodic axis: `edges`, a time-dependent element
// sharing position's step and time, value float64[T][3][3] = diag(region width, region height, 0) in every frame
// (MDAnalysis reads box/edges/value[frame] as the three box vectors; a zero z side makes it report no box rather
// than an invented one), and `offset` float64[3], the region's lower corner (z 0). Written after position.
void write_box(const h5::Group& trajectory, const Scene& scene, std::uint64_t T) {
  const h5::Group box = trajectory.create_group("box");
  detail::write_box_attributes(box, scene);
  if (!scene.region || (!scene.region->periodic[0] && !scene.region->periodic[1])) return;
  const Region& r = *scene.region;
  const h5::Group edges = box.create_group("edges");
  edges.link("step", "/particles/trajectory/position/step");
  edges.link("time", "/particles/trajectory/position/time");
  const std::array<double, 9> frame = detail::box_edges_frame(r);
  std::vector<double> value;
  value.reserve(9 * T);
  for (std::uint64_t t = 0; t < T; ++t) value.insert(value.end(), frame.begin(), frame.end());
  edges.write("value", value, {T, 3, 3});
}

// What a file's box says about periodic axes: which of x and y wrap, and the box's lower corner and sides.
struct PeriodicBox {
  std::array<bool, 2> periodic{false, false};
  Eigen::Vector2d offset{0, 0};
  Eigen::Vector2d edges{0, 0};  // x and y sides (0 when a non-periodic side is not given)
};

// Reads the H5MD box when it marks x or y periodic (nullopt otherwise; a periodic z is ignored: crowds are
// planar). edges may be a dataset ([3] sides or a [3][3] matrix) or a time-dependent element (value [T][3] or
// [T][3][3]); it must be rectangular in x and y and the same in every frame. offset (optional, [3]) defaults to 0.
// InputError naming the attribute or dataset otherwise.
std::optional<PeriodicBox> read_periodic_box(const h5::Group& trajectory) {
  if (!trajectory.has_group("box")) return std::nullopt;
  const h5::Group box = trajectory.open_group("box");
  const std::vector<std::string> boundary = box.string_array_attribute("boundary");
  if (boundary.empty()) return std::nullopt;
  if (boundary.size() != 3) {
    throw InputError(box.where() + ": attribute boundary has " + std::to_string(boundary.size()) +
                     " entries, expected 3 (one per axis)");
  }
  PeriodicBox out;
  for (std::size_t a = 0; a < 3; ++a) {
    if (boundary[a] != "none" && boundary[a] != "periodic") {
      throw InputError(box.where() + ": attribute boundary[" + std::to_string(a) + "] is '" + boundary[a] +
                       "', expected \"none\" or \"periodic\"");
    }
    if (a < 2) out.periodic[a] = boundary[a] == "periodic";
  }
  if (!out.periodic[0] && !out.periodic[1]) return std::nullopt;

  // A row of sides per frame: [3] or [3][3] (a dataset), [T][3] or [T][3][3] (an element's value).
  const bool element = box.has_group("edges");
  if (!element && !box.has("edges")) {
    throw InputError(box.where("edges") + ": missing dataset; H5MD requires edges when an axis is periodic");
  }
  const std::string name = element ? "edges/value" : "edges";
  const auto edges = box.read_doubles(name);
  const std::size_t lead = element ? 1 : 0;  // the frame axis
  const auto& shape = edges.shape;
  const bool vector = shape.size() == lead + 1 && shape[lead] == 3;
  const bool matrix = shape.size() == lead + 2 && shape[lead] == 3 && shape[lead + 1] == 3;
  if (!vector && !matrix) {
    throw InputError(box.where(name) + ": expected " + (element ? "[frames][3] or [frames][3][3]" : "[3] or [3][3]") +
                     " (box sides or box vectors)");
  }
  const std::size_t per_frame = vector ? 3 : 9;
  if (edges.values.size() < per_frame) throw InputError(box.where(name) + ": holds no frame");
  for (std::size_t i = per_frame; i < edges.values.size(); ++i) {
    if (edges.values[i] != edges.values[i % per_frame]) {
      throw InputError(box.where(name) + ": the box changes between frames (not supported: a crowd's region is fixed)");
    }
  }
  const double* e = edges.values.data();
  if (matrix && (e[1] != 0 || e[2] != 0 || e[3] != 0 || e[5] != 0)) {
    throw InputError(box.where(name) + ": a triclinic box (x and y box vectors not along the axes) is not supported");
  }
  out.edges = matrix ? Eigen::Vector2d(e[0], e[4]) : Eigen::Vector2d(e[0], e[1]);
  for (int a = 0; a < 2; ++a) {
    if (out.periodic[static_cast<std::size_t>(a)] && !(std::isfinite(out.edges[a]) && out.edges[a] > 0)) {
      throw InputError(box.where(name) + ": periodic axis " + std::string(1, "xy"[a]) + " has side " +
                       std::to_string(out.edges[a]) + ", expected a finite length > 0");
    }
  }
  if (box.has("offset")) {
    const auto offset = box.read_doubles("offset", 1);
    if (offset.values.size() != 3 || !std::isfinite(offset.values[0]) || !std::isfinite(offset.values[1])) {
      throw InputError(box.where("offset") + ": expected 3 finite numbers (the box's lower corner)");
    }
    out.offset = {offset.values[0], offset.values[1]};
  }
  return out;
}

// The scene's region from the box (files whose region is not stored under /parameters/throng: other programs'),
// or a check that both agree. Non-periodic sides the box does not give span the agents' positions; times span
// the frames.
void apply_periodic_box(const PeriodicBox& box, const h5::Group& trajectory, const CrowdMotion& m, Scene& scene) {
  if (scene.region) {
    const Region& r = *scene.region;
    for (std::size_t a = 0; a < 2; ++a) {
      const auto i = static_cast<Eigen::Index>(a);
      const bool agrees = r.periodic[a] == box.periodic[a] &&
                          (!box.periodic[a] || (r.min[i] == box.offset[i] && r.max[i] - r.min[i] == box.edges[i]));
      if (!agrees) {
        throw InputError(trajectory.where("box") + ": axis " + std::string(1, "xy"[a]) +
                         " disagrees with /parameters/throng/scene/region (periodic flag, lower corner or side)");
      }
    }
    return;
  }
  Region r;
  Eigen::AlignedBox2d extent;
  for (std::size_t t = 0; t < m.frame_count(); ++t) {
    for (std::size_t n = 0; n < m.agent_count(); ++n) {
      if (m.present(t, n)) extent.extend(Eigen::Vector2d(m.position(t, n).head<2>()));
    }
  }
  for (Eigen::Index a = 0; a < 2; ++a) {
    if (box.periodic[static_cast<std::size_t>(a)] || box.edges[a] > 0 || extent.isEmpty()) {
      r.min[a] = box.offset[a];
      r.max[a] = box.offset[a] + (box.edges[a] > 0 ? box.edges[a] : 1.0);
    } else {
      r.min[a] = extent.min()[a];
      r.max[a] = extent.max()[a] > extent.min()[a] ? extent.max()[a] : extent.min()[a] + 1.0;
    }
  }
  r.t0 = m.frame_count() ? m.times.front() : 0.0;
  r.t1 = m.frame_count() > 1 ? m.times.back() : r.t0 + 1.0;
  r.periodic = {box.periodic[0], box.periodic[1], false};
  scene.region = r;
}

// The crowd's arrays, from the shapes alone, against what the file's budget has left: positions (24 bytes per
// frame and agent), per-frame ids (8) and velocities (24) when present, per-agent ids, radii and species.
// InputError (exit 3) with the estimate before anything large is read; the reads then charge what they read.
void check_crowd_memory(const h5::Group& trajectory, std::uint64_t T, std::uint64_t N) {
  std::uint64_t per_entry = 24;
  if (trajectory.has("id/value")) per_entry += 8;
  if (trajectory.has("velocity/value")) per_entry += 24;
  const auto entries = checked_product(T, N);
  const auto bytes = entries ? checked_product(*entries, per_entry) : std::nullopt;
  const auto total = bytes ? checked_sum(*bytes, checked_product(N, 20).value_or(UINT64_MAX)) : std::nullopt;
  trajectory.budget().require(total.value_or(UINT64_MAX), trajectory.where("position/value"),
                              std::to_string(T) + " frames × " + std::to_string(N) + " agents × " + std::to_string(per_entry) +
                                  " bytes");
}

// id/value [T][N] when the file has it (empty otherwise): InputError for another shape.
std::vector<std::int64_t> read_per_frame_ids(const h5::Group& trajectory, std::uint64_t T, std::uint64_t N) {
  if (!trajectory.has("id/value")) return {};
  auto id = trajectory.read_int64("id/value", 2);
  if (id.shape[0] != T || id.shape[1] != N) {
    throw InputError(trajectory.where("id/value") + ": has shape [" + std::to_string(id.shape[0]) + "][" +
                     std::to_string(id.shape[1]) + "], expected [" + std::to_string(T) + "][" + std::to_string(N) + "]");
  }
  return std::move(id.values);
}

// The classic layout, one agent per column: per-agent ids, radii, species and presence, then velocities and the
// pose elements. `m` holds the times and positions [T][N][3] (`shape`) as read; `per_frame_id` is id/value
// (empty when the file has none).
void read_agent_columns(const h5::Group& root, const h5::Group& trajectory, const std::vector<std::uint64_t>& shape,
                        const std::vector<std::int64_t>& per_frame_id, CrowdMotion& m) {
  const std::uint64_t T = shape[0], N = shape[1];
  // Per-agent ids: from /parameters/throng/agents/id when present, else from the first present frame of id/value.
  m.ids.assign(N, -1);
  const bool ours = root.has("parameters/throng/agents");
  if (ours) {
    const h5::Group agents = root.open_group("parameters/throng/agents");
    auto ids = agents.read_int64("id", 1);
    auto radius = agents.read_doubles("radius", 1);
    if (ids.shape[0] != N) throw InputError(agents.where("id") + ": has " + std::to_string(ids.shape[0]) + " entries for " + std::to_string(N) + " agents");
    if (radius.shape[0] != N) throw InputError(agents.where("radius") + ": has " + std::to_string(radius.shape[0]) + " entries for " + std::to_string(N) + " agents");
    m.ids = std::move(ids.values);
    m.radii = std::move(radius.values);
  } else {
    m.radii.assign(N, 0.25);
    for (std::uint64_t n = 0; n < N; ++n) {
      m.ids[n] = static_cast<std::int64_t>(n);
      for (std::uint64_t t = 0; t < T && !per_frame_id.empty(); ++t) {
        if (per_frame_id[t * N + n] >= 0) {
          m.ids[n] = per_frame_id[t * N + n];
          break;
        }
      }
    }
  }

  // Presence: id/value ≥ 0 marks a present agent; without id/value, an agent is absent where its position is
  // NaN (all three coordinates), as we write it. A present agent's position must be finite: an infinity is never
  // "absent". Absent entries become NaN.
  for (std::uint64_t t = 0; t < T; ++t) {
    for (std::uint64_t n = 0; n < N; ++n) {
      double* p = m.positions.data() + (t * N + n) * 3;
      const bool finite = std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
      bool present = !(std::isnan(p[0]) && std::isnan(p[1]) && std::isnan(p[2]));
      if (!per_frame_id.empty()) {
        const std::int64_t id = per_frame_id[t * N + n];
        present = id >= 0;
        if (present && id != m.ids[n]) {
          throw InputError(trajectory.where("id/value") + ": column " + std::to_string(n) + " holds id " + std::to_string(id) +
                           " at frame " + std::to_string(t) + " but agent id " + std::to_string(m.ids[n]) + " elsewhere");
        }
      }
      if (present && !finite) {
        const bool nan = std::isnan(p[0]) || std::isnan(p[1]) || std::isnan(p[2]);
        throw InputError(trajectory.where("position/value") + ": " + (nan ? "NaN" : "infinite") +
                         " position for present agent " + std::to_string(m.ids[n]) + " (column " + std::to_string(n) +
                         ") at frame " + std::to_string(t) +
                         (per_frame_id.empty() ? " (without id/value, only NaN in all three coordinates means absent)"
                                               : ""));
      }
      if (!present) p[0] = p[1] = p[2] = absent;
    }
  }

  if (trajectory.has("species")) {
    auto species = trajectory.read_int32("species", 1);
    if (species.shape[0] != N) throw InputError(trajectory.where("species") + ": has " + std::to_string(species.shape[0]) + " entries for " + std::to_string(N) + " agents");
    m.species = std::move(species.values);
  } else {
    m.species.assign(N, 0);
  }
  if (trajectory.has("velocity/value")) {
    auto velocity = trajectory.read_doubles("velocity/value", 3);
    if (velocity.shape != shape) throw InputError(trajectory.where("velocity/value") + ": shape differs from position/value");
    m.velocities = std::move(velocity.values);
  }
  detail::read_pose_elements(trajectory, m);
}

// /connectivity/formation_edges of a file with N agent columns (none when absent).
std::vector<std::array<std::int32_t, 2>> read_formation_edges(const h5::Group& root, std::uint64_t N) {
  std::vector<std::array<std::int32_t, 2>> out;
  if (root.has("connectivity/formation_edges")) {
    const auto edges = root.open_group("connectivity").read_int32("formation_edges", 2);
    if (edges.shape[1] != 2) throw InputError(root.where("connectivity/formation_edges") + ": expected shape [edges][2]");
    for (std::size_t e = 0; e < edges.shape[0]; ++e) {
      const std::int32_t a = edges.values[2 * e], b = edges.values[2 * e + 1];
      if (a < 0 || b < 0 || static_cast<std::uint64_t>(a) >= N || static_cast<std::uint64_t>(b) >= N) {
        throw InputError(root.where("connectivity/formation_edges") + ": edge " + std::to_string(e) + " names an agent out of range");
      }
      out.push_back({a, b});
    }
  }
  return out;
}

}  // namespace

void write_crowd_file(const std::filesystem::path& path, const CrowdFile& file, const ExtraWriter& extra, CrowdStorage storage) {
  const h5::Layout per_frame{storage == CrowdStorage::compressed, 0};
  const CrowdMotion& m = file.motion;
  m.validate("output " + path.filename().string());
  file.scene.validate("output " + path.filename().string());
  const std::uint64_t T = m.frame_count(), N = m.agent_count();
  for (const auto& e : file.formation_edges) {
    if (e[0] < 0 || e[1] < 0 || static_cast<std::uint64_t>(e[0]) >= N || static_cast<std::uint64_t>(e[1]) >= N) {
      throw InputError("output " + path.filename().string() + ": formation edge (" + std::to_string(e[0]) + ", " +
                       std::to_string(e[1]) + ") names an agent outside 0.." + std::to_string(N) + "-1");
    }
  }

  AtomicOutput output(path);
  {
    h5::File f = h5::File::create(output.descriptor_path(), path.filename().string());
    {
      const h5::Group root = f.root();
      const h5::Group parameters = detail::write_crowd_header(root, file.provenance, file.scene);

      const h5::Group trajectory = root.create_group("particles").create_group("trajectory");
      write_time_element(trajectory, "position", m.positions, T, N, 3, true, per_frame);
      const h5::Group position = trajectory.open_group("position");
      position.write("time", m.times, {T});
      position.set_attribute_on("time", "unit", "s");
      write_box(trajectory, file.scene, T);
      if (!m.velocities.empty()) write_time_element(trajectory, "velocity", m.velocities, T, N, 3, false, per_frame);
      detail::write_pose_elements(trajectory, m, per_frame);

      std::vector<std::int64_t> per_frame_id(T * N);
      for (std::uint64_t t = 0; t < T; ++t) {
        for (std::uint64_t n = 0; n < N; ++n) per_frame_id[t * N + n] = m.present(t, n) ? m.ids[n] : -1;
      }
      h5::Group id = trajectory.create_group("id");
      id.link("step", "/particles/trajectory/position/step");
      id.link("time", "/particles/trajectory/position/time");
      id.write("value", per_frame_id, {T, N}, per_frame);
      trajectory.write("species", m.species, {N});

      detail::write_agent_parts(root, parameters, m, file.formation_edges);
      if (extra) extra(parameters);
    }
    f.close();
  }
  output.commit();
}

h5::Group open_throng_parameters(const h5::File& file) { return file.root().open_group("parameters/throng"); }

CrowdFile read_crowd_file(const std::filesystem::path& path, const ReadLimits& limits) {
  return read_crowd_file(h5::File::open(path, limits));
}

CrowdFile read_crowd_file(const h5::File& f) {
  const h5::Group root = f.root();
  CrowdFile out;
  CrowdMotion& m = out.motion;

  detail::check_format_version(root);
  if (!root.has("h5md")) throw InputError(root.where("h5md") + ": missing group; not an H5MD crowd file");
  const h5::Group trajectory = root.open_group(trajectory_path);

  const std::vector<std::uint64_t> shape = trajectory.shape("position/value");
  if (shape.size() != 3) {
    throw InputError(trajectory.where("position/value") + ": has rank " + std::to_string(shape.size()) + ", expected 3");
  }
  if (shape[2] != 3) {
    throw InputError(trajectory.where("position/value") + ": has shape [" + std::to_string(shape[0]) + "][" +
                     std::to_string(shape[1]) + "][" + std::to_string(shape[2]) + "], expected [frames][agents][3]");
  }
  const std::uint64_t T = shape[0], N = shape[1];
  check_crowd_memory(trajectory, T, N);
  auto position = trajectory.read_doubles("position/value", 3);
  auto time = trajectory.read_doubles("position/time", 1);
  if (time.shape[0] != T) {
    throw InputError(trajectory.where("position/time") + ": has " + std::to_string(time.shape[0]) + " entries for " +
                     std::to_string(T) + " frames of position/value");
  }
  m.times = std::move(time.values);
  m.positions = std::move(position.values);
  for (std::uint64_t t = 0; t < T; ++t) {
    if (!std::isfinite(m.times[t])) throw InputError(trajectory.where("position/time") + ": frame " + std::to_string(t) + " has a non-finite time");
    if (t > 0 && !(m.times[t] > m.times[t - 1])) {
      throw InputError(trajectory.where("position/time") + ": times not increasing at frame " + std::to_string(t) + " (" +
                       std::to_string(m.times[t - 1]) + " then " + std::to_string(m.times[t]) + ")");
    }
  }

  // A column is an agent (the classic layout) unless id/value reuses it for several agents (crowd_file.h).
  std::vector<std::int64_t> per_frame_id = read_per_frame_ids(trajectory, T, N);
  if (detail::has_reused_slots(per_frame_id, N)) {
    if (root.has("connectivity/formation_edges")) {
      throw InputError(root.where("connectivity/formation_edges") + ": formation edges name columns, and this file's "
                       "columns are reused slots (id/value holds several agents in one column); not supported");
    }
    m = detail::read_slotted_motion(root, trajectory, std::move(m), std::move(per_frame_id), N);
  } else {
    read_agent_columns(root, trajectory, shape, per_frame_id, m);
    out.formation_edges = read_formation_edges(root, N);
  }

  if (root.has("parameters/throng")) {
    const h5::Group parameters = root.open_group("parameters/throng");
    Provenance& p = out.provenance;
    p.program_version = parameters.string_attribute("program_version").value_or("");
    p.command_line = parameters.string_attribute("command_line").value_or("");
    p.options = parameters.string_attribute("options").value_or("");
    p.seed = parameters.unsigned_attribute("seed").value_or(0);
    p.inputs = parameters.string_array_attribute("inputs");
    p.credits = parameters.string_array_attribute("credits");
    out.scene = detail::read_scene(parameters);
  }
  if (const auto box = read_periodic_box(trajectory)) {
    apply_periodic_box(*box, trajectory, m, out.scene);
    out.scene.validate(trajectory.where("box"));
  }
  m.validate(root.file());
  return out;
}

}  // namespace throng
