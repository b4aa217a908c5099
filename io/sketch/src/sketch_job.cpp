#include <throng/core/errors.h>
#include <throng/io/scene_config.h>
#include <throng/io/sketch_job.h>

#include <cmath>
#include <sstream>
#include <string>

namespace throng {
namespace {

using sketch::EndOfPath;
using sketch::Options;
using sketch::Stroke;

// Every option but the data (strokes, agent positions, obstacles) and the seed (--seed).
void bind(OptionBinder& b, Options& o) {
  b.field("smoothing_window", o.smoothing_window, Range::closed(0, 100000));
  b.field("resample_spacing", o.resample_spacing_m, Range::non_negative());
  b.field("speed_scale", o.speed_scale, Range::positive());
  b.section("width", [&](OptionBinder& w) {
    w.field("narrow", o.narrow_width_m, Range::non_negative());
    w.field("wide", o.wide_width_m, Range::positive());
  });
  b.section("standard_distance", [&](OptionBinder& s) {
    s.field("narrow", o.narrow_distance_m, Range::positive());
    s.field("wide", o.wide_distance_m, Range::positive());
  });
  b.section("irregularity", [&](OptionBinder& i) {
    i.field("gain", o.irregularity_gain, Range::non_negative());
    i.field("max", o.irregularity_max, Range::positive());
  });
  b.section("agents", [&](OptionBinder& a) {
    a.field("count", o.agent_count, Range::closed(1, 1e8));
    a.field("radius", o.agent_radius_m, Range::positive());
  });
  b.field("follow_radius", o.follow_radius_m, Range::positive());
  b.field("obstacle_distance", o.obstacle_distance_m, Range::non_negative());
  b.field("slide_around_obstacles", o.slide_around_obstacles);
  b.section("weights", [&](OptionBinder& w) {
    w.field("trajectory", o.trajectory_weight, Range::positive());
    w.field("avoid", o.avoid_weight, Range::non_negative());
    w.field("obstacle", o.obstacle_weight, Range::non_negative());
  });
  b.field("time_step", o.time_step_s, Range::positive());
  b.field("direction_filter", o.direction_filter_s, Range::non_negative());
  b.field("max_acceleration", o.max_acceleration_m_s2, Range::non_negative());
  b.field("output_rate", o.output_rate_hz, Range::positive());
  b.field("duration", o.duration_s, Range::non_negative());
  b.field("max_duration", o.max_duration_s, Range::positive());
  b.choice("end_of_path", o.end_of_path, {{"stop", EndOfPath::stop}, {"remove", EndOfPath::remove}});
}

std::string number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// A stroke from a list of points [x, y] or [x, y, t] (`timed`: [x, y, t] required, times strictly increasing).
// Numbers are finite (ConfigNode::as_doubles rejects NaN and infinities).
Stroke read_stroke(const ConfigNode& node, bool timed, const std::string& name) {
  Stroke stroke;
  const std::vector<ConfigNode> points = node.elements();
  if (points.size() < 2) {
    node.fail(name + " has " + std::to_string(points.size()) + " point(s), expected at least 2");
  }
  bool has_times = timed;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const ConfigNode& p = points[k];
    const std::vector<double> v = timed ? p.as_doubles({3}) : p.as_doubles({2, 3});
    if (k == 0 && !timed) has_times = v.size() == 3;
    if (!timed && (v.size() == 3) != has_times) p.fail(name + ": give every point a time, or none");
    stroke.points.emplace_back(v[0], v[1]);
    if (v.size() == 3) {
      if (timed && k > 0 && !(v[2] > stroke.times.back())) {
        p.fail(name + " point " + std::to_string(k) + " is drawn at " + number(v[2]) + " s, not after " +
               number(stroke.times.back()) + " s; the main line's times must increase strictly (they set the speed)");
      }
      stroke.times.push_back(v[2]);
    }
  }
  return stroke;
}

YAML::Node flow(std::initializer_list<double> values) {
  YAML::Node n(YAML::NodeType::Sequence);
  for (double v : values) n.push_back(yaml_number(v));
  n.SetStyle(YAML::EmitterStyle::Flow);
  return n;
}

YAML::Node stroke_yaml(const Stroke& s) {
  YAML::Node list(YAML::NodeType::Sequence);
  for (std::size_t k = 0; k < s.points.size(); ++k) {
    list.push_back(s.times.empty() ? flow({s.points[k].x(), s.points[k].y()})
                                   : flow({s.points[k].x(), s.points[k].y(), s.times[k]}));
  }
  return list;
}

std::vector<double> flatten(const std::vector<Eigen::Vector2d>& points) {
  std::vector<double> v;
  v.reserve(2 * points.size());
  for (const auto& p : points) {
    v.push_back(p.x());
    v.push_back(p.y());
  }
  return v;
}

}  // namespace

