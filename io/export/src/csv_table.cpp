#include "agent_poses.h"
#include "agent_ranges.h"
#include "output_file.h"
#include "text_numbers.h"

#include <throng/core/errors.h>
#include <throng/io/export/csv_table.h>

#include <cmath>
#include <string>
#include <variant>

namespace throng {
namespace {

constexpr std::size_t flush_bytes = 1 << 22;  // text per write: large writes, a few MB held at a time

// A text field as RFC 4180 writes it: quoted (quotes doubled) when it holds a comma, a quote or a line break.
void append_field(std::string& out, const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) {
    out += text;
    return;
  }
  out += '"';
  for (const char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
}

void write_rows(const CrowdFile& crowd, detail::OutputFile& file, const ExportOptions& options) {
  const CrowdMotion& m = crowd.motion;
  detail::AgentPoses poses(m, options.pose);
  const auto& table = poses.action_table();
  std::string text = "frame,time,id,x,y,z,qx,qy,qz,qw,heading_deg,action,prop,radius,species\n";
  constexpr double degrees = 180.0 / 3.14159265358979323846;
  for (std::size_t t = 0; t < m.frame_count(); ++t) {
    detail::for_agent_ranges<std::string>(m.agent_count(), [&](std::size_t n, std::string& row) {
      if (!poses.present(t, n)) return;
      const Eigen::Vector3d position = poses.position(t, n);
      const Eigen::Quaterniond facing = poses.facing(t, n);
      detail::append_number(row, static_cast<std::int64_t>(t));
      row += ',';
      detail::append_number(row, m.times[t]);
      row += ',';
      detail::append_number(row, m.ids[n]);
      for (int k = 0; k < 3; ++k) {
        row += ',';
        detail::append_number(row, position[k]);
      }
      for (int k = 0; k < 4; ++k) {
        row += ',';
        detail::append_number(row, facing.coeffs()[k]);
      }
      row += ',';
      detail::append_number(row, detail::heading(facing) * degrees);
      const ActionKind& action = table[static_cast<std::size_t>(poses.action(t, n))];
      row += ',';
      append_field(row, action.name);
      row += ',';
      append_field(row, action.prop);
      row += ',';
      detail::append_number(row, m.radii[n]);
      row += ',';
      detail::append_number(row, m.species[n]);
      row += '\n';
    }, [&](const std::string& rows) { text += rows; });
    if (text.size() > flush_bytes) {
      file.write(text);
      text.clear();
    }
  }
  file.write(text);
}

void write_obstacles(const CrowdFile& crowd, detail::OutputFile& file) {
  std::string text = "obstacle,name,kind,size,point,x,y,moving\n";
  const double t0 = crowd.motion.frame_count() ? crowd.motion.times.front() : 0.0;
  for (std::size_t k = 0; k < crowd.scene.obstacles.size(); ++k) {
    const Obstacle& ob = crowd.scene.obstacles[k];
    const Eigen::Isometry2d pose = pose_at(ob, t0);
    std::string kind;
    double size = 0;
    std::vector<Eigen::Vector2d> points;
    std::visit(
        [&](const auto& s) {
          using S = std::decay_t<decltype(s)>;
          if constexpr (std::is_same_v<S, Circle>) {
            kind = "circle", size = s.radius, points = {s.center};
          } else if constexpr (std::is_same_v<S, ConvexPolygon>) {
            kind = "polygon", points = s.vertices;
          } else {
            kind = "wall", size = s.thickness, points = {s.a, s.b};
          }
        },
        ob.shape);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Eigen::Vector2d p = pose * points[i];
      detail::append_number(text, static_cast<std::int64_t>(k));
      text += ',';
      append_field(text, ob.name);
      text += ',' + kind + ',';
      detail::append_number(text, size);
      text += ',';
      detail::append_number(text, static_cast<std::int64_t>(i));
      text += ',';
      detail::append_number(text, p.x());
      text += ',';
      detail::append_number(text, p.y());
      text += ob.is_moving() ? ",1\n" : ",0\n";
    }
  }
  file.write(text);
}

void export_csv_to(const CrowdFile& crowd, detail::OutputFile& rows, detail::OutputFile& obstacles, const ExportOptions& options) {
  write_rows(crowd, rows, options);
  write_obstacles(crowd, obstacles);
  obstacles.commit();
  rows.commit();
}

}  // namespace

std::filesystem::path csv_obstacles_path(const std::filesystem::path& output) {
  return output.parent_path() / (output.stem().string() + "_obstacles.csv");
}

void export_csv(const CrowdFile& crowd, const std::filesystem::path& output, const ExportOptions& options) {
  detail::OutputFile rows(output);
  detail::OutputFile obstacles(csv_obstacles_path(output));
  export_csv_to(crowd, rows, obstacles, options);
}

void export_csv(const std::filesystem::path& crowd, const std::filesystem::path& output, const ExportOptions& options) {
  check_distinct(crowd, output);
  check_distinct(crowd, csv_obstacles_path(output));
  detail::OutputFile rows(output);
  detail::OutputFile obstacles(csv_obstacles_path(output));
  export_csv_to(read_crowd_file(crowd), rows, obstacles, options);
}

}  // namespace throng
