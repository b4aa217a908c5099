#include <throng/core/errors.h>
#include <throng/io/scene_config.h>

#include <cmath>
#include <numbers>

namespace throng {
namespace {

constexpr double degrees = std::numbers::pi / 180.0;

Eigen::Vector2d point(const ConfigNode& n) {
  const auto v = n.as_doubles({2});
  return {v[0], v[1]};
}

double signed_area(const std::vector<Eigen::Vector2d>& v) {
  double a = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const auto& p = v[i];
    const auto& q = v[(i + 1) % v.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * a;
}

Obstacle read_obstacle(const ConfigNode& n) {
  Obstacle o;
  int shapes = 0;
  if (auto c = n.find("circle")) {
    ++shapes;
    Circle circle{point(c->at("center")), c->at("radius").as_double()};
    if (!(circle.radius > 0)) c->at("radius").fail("radius must be > 0");
    o.shape = circle;
  }
  if (auto p = n.find("polygon")) {
    ++shapes;
    ConvexPolygon polygon;
    for (const auto& v : p->elements()) polygon.vertices.push_back(point(v));
    if (polygon.vertices.size() < 3) p->fail("a polygon needs at least 3 vertices");
    if (signed_area(polygon.vertices) < 0) std::reverse(polygon.vertices.begin(), polygon.vertices.end());
    o.shape = std::move(polygon);
  }
  if (auto w = n.find("wall")) {
    ++shapes;
    Wall wall{point(w->at("from")), point(w->at("to")), 0.2};
    if (auto t = w->find("thickness")) {
      wall.thickness = t->as_double();
      if (wall.thickness < 0) t->fail("thickness must be ≥ 0");
    }
    o.shape = wall;
  }
  if (shapes != 1) n.fail("an obstacle needs exactly one of circle, polygon, wall");
  if (auto name = n.find("name")) o.name = name->as_string();
  if (auto motion = n.find("motion")) {
    for (const auto& k : motion->elements()) {
      PoseKey key;
      key.time = k.at("time").as_double();
      if (auto t = k.find("translation")) key.translation = point(*t);
      if (auto a = k.find("angle")) key.angle = a->as_double() * degrees;
      o.motion.push_back(key);
    }
  }
  try {
    validate(o, "obstacle");
  } catch (const InputError& e) {
    n.fail(e.what());
  }
  return o;
}

YAML::Node flow_point(const Eigen::Vector2d& p) { return yaml_numbers({p.x(), p.y()}); }

}  // namespace

std::vector<Obstacle> read_obstacles(const ConfigNode& job) {
  std::vector<Obstacle> out;
  if (auto obstacles = job.find("obstacles")) {
    if (!obstacles->is_null()) {
      for (const auto& o : obstacles->elements()) out.push_back(read_obstacle(o));
    }
  }
  return out;
}

Scene read_scene(const ConfigNode& job) {
  Scene scene;
  scene.obstacles = read_obstacles(job);
  if (auto r = job.find("region")) {
    Region region;
    region.min = point(r->at("min"));
    region.max = point(r->at("max"));
    if (auto t = r->find("time")) {
      const auto v = t->as_doubles({2});
      region.t0 = v[0];
      region.t1 = v[1];
    }
    if (auto p = r->find("periodic")) {
      const auto flags = p->elements();
      if (flags.size() != 3) p->fail("expected 3 flags (x, y, t)");
      for (std::size_t i = 0; i < 3; ++i) region.periodic[i] = flags[i].as_bool();
    }
    if (!(region.max.x() > region.min.x() && region.max.y() > region.min.y() && region.t1 > region.t0)) {
      r->fail("region is empty: expected min < max and time[0] < time[1]");
    }
    scene.region = region;
  }
  return scene;
}

void write_scene(YAML::Node& job, const Scene& scene) {
  if (!scene.obstacles.empty()) {
    YAML::Node list(YAML::NodeType::Sequence);
    for (const Obstacle& o : scene.obstacles) {
      YAML::Node n(YAML::NodeType::Map);
      std::visit(
          [&](const auto& s) {
            using S = std::decay_t<decltype(s)>;
            if constexpr (std::is_same_v<S, Circle>) {
              n["circle"]["center"] = flow_point(s.center);
              n["circle"]["radius"] = yaml_number(s.radius);
            } else if constexpr (std::is_same_v<S, ConvexPolygon>) {
              YAML::Node vertices(YAML::NodeType::Sequence);
              for (const auto& v : s.vertices) vertices.push_back(flow_point(v));
              n["polygon"] = vertices;
            } else {
              n["wall"]["from"] = flow_point(s.a);
              n["wall"]["to"] = flow_point(s.b);
              n["wall"]["thickness"] = yaml_number(s.thickness);
            }
          },
          o.shape);
      if (!o.name.empty()) n["name"] = o.name;
      for (const PoseKey& k : o.motion) {
        YAML::Node key(YAML::NodeType::Map);
        key["time"] = yaml_number(k.time);
        key["translation"] = flow_point(k.translation);
        key["angle"] = yaml_number(k.angle / degrees);
        key.SetStyle(YAML::EmitterStyle::Flow);
        n["motion"].push_back(key);
      }
      list.push_back(n);
    }
    job["obstacles"] = list;
  }
  if (scene.region) {
    const Region& r = *scene.region;
    YAML::Node n(YAML::NodeType::Map);
    n["min"] = flow_point(r.min);
    n["max"] = flow_point(r.max);
    n["time"] = flow_point({r.t0, r.t1});
    YAML::Node p(YAML::NodeType::Sequence);
    for (bool b : r.periodic) p.push_back(b);
    p.SetStyle(YAML::EmitterStyle::Flow);
    n["periodic"] = p;
    job["region"] = n;
  }
}

}  // namespace throng