SketchJob read_sketch_job(const ConfigNode& job) {
  SketchJob parsed;
  Options& o = parsed.options;
  OptionReader reader(job);
  bind(reader, o);
  if (!(o.wide_width_m > o.narrow_width_m)) {
    job.at("width").fail("wide (" + number(o.wide_width_m) + " m) must be greater than narrow (" +
                         number(o.narrow_width_m) + " m)");
  }

  // Strokes: the main line with times, then the auxiliary lines.
  const ConfigNode strokes = job.at("strokes");
  parsed.drawing.strokes.push_back(read_stroke(strokes.at("main"), true, "the main line"));
  const ConfigNode auxiliary = strokes.at("auxiliary");
  const std::vector<ConfigNode> lines = auxiliary.elements();
  if (lines.empty()) auxiliary.fail("give at least one auxiliary line");
  for (std::size_t i = 0; i < lines.size(); ++i) {
    parsed.drawing.strokes.push_back(read_stroke(lines[i], false, "auxiliary line " + std::to_string(i)));
  }

  // The scene: obstacles only. read_scene also knows `region`, which sketch does not take; it reads a view of
  // the job holding just the obstacles, so an unknown-key message never offers `region` as a known key.
  if (job.is_map() && job.yaml()["region"].IsDefined()) job.at("region").fail("sketch does not use a region");
  if (auto obstacles = job.find("obstacles")) {
    YAML::Node only(YAML::NodeType::Map);
    only["obstacles"] = obstacles->yaml();
    const ConfigNode scene_job(only, job.source());
    parsed.scene = read_scene(scene_job);
    scene_job.finish();
  }

  // Given start positions: their number is the agent count.
  std::optional<ConfigNode> positions;
  if (auto agents = job.find("agents")) positions = agents->find("positions");
  if (positions) {
    const std::vector<ConfigNode> points = positions->elements();
    if (points.empty()) positions->fail("give at least one position, or leave positions out");
    const bool count_given = job.at("agents").has("count");
    if (count_given && o.agent_count != points.size()) {
      job.at("agents").at("count").fail("count is " + std::to_string(o.agent_count) + " but " +
                                        std::to_string(points.size()) + " positions are given");
    }
    o.agent_count = points.size();
    for (std::size_t j = 0; j < points.size(); ++j) {
      const std::vector<double> v = points[j].as_doubles({2});
      const Eigen::Vector2d p(v[0], v[1]);  // finite: as_doubles rejects NaN and infinities
      for (std::size_t k = 0; k < parsed.scene.obstacles.size(); ++k) {
        const Obstacle& obstacle = parsed.scene.obstacles[k];
        if (distance_to(obstacle, p, 0.0).signed_distance < 0) {
          points[j].fail("agent " + std::to_string(j) + " starts inside obstacle " + std::to_string(k) +
                         (obstacle.name.empty() ? "" : " ('" + obstacle.name + "')"));
        }
      }
      parsed.drawing.initial_positions.push_back(p);
    }
  }
  job.finish();

  // What only the whole drawing can tell (a zero-length stroke, options the solver rejects): same exit code,
  // pointing at the strokes.
  sketch::Course course;
  try {
    sketch::validate(o);
    course = sketch::analyse_strokes(parsed.drawing.strokes, o);
  } catch (const Error& e) {
    strokes.fail(e.what());
  }
  // Automatic placement: an agent count the course cannot hold is an error at agents.count (at the strokes when
  // the count is the default). Placement is deterministic and cheap next to the run, which places them again.
  if (parsed.drawing.initial_positions.empty()) {
    try {
      (void)sketch::place_agents(course, o.agent_count, parsed.scene, o);
    } catch (const ConfigError& e) {
      std::optional<ConfigNode> count;
      if (auto agents = job.find("agents")) count = agents->find("count");
      if (count) count->fail(e.what());
      strokes.fail(std::string(e.what()) + " (the default agents.count)");
    }
  }
  return parsed;
}

