#include "agent_poses.h"
#include "frame_text.h"
#include "output_file.h"
#include "text_numbers.h"

#include <throng/core/errors.h>
#include <throng/io/export/csv_table.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <variant>

namespace throng {
namespace {

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

// The parts of a row that do not change from frame to frame or from agent to agent, formatted once: per agent
// "id," and ",radius,species\n", per action ",name,prop", per frame "frame,time,".
struct RowConstants {
  std::vector<std::string> agent_head, agent_tail, action;
  std::size_t longest = 0;  // the longest agent and action parts together

  RowConstants(const CrowdMotion& m, const std::vector<ActionKind>& table) {
    const std::size_t N = m.agent_count();
    agent_head.resize(N);
    agent_tail.resize(N);
    std::size_t agent_longest = 0, action_longest = 0;
    for (std::size_t n = 0; n < N; ++n) {
      detail::append_number(agent_head[n], m.ids[n]);
      agent_head[n] += ',';
      agent_tail[n] += ',';
      detail::append_number(agent_tail[n], m.radii[n]);
      agent_tail[n] += ',';
      detail::append_number(agent_tail[n], m.species[n]);
      agent_tail[n] += '\n';
      agent_longest = std::max(agent_longest, agent_head[n].size() + agent_tail[n].size());
    }
    for (const ActionKind& a : table) {
      std::string& text = action.emplace_back(",");
      append_field(text, a.name);
      text += ',';
      append_field(text, a.prop);
      action_longest = std::max(action_longest, text.size());
    }
    longest = agent_longest + action_longest;
  }
};

void write_rows(const CrowdFile& crowd, detail::OutputFile& file, const ExportOptions& options) {
  const CrowdMotion& m = crowd.motion;
  detail::AgentPoses poses(m, options.pose);
  const RowConstants constants(m, poses.action_table());
  file.write("frame,time,id,x,y,z,qx,qy,qz,qw,heading_deg,action,prop,radius,species\n");
  constexpr double degrees = 180.0 / 3.14159265358979323846;
  std::vector<std::string> frame_head(m.frame_count());
  for (std::size_t t = 0; t < m.frame_count(); ++t) {
    detail::append_number(frame_head[t], static_cast<std::int64_t>(t));
    frame_head[t] += ',';
    detail::append_number(frame_head[t], m.times[t]);
    frame_head[t] += ',';
  }
  // Room for one row: the constant parts, 8 numbers and their commas.
  const std::size_t row_room = constants.longest + 64 + 8 * (detail::max_number_chars + 1);
  // A frame's facings a range of agents at a time (AgentPoses::facings), each range into its own agents' slots.
  std::vector<Eigen::Quaterniond> facings(m.agent_count());
  detail::stream_frame_text(
      file, m.frame_count(), m.agent_count(), {.bytes_per_agent = 120}, [](std::size_t, detail::TextBuffer&) {},
      [&](std::size_t t, std::size_t n, detail::TextBuffer& out) {
        if (!poses.present(t, n)) return;
        const Eigen::Vector3d position = poses.position(t, n);
        const Eigen::Quaterniond& facing = facings[n];
        const std::string& action = constants.action[static_cast<std::size_t>(poses.action(t, n))];
        char* p = out.room(row_room + frame_head[t].size());
        p = detail::put_text(p, frame_head[t]);
        p = detail::put_text(p, constants.agent_head[n]);
        p = detail::put_number(p, position.x());
        *p++ = ',';
        p = detail::put_number(p, position.y());
        *p++ = ',';
        p = detail::put_number(p, position.z());
        for (int k = 0; k < 4; ++k) {
          *p++ = ',';
          p = detail::put_number(p, facing.coeffs()[k]);
        }
        *p++ = ',';
        p = detail::put_number(p, detail::heading(facing) * degrees);
        p = detail::put_text(p, action);
        p = detail::put_text(p, constants.agent_tail[n]);
        out.advance(p);
      },
      [](std::size_t, detail::TextBuffer&) {},
      [&](std::size_t t, std::size_t n0, std::size_t n1) { poses.facings(t, n0, n1, facings.data() + n0); });
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
