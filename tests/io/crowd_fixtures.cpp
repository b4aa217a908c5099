#include "crowd_fixtures.h"

#include <cstring>

namespace throng::test {

CrowdFile rich_crowd() {
  CrowdFile f;
  CrowdMotion& m = f.motion;
  m = CrowdMotion::with_shape(5, 4, 0.3);
  m.times = {0.0, 0.5, 1.25, 2.0, 3.5};
  m.ids = {7, 3, 11, 100000000000};
  m.radii = {0.3, 0.25, 0.4, 0.2};
  m.species = {1, 1, 2, 0};
  for (std::size_t t = 0; t < 5; ++t) {
    for (std::size_t n = 0; n < 4; ++n) {
      if ((n == 2 && t < 2) || (n == 3 && t == 4)) continue;  // agent 11 enters late, the last leaves early
      m.position(t, n) = Eigen::Vector3d(0.1 * t + n, -0.3 * n + 1.0 / 3.0, 0.0);
    }
  }
  m.velocities.assign(m.positions.size(), 0.0);
  for (std::size_t i = 0; i < m.positions.size(); ++i) m.velocities[i] = std::isfinite(m.positions[i]) ? 0.2 : absent;
  f.scene.obstacles.push_back({Circle{{1, 2}, 0.5}, {}, "pillar"});
  f.scene.obstacles.push_back({ConvexPolygon{{{0, 0}, {1, 0}, {1, 1}}}, {{0, {0, 0}, 0}, {2, {1, 1}, 0.5}}, "cart"});
  f.scene.obstacles.push_back({Wall{{-1, -1}, {5, -1}, 0.2}, {}, ""});
  f.scene.region = Region{{-2, -2}, {6, 6}, 0.0, 3.5, {true, false, true}};
  f.formation_edges = {{0, 1}, {1, 2}};
  f.provenance.program_version = "test";
  f.provenance.command_line = "throng test --seed 9";
  f.provenance.options = "a: 1\n";
  f.provenance.seed = 9;
  f.provenance.inputs = {"in.h5"};
  f.provenance.credits = {"someone"};
  return f;
}

namespace {
template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}
}  // namespace

bool same_crowd(const CrowdFile& a, const CrowdFile& b) {
  const CrowdMotion &x = a.motion, &y = b.motion;
  if (!same_bits(x.times, y.times) || !same_bits(x.positions, y.positions) || !same_bits(x.ids, y.ids) ||
      !same_bits(x.radii, y.radii) || !same_bits(x.species, y.species) || !same_bits(x.velocities, y.velocities)) {
    return false;
  }
  if (a.formation_edges != b.formation_edges) return false;
  if (a.scene.obstacles.size() != b.scene.obstacles.size()) return false;
  for (std::size_t i = 0; i < a.scene.obstacles.size(); ++i) {
    const Obstacle &p = a.scene.obstacles[i], &q = b.scene.obstacles[i];
    if (p.name != q.name || p.shape.index() != q.shape.index() || p.motion.size() != q.motion.size()) return false;
    for (std::size_t k = 0; k < p.motion.size(); ++k) {
      if (p.motion[k].time != q.motion[k].time || p.motion[k].translation != q.motion[k].translation || p.motion[k].angle != q.motion[k].angle) return false;
    }
    const bool shape_equal = std::visit(
        [&](const auto& s) {
          using S = std::decay_t<decltype(s)>;
          const S& t = std::get<S>(q.shape);
          if constexpr (std::is_same_v<S, Circle>) return s.center == t.center && s.radius == t.radius;
          else if constexpr (std::is_same_v<S, ConvexPolygon>) return s.vertices == t.vertices;
          else return s.a == t.a && s.b == t.b && s.thickness == t.thickness;
        },
        p.shape);
    if (!shape_equal) return false;
  }
  if (a.scene.region.has_value() != b.scene.region.has_value()) return false;
  if (a.scene.region) {
    const Region &r = *a.scene.region, &s = *b.scene.region;
    if (r.min != s.min || r.max != s.max || r.t0 != s.t0 || r.t1 != s.t1 || r.periodic != s.periodic) return false;
  }
  const Provenance &p = a.provenance, &q = b.provenance;
  return p.program_version == q.program_version && p.command_line == q.command_line && p.options == q.options &&
         p.seed == q.seed && p.inputs == q.inputs && p.credits == q.credits;
}

}  // namespace throng::test
