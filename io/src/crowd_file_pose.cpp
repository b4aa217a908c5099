// Facing and action in the crowd file (layout in crowd_file.h):
//
//   /particles/trajectory/orientation  step/time hard links to position's; value float64[T][N][4], unit
//                                      quaternions (x, y, z, w) turning the body frame (forward +x, left +y,
//                                      up +z) into the world; NaN where absent. Attributes components =
//                                      ["x", "y", "z", "w"] and body_frame (text): an orientation element without
//                                      that components attribute is another program's and is not read.
//   /particles/trajectory/action       step/time hard links; value int32[T][N], an index into the name table,
//                                      −1 where absent. Attributes names and props (string[K], the table stored
//                                      once: entry k is what the agent does and what it carries, "" for nothing).
//
// Both are optional: files without them (older files, methods that fill neither) read with both empty.
#include "crowd_file_pose.h"

#include <throng/io/crowd_file_parts.h>

#include <throng/core/errors.h>

#include <cmath>
#include <string>
#include <vector>

namespace throng::detail {
namespace {

h5::Group create_element(const h5::Group& trajectory, const std::string& name) {
  h5::Group element = trajectory.create_group(name);
  element.link("step", "/particles/trajectory/position/step");
  element.link("time", "/particles/trajectory/position/time");
  return element;
}

std::string shape_text(const std::vector<std::uint64_t>& shape) {
  std::string s;
  for (const auto d : shape) s += "[" + std::to_string(d) + "]";
  return s;
}

void read_orientations(const h5::Group& trajectory, CrowdMotion& m, const ColumnName& name) {
  if (!trajectory.has_group("orientation")) return;
  const h5::Group element = trajectory.open_group("orientation");
  if (element.string_array_attribute("components") != quaternion_components) {
    if (!element.has_attribute("components")) return;  // another program's element, in its own convention
    throw InputError(element.where() + ": attribute components is not [\"x\", \"y\", \"z\", \"w\"]");
  }
  auto value = element.read_doubles("value", 3);
  const std::uint64_t T = m.frame_count(), N = m.agent_count();
  if (value.shape != std::vector<std::uint64_t>{T, N, 4}) {
    throw InputError(element.where("value") + ": has shape " + shape_text(value.shape) + ", expected [" +
                     std::to_string(T) + "][" + std::to_string(N) + "][4] (frames, agents, quaternion)");
  }
  m.orientations = std::move(value.values);
  for (std::uint64_t t = 0; t < T; ++t) {
    for (std::uint64_t n = 0; n < N; ++n) {
      if (!m.present(t, n)) continue;
      const Eigen::Vector4d q = m.orientation(t, n).coeffs();
      if (!q.allFinite() || std::abs(q.norm() - 1.0) > orientation_tolerance) {
        throw InputError(element.where("value") + ": " + name(t, n) + " at frame " + std::to_string(t) +
                         " is present but its orientation is not a finite unit quaternion (|q| = " +
                         std::to_string(q.norm()) + ")");
      }
    }
  }
}

void read_actions(const h5::Group& trajectory, CrowdMotion& m, const ColumnName& name) {
  if (!trajectory.has_group("action")) return;
  const h5::Group element = trajectory.open_group("action");
  const auto names = element.string_array_attribute("names");
  const auto props = element.string_array_attribute("props");
  if (names.empty()) throw InputError(element.where() + ": attribute names (the action table) is missing or empty");
  if (props.size() != names.size()) {
    throw InputError(element.where() + ": attribute props has " + std::to_string(props.size()) + " entries for " +
                     std::to_string(names.size()) + " names");
  }
  auto value = element.read_int32("value", 2);
  const std::uint64_t T = m.frame_count(), N = m.agent_count();
  if (value.shape != std::vector<std::uint64_t>{T, N}) {
    throw InputError(element.where("value") + ": has shape " + shape_text(value.shape) + ", expected [" +
                     std::to_string(T) + "][" + std::to_string(N) + "] (frames, agents)");
  }
  m.action_table.clear();
  for (std::size_t k = 0; k < names.size(); ++k) m.action_table.push_back({names[k], props[k]});
  m.actions = std::move(value.values);
  for (std::uint64_t t = 0; t < T; ++t) {
    for (std::uint64_t n = 0; n < N; ++n) {
      const std::int32_t a = m.action(t, n);
      if (m.present(t, n) && (a < 0 || static_cast<std::size_t>(a) >= names.size())) {
        throw InputError(element.where("value") + ": " + name(t, n) + " at frame " + std::to_string(t) +
                         " has action " + std::to_string(a) + ", expected 0.." + std::to_string(names.size() - 1) +
                         " (an index into attribute names)");
      }
    }
  }
}

}  // namespace

void write_pose_elements(const h5::Group& trajectory, const CrowdMotion& m, const h5::Layout& layout) {
  const std::uint64_t T = m.frame_count(), N = m.agent_count();
  if (!m.orientations.empty()) {
    std::vector<double> value(m.orientations);
    for (std::uint64_t t = 0; t < T; ++t) {
      for (std::uint64_t n = 0; n < N; ++n) {
        if (!m.present(t, n)) std::fill_n(value.begin() + static_cast<std::ptrdiff_t>((t * N + n) * 4), 4, absent);
      }
    }
    const h5::Group element = create_element(trajectory, "orientation");
    write_orientation_attributes(element);
    element.write("value", value, {T, N, 4}, layout);
  }
  if (!m.actions.empty()) {
    std::vector<std::int32_t> value(m.actions);
    for (std::uint64_t t = 0; t < T; ++t) {
      for (std::uint64_t n = 0; n < N; ++n) {
        if (!m.present(t, n)) value[t * N + n] = -1;
      }
    }
    const h5::Group element = create_element(trajectory, "action");
    write_action_attributes(element, m.action_table);
    element.write("value", value, {T, N}, layout);
  }
}

void read_pose_elements(const h5::Group& trajectory, CrowdMotion& m, const ColumnName& name) {
  const ColumnName by_column = [&m](std::uint64_t, std::uint64_t n) {
    return "agent " + std::to_string(m.ids[n]) + " (column " + std::to_string(n) + ")";
  };
  read_orientations(trajectory, m, name ? name : by_column);
  read_actions(trajectory, m, name ? name : by_column);
}

}  // namespace throng::detail
