// Writes the sketch scenes of scenes.h as job files: configs/sketch-paper.yaml and configs/sketch-large.yaml.
// The configs are data generated from the fixtures (never edited by hand), and the CLI test
// "the sketch configs are the test scenes" checks that they still read back to them.
//
//   cmake --build build/<dir> --target sketch_make_configs && build/<dir>/tests/sketch/sketch_make_configs configs
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <string>
#include <variant>

#include "scenes.h"

using namespace throng;
using namespace throng::sketch;

namespace {

// Shortest text that reads back to the same double.
std::string num(double v) {
  char buffer[64];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;
  return std::string(buffer, end);
}

std::string point(const Eigen::Vector2d& p) { return "[" + num(p.x()) + ", " + num(p.y()) + "]"; }

// A list of points as a flow sequence over several lines, `per_line` points a line.
void write_points(std::ostream& out, const std::string& indent, const Stroke& s, bool with_times, int per_line) {
  out << "[\n";
  for (std::size_t k = 0; k < s.points.size(); ++k) {
    if (k % static_cast<std::size_t>(per_line) == 0) out << indent << "  ";
    out << "[" << num(s.points[k].x()) << ", " << num(s.points[k].y());
    if (with_times) out << ", " << num(s.times[k]);
    out << "]";
    if (k + 1 < s.points.size()) out << ((k + 1) % static_cast<std::size_t>(per_line) == 0 ? ",\n" : ", ");
  }
  out << "]\n";
}

void write_strokes(std::ostream& out, const Drawing& d) {
  out << "strokes:\n  main: ";
  write_points(out, "  ", d.strokes[0], true, 4);
  out << "  auxiliary:\n";
  for (std::size_t i = 1; i < d.strokes.size(); ++i) {
    out << "    - ";
    write_points(out, "    ", d.strokes[i], false, 6);
  }
}

void write_options(std::ostream& out, const Options& o) {
  out << "agents: {count: " << o.agent_count << ", radius: " << num(o.agent_radius_m) << "}\n";
  out << "smoothing_window: " << o.smoothing_window << "\n";
  out << "width: {narrow: " << num(o.narrow_width_m) << ", wide: " << num(o.wide_width_m) << "}\n";
  out << "standard_distance: {narrow: " << num(o.narrow_distance_m) << ", wide: " << num(o.wide_distance_m) << "}\n";
  out << "irregularity: {gain: " << num(o.irregularity_gain) << ", max: " << num(o.irregularity_max) << "}\n";
  out << "follow_radius: " << num(o.follow_radius_m) << "\n";
  out << "weights: {trajectory: " << num(o.trajectory_weight) << ", avoid: " << num(o.avoid_weight)
      << ", obstacle: " << num(o.obstacle_weight) << "}\n";
  out << "time_step: " << num(o.time_step_s) << "\n";
  out << "direction_filter: " << num(o.direction_filter_s) << "\n";
  out << "max_acceleration: " << num(o.max_acceleration_m_s2) << "\n";
  out << "output_rate: " << num(o.output_rate_hz) << "\n";
  out << "duration: " << num(o.duration_s) << "\n";
  out << "end_of_path: " << (o.end_of_path == EndOfPath::stop ? "stop" : "remove") << "\n";
}

void write_obstacles(std::ostream& out, const Scene& scene) {
  if (scene.obstacles.empty()) return;
  out << "obstacles:\n";
  for (const Obstacle& o : scene.obstacles) {
    std::visit(
        [&](const auto& s) {
          using S = std::decay_t<decltype(s)>;
          if constexpr (std::is_same_v<S, Circle>) {
            out << "  - circle: {center: " << point(s.center) << ", radius: " << num(s.radius) << "}\n";
          } else if constexpr (std::is_same_v<S, ConvexPolygon>) {
            out << "  - polygon: [";
            for (std::size_t i = 0; i < s.vertices.size(); ++i) out << (i ? ", " : "") << point(s.vertices[i]);
            out << "]\n";
          } else {
            out << "  - wall: {from: " << point(s.a) << ", to: " << point(s.b) << ", thickness: " << num(s.thickness)
                << "}\n";
          }
        },
        o.shape);
    if (!o.name.empty()) out << "    name: " << o.name << "\n";
    if (o.is_moving()) {
      out << "    motion:\n";
      for (const PoseKey& k : o.motion) {
        out << "      - {time: " << num(k.time) << ", translation: " << point(k.translation)
            << ", angle: " << num(k.angle * 180.0 / std::numbers::pi) << "}\n";
      }
    }
  }
}

void write(const std::filesystem::path& path, const std::string& header, const scenes::SketchScene& scene) {
  std::ofstream out(path);
  out << header;
  write_options(out, scene.options);
  write_obstacles(out, scene.scene);
  write_strokes(out, scene.drawing);
  if (!out) throw std::runtime_error("cannot write " + path.string());
  std::cout << "wrote " << path.string() << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: sketch_make_configs CONFIG_DIR\n";
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  write(dir / "sketch-paper.yaml",
        "# The paper's experiment (Ogiwara & Oshita, §6): 50 agents on a 140 m course that changes speed, spread and\n"
        "# irregularity along the way. 0-40 m: a 8 m wide band drawn smoothly at 1.2 m/s; 40-80 m: widening to 16 m,\n"
        "# auxiliary lines drawn wobbly (irregular spacing); 80-140 m: a left turn, narrowing to 5 m, drawn twice as\n"
        "# fast. Agents are placed automatically between the auxiliary lines at the start; the run lasts until\n"
        "# every agent has arrived.\n"
        "#\n"
        "#   throng sketch configs/sketch-paper.yaml -o paper.h5 && throng plot paper.h5 -o paper.svg\n"
        "#\n"
        "# Generated from tests/sketch/scenes.cpp by tests/sketch/make_configs.cpp: edit those, not this file.\n",
        scenes::paper_experiment());
  write(dir / "sketch-large.yaml",
        "# A large crowd: 2,000 agents on a 40 m wide, 250 m long course past two pillars, a kiosk (a convex\n"
        "# polygon), a gate of two thick walls with a 20 m opening, and a cart crossing the course (a moving\n"
        "# circle), with four auxiliary lines. Agents slide round obstacles and never end a step inside one. The job\n"
        "# stops after 200 s of crowd time, when the whole crowd is past the obstacles; duration=0 runs until every\n"
        "# agent has arrived (about 350 s of crowd time).\n"
        "#\n"
        "#   throng sketch configs/sketch-large.yaml -o large.h5\n"
        "#\n"
        "# Generated from tests/sketch/scenes.cpp by tests/sketch/make_configs.cpp: edit those, not this file.\n",
        scenes::large_crowd());
  return 0;
}
