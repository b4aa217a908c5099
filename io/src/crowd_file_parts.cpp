// The parts of a crowd file shared by its writer (crowd_file.cpp) and other layouts (crowd_file_parts.h).
#include <throng/core/errors.h>
#include <throng/io/checked_numbers.h>
#include <throng/io/crowd_file_parts.h>

#include <string>
#include <variant>

namespace throng::detail {
namespace {

// Obstacle kinds in /parameters/throng/scene/obstacles/kind.
enum ObstacleKind : std::int32_t { kind_circle = 0, kind_polygon = 1, kind_wall = 2 };

void write_h5md_header(const h5::Group& root, const std::string& version) {
  h5::Group h5md = root.create_group("h5md");
  h5md.set_attribute("version", std::vector<std::int32_t>{1, 1});
  h5md.create_group("author").set_attribute("name", std::string("throng"));
  h5::Group creator = h5md.create_group("creator");
  creator.set_attribute("name", std::string("throng"));
  creator.set_attribute("version", version);
  h5::Group units = h5md.create_group("modules").create_group("units");
  units.set_attribute("version", std::vector<std::int32_t>{1, 0});
  units.set_attribute("system", std::string("SI"));
}

// Scene layout under /parameters/throng/scene:
//   obstacles/kind int32[K] (0 circle, 1 convex polygon, 2 wall), obstacles/name string[K],
//   obstacles/size float64[K] (circle radius, wall thickness, 0 for polygons),
//   obstacles/vertex_offset int64[K+1] and obstacles/vertices float64[V][2] (circle: its centre; polygon: its
//   vertices CCW; wall: its two end points), obstacles/motion_offset int64[K+1] and obstacles/motion float64[M][4]
//   (time, translation x, translation y, angle) — no rows for a static obstacle;
//   region float64[6] (min x, min y, max x, max y, t0, t1) and region_periodic int32[3] when a region is set.
void write_scene(const h5::Group& parameters, const Scene& scene) {
  h5::Group g = parameters.create_group("scene");
  if (!scene.obstacles.empty()) {
    h5::Group o = g.create_group("obstacles");
    std::vector<std::int32_t> kind;
    std::vector<std::string> name;
    std::vector<double> size, vertices, motion;
    std::vector<std::int64_t> vertex_offset{0}, motion_offset{0};
    for (const Obstacle& ob : scene.obstacles) {
      name.push_back(ob.name);
      std::visit(
          [&](const auto& s) {
            using S = std::decay_t<decltype(s)>;
            if constexpr (std::is_same_v<S, Circle>) {
              kind.push_back(kind_circle);
              size.push_back(s.radius);
              vertices.insert(vertices.end(), {s.center.x(), s.center.y()});
            } else if constexpr (std::is_same_v<S, ConvexPolygon>) {
              kind.push_back(kind_polygon);
              size.push_back(0.0);
              for (const auto& v : s.vertices) vertices.insert(vertices.end(), {v.x(), v.y()});
            } else {
              kind.push_back(kind_wall);
              size.push_back(s.thickness);
              vertices.insert(vertices.end(), {s.a.x(), s.a.y(), s.b.x(), s.b.y()});
            }
          },
          ob.shape);
      vertex_offset.push_back(static_cast<std::int64_t>(vertices.size() / 2));
      for (const PoseKey& k : ob.motion) motion.insert(motion.end(), {k.time, k.translation.x(), k.translation.y(), k.angle});
      motion_offset.push_back(static_cast<std::int64_t>(motion.size() / 4));
    }
    const std::uint64_t K = scene.obstacles.size();
    o.write("kind", kind, {K});
    o.write("name", name);
    o.write("size", size, {K});
    o.write("vertex_offset", vertex_offset, {K + 1});
    o.write("vertices", vertices, {vertices.size() / 2, 2});
    o.write("motion_offset", motion_offset, {K + 1});
    o.write("motion", motion, {motion.size() / 4, 4});
  }
  if (scene.region) {
    const Region& r = *scene.region;
    g.write("region", std::vector<double>{r.min.x(), r.min.y(), r.max.x(), r.max.y(), r.t0, r.t1}, {6});
    g.write("region_periodic", std::vector<std::int32_t>{r.periodic[0], r.periodic[1], r.periodic[2]}, {3});
  }
}

}  // namespace

h5::Group write_crowd_header(const h5::Group& root, const Provenance& provenance, const Scene& scene) {
  write_h5md_header(root, provenance.program_version);
  h5::Group parameters = root.create_group("parameters").create_group("throng");
  parameters.set_attribute("format_version", crowd_format_version);
  parameters.set_attribute("program", std::string("throng"));
  parameters.set_attribute("program_version", provenance.program_version);
  parameters.set_attribute("command_line", provenance.command_line);
  parameters.set_attribute("options", provenance.options);
  parameters.set_attribute("seed", provenance.seed);
  parameters.set_attribute("inputs", provenance.inputs);
  parameters.set_attribute("credits", provenance.credits);
  write_scene(parameters, scene);
  return parameters;
}

const std::vector<std::string> quaternion_components{"x", "y", "z", "w"};

void write_orientation_attributes(const h5::Group& element) {
  element.set_attribute("components", quaternion_components);
  element.set_attribute("body_frame", std::string("unit quaternion (x, y, z, w) turning the agent's body frame "
                                                  "(forward +x, left +y, up +z) into the world; NaN where absent"));
}

void write_agent_parts(const h5::Group& root, const h5::Group& parameters, const CrowdMotion& motion,
                       const std::vector<std::array<std::int32_t, 2>>& formation_edges) {
  if (!formation_edges.empty()) {
    const h5::Group connectivity = root.create_group("connectivity");
    std::vector<std::int32_t> edges;
    for (const auto& e : formation_edges) edges.insert(edges.end(), {e[0], e[1]});
    connectivity.write("formation_edges", edges, {formation_edges.size(), 2});
    connectivity.set_reference_attribute_on("formation_edges", "particles_group", "/particles/trajectory");
  }
  const h5::Group agents = parameters.create_group("agents");
  agents.write("id", motion.ids, {motion.ids.size()});
  agents.write("radius", motion.radii, {motion.radii.size()});
}

void write_action_attributes(const h5::Group& element, const std::vector<ActionKind>& table) {
  std::vector<std::string> names, props;
  for (const ActionKind& a : table) {
    names.push_back(a.name);
    props.push_back(a.prop);
  }
  element.set_attribute("names", names);
  element.set_attribute("props", props);
}

void write_box_attributes(const h5::Group& box, const Scene& scene) {
  box.set_attribute("dimension", std::int64_t{3});
  const bool px = scene.region && scene.region->periodic[0], py = scene.region && scene.region->periodic[1];
  box.set_attribute("boundary", std::vector<std::string>{px ? "periodic" : "none", py ? "periodic" : "none", "none"});
  if (!px && !py) return;
  const Region& r = *scene.region;
  box.write("offset", std::vector<double>{r.min.x(), r.min.y(), 0.0}, {3});
}

std::array<double, 9> box_edges_frame(const Region& r) {
  return {r.max.x() - r.min.x(), 0, 0, 0, r.max.y() - r.min.y(), 0, 0, 0, 0};
}

void check_format_version(const h5::Group& root) {
  if (!root.has("parameters/throng")) return;
  const h5::Group parameters = root.open_group("parameters/throng");
  const auto v = parameters.int_attribute("format_version");
  if (v.size() != 1) throw InputError(parameters.where() + ": missing attribute format_version");
  if (v.front() != crowd_format_version) {
    throw InputError(parameters.where() + ": unknown format version " + std::to_string(v.front()) +
                     " (this throng reads version " + std::to_string(crowd_format_version) + ")");
  }
}

Scene read_scene(const h5::Group& parameters) {
  Scene scene;
  if (!parameters.has("scene")) return scene;
  const h5::Group g = parameters.open_group("scene");
  if (g.has("obstacles")) {
    const h5::Group o = g.open_group("obstacles");
    const auto kind = o.read_int32("kind", 1).values;
    const std::size_t K = kind.size();
    const auto names = o.read_strings("name");
    const auto size = o.read_doubles("size", 1).values;
    const auto vertex_offset = o.read_int64("vertex_offset", 1).values;
    const auto vertices = o.read_doubles("vertices", 2);
    const auto motion_offset = o.read_int64("motion_offset", 1).values;
    const auto motion = o.read_doubles("motion", 2);
    if (names.size() != K || size.size() != K || vertex_offset.size() != K + 1 || motion_offset.size() != K + 1 ||
        vertices.shape[1] != 2 || motion.shape[1] != 4) {
      throw InputError(o.where() + ": obstacle datasets disagree in length (kind has " + std::to_string(K) + " entries)");
    }
    const auto V = static_cast<std::int64_t>(vertices.shape[0]);
    const auto M = static_cast<std::int64_t>(motion.shape[0]);
    // The obstacles built from the arrays (K of them, V vertices and M pose keys in all), against the limit.
    const auto bytes = checked_sum(checked_product(K, sizeof(Obstacle) + 32).value_or(UINT64_MAX),
                                   checked_sum(checked_product(vertices.shape[0], sizeof(Eigen::Vector2d)).value_or(UINT64_MAX),
                                               checked_product(motion.shape[0], sizeof(PoseKey)).value_or(UINT64_MAX))
                                       .value_or(UINT64_MAX));
    o.budget().charge(bytes.value_or(UINT64_MAX), o.where(), std::to_string(K) + " obstacles");
    for (std::size_t k = 0; k < K; ++k) {
      const std::int64_t v0 = vertex_offset[k], v1 = vertex_offset[k + 1];
      const std::int64_t m0 = motion_offset[k], m1 = motion_offset[k + 1];
      if (v0 < 0 || v1 < v0 || v1 > V || m0 < 0 || m1 < m0 || m1 > M) {
        throw InputError(o.where("vertex_offset") + ": offsets of obstacle " + std::to_string(k) + " are out of range");
      }
      auto vertex = [&](std::int64_t i) {
        return Eigen::Vector2d(vertices.values[static_cast<std::size_t>(2 * i)], vertices.values[static_cast<std::size_t>(2 * i + 1)]);
      };
      Obstacle ob;
      ob.name = names[k];
      const std::int64_t count = v1 - v0;
      auto need = [&](std::int64_t n, const char* what) {
        if (count != n) throw InputError(o.where("vertices") + ": " + what + " " + std::to_string(k) + " has " + std::to_string(count) + " points");
      };
      switch (kind[k]) {
        case kind_circle: need(1, "circle"); ob.shape = Circle{vertex(v0), size[k]}; break;
        case kind_wall: need(2, "wall"); ob.shape = Wall{vertex(v0), vertex(v0 + 1), size[k]}; break;
        case kind_polygon: {
          ConvexPolygon p;
          for (std::int64_t i = v0; i < v1; ++i) p.vertices.push_back(vertex(i));
          ob.shape = std::move(p);
          break;
        }
        default: throw InputError(o.where("kind") + ": unknown obstacle kind " + std::to_string(kind[k]));
      }
      for (std::int64_t i = m0; i < m1; ++i) {
        const double* row = motion.values.data() + 4 * i;
        ob.motion.push_back({row[0], {row[1], row[2]}, row[3]});
      }
      scene.obstacles.push_back(std::move(ob));
    }
  }
  if (g.has("region")) {
    const auto r = g.read_doubles("region", 1).values;
    const auto p = g.read_int32("region_periodic", 1).values;
    if (r.size() != 6 || p.size() != 3) throw InputError(g.where("region") + ": expected 6 bounds and 3 periodic flags");
    Region region;
    region.min = {r[0], r[1]};
    region.max = {r[2], r[3]};
    region.t0 = r[4];
    region.t1 = r[5];
    region.periodic = {p[0] != 0, p[1] != 0, p[2] != 0};
    scene.region = region;
  }
  scene.validate(g.where());
  return scene;
}

Scene read_crowd_scene(const h5::File& file) {
  const h5::Group root = file.root();
  check_format_version(root);
  if (!root.has("parameters/throng")) return Scene{};
  return read_scene(root.open_group("parameters/throng"));
}

std::uint64_t crowd_agent_count(const h5::File& file) {
  const h5::Group root = file.root();
  if (root.has("parameters/throng/agents/id")) {
    const auto shape = root.open_group("parameters/throng/agents").shape("id");
    if (shape.size() != 1) throw InputError(root.where("parameters/throng/agents/id") + ": expected one id per agent (rank 1)");
    return shape[0];
  }
  const auto shape = root.open_group("particles/trajectory").shape("position/value");
  if (shape.size() != 3) throw InputError(root.where("particles/trajectory/position/value") + ": expected [frames][agents][3]");
  return shape[1];
}

}  // namespace throng::detail