YAML::Node effective_sketch_job(const SketchJob& job) {
  YAML::Node out;
  YAML::Node strokes;
  strokes["main"] = stroke_yaml(job.drawing.strokes.front());
  YAML::Node auxiliary(YAML::NodeType::Sequence);
  for (std::size_t i = 1; i < job.drawing.strokes.size(); ++i) auxiliary.push_back(stroke_yaml(job.drawing.strokes[i]));
  strokes["auxiliary"] = auxiliary;
  out["strokes"] = strokes;
  Options options = job.options;
  OptionWriter writer(out);
  bind(writer, options);
  if (!job.drawing.initial_positions.empty()) {
    YAML::Node positions(YAML::NodeType::Sequence);
    for (const auto& p : job.drawing.initial_positions) positions.push_back(flow({p.x(), p.y()}));
    out["agents"]["positions"] = positions;
  }
  write_scene(out, job.scene);
  return out;
}

void write_sketch_data(const h5::Group& throng_parameters, const SketchJob& job,
                       const sketch::SimulationResult& result) {
  const h5::Group sketch = throng_parameters.create_group("sketch");
  const h5::Group strokes = sketch.create_group("strokes");
  // As given: [x, y, t] when the line has times (the main line always has), else [x, y] (an auxiliary line
  // drawn without them; the method does not use an auxiliary line's times).
  const auto write_stroke = [&](const std::string& name, const Stroke& stroke) {
    if (stroke.times.empty()) {
      strokes.write(name, flatten(stroke.points), {stroke.points.size(), 2});
      return;
    }
    std::vector<double> rows;
    for (std::size_t k = 0; k < stroke.points.size(); ++k) {
      rows.insert(rows.end(), {stroke.points[k].x(), stroke.points[k].y(), stroke.times[k]});
    }
    strokes.write(name, rows, {stroke.points.size(), 3});
  };
  write_stroke("main", job.drawing.strokes.front());
  for (std::size_t i = 1; i < job.drawing.strokes.size(); ++i) {
    write_stroke("auxiliary_" + std::to_string(i - 1), job.drawing.strokes[i]);
  }

  const sketch::Course& c = result.course;
  const std::uint64_t K = c.point_count();
  const h5::Group course = sketch.create_group("course");
  course.write("main", flatten(c.main), {K, 2});
  course.write("speed", c.speed, {K});
  course.write("width", c.width, {K});
  course.write("standard_distance", c.standard_distance, {K});
  course.write("irregularity", c.irregularity, {K});
  course.write("correction_scale", c.correction_scale, {K});

  const sketch::AgentParameters& a = result.agents;
  const std::uint64_t N = a.agent_count();
  const h5::Group agents = sketch.create_group("agents");
  agents.write("start", flatten(a.start), {N, 2});
  std::vector<double> weights(N * static_cast<std::uint64_t>(a.weights.cols()));
  for (Eigen::Index j = 0; j < a.weights.rows(); ++j) {
    for (Eigen::Index i = 0; i < a.weights.cols(); ++i) {
      weights[static_cast<std::size_t>(j * a.weights.cols() + i)] = a.weights(j, i);
    }
  }
  agents.write("weights", weights, {N, static_cast<std::uint64_t>(a.weights.cols())});
  agents.write("correction_draw", a.correction_draw, {N});
  agents.write("arrival_time", result.arrival_time_s, {N});
}

}  // namespace throng
