#include <throng/core/crowd_motion.h>
#include <throng/core/errors.h>

#include <cmath>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>

namespace throng {

CrowdMotion CrowdMotion::with_shape(std::size_t frame_count, std::size_t agent_count, double radius) {
  CrowdMotion m;
  m.times.resize(frame_count);
  for (std::size_t t = 0; t < frame_count; ++t) m.times[t] = static_cast<double>(t);
  m.positions.assign(frame_count * agent_count * 3, absent);
  m.ids.resize(agent_count);
  for (std::size_t n = 0; n < agent_count; ++n) m.ids[n] = static_cast<std::int64_t>(n);
  m.radii.assign(agent_count, radius);
  m.species.assign(agent_count, 0);
  return m;
}

std::pair<std::size_t, std::size_t> CrowdMotion::presence_span(std::size_t agent) const noexcept {
  const std::size_t T = frame_count();
  std::size_t first = T;
  std::size_t last = 0;
  for (std::size_t t = 0; t < T; ++t) {
    if (present(t, agent)) {
      if (first == T) first = t;
      last = t + 1;
    }
  }
  if (first == T) return {0, 0};
  return {first, last};
}

void CrowdMotion::validate(const std::string& what) const {
  const std::size_t T = frame_count();
  const std::size_t N = agent_count();
  auto fail = [&](const std::string& message) { throw InputError(what + ": " + message); };
  if (positions.size() != T * N * 3) {
    fail("positions hold " + std::to_string(positions.size()) + " values, expected frames × agents × 3 = " +
         std::to_string(T) + " × " + std::to_string(N) + " × 3");
  }
  if (!velocities.empty() && velocities.size() != positions.size()) {
    fail("velocities hold " + std::to_string(velocities.size()) + " values, expected " +
         std::to_string(positions.size()) + " (same shape as positions)");
  }
  if (radii.size() != N) fail("radii hold " + std::to_string(radii.size()) + " values for " + std::to_string(N) + " agents");
  if (species.size() != N) fail("species hold " + std::to_string(species.size()) + " values for " + std::to_string(N) + " agents");
  for (std::size_t t = 0; t < T; ++t) {
    if (!std::isfinite(times[t])) fail("time of frame " + std::to_string(t) + " is not finite");
    if (t > 0 && !(times[t] > times[t - 1])) {
      fail("times not strictly increasing at frame " + std::to_string(t) + " (" + std::to_string(times[t - 1]) +
           " then " + std::to_string(times[t]) + ")");
    }
  }
  for (std::size_t t = 0; t < T; ++t) {
    for (std::size_t n = 0; n < N; ++n) {
      const std::size_t i = index(t, n);
      const bool x = std::isfinite(positions[i]);
      const bool y = std::isfinite(positions[i + 1]);
      const bool z = std::isfinite(positions[i + 2]);
      if (x != y || x != z) {
        fail("agent " + std::to_string(ids[n]) + " at frame " + std::to_string(t) +
             " has a NaN or infinite coordinate while present");
      }
    }
  }
  std::unordered_map<std::int64_t, std::size_t> seen;
  for (std::size_t n = 0; n < N; ++n) {
    if (ids[n] < 0) fail("agent " + std::to_string(n) + " has negative id " + std::to_string(ids[n]));
    auto [it, inserted] = seen.emplace(ids[n], n);
    if (!inserted) {
      fail("id " + std::to_string(ids[n]) + " is used by agents " + std::to_string(it->second) + " and " + std::to_string(n));
    }
    if (!(std::isfinite(radii[n]) && radii[n] >= 0)) {
      fail("agent " + std::to_string(ids[n]) + " has radius " + std::to_string(radii[n]) + ", expected a finite value ≥ 0");
    }
  }
  if (!orientations.empty()) {
    if (orientations.size() != T * N * 4) {
      fail("orientations hold " + std::to_string(orientations.size()) + " values, expected frames × agents × 4 = " +
           std::to_string(T) + " × " + std::to_string(N) + " × 4");
    }
    for (std::size_t t = 0; t < T; ++t) {
      for (std::size_t n = 0; n < N; ++n) {
        if (!present(t, n)) continue;
        const Eigen::Vector4d q = orientation(t, n).coeffs();
        if (!q.allFinite() || std::abs(q.norm() - 1.0) > orientation_tolerance) {
          fail("agent " + std::to_string(ids[n]) + " at frame " + std::to_string(t) + " has orientation (" +
               std::to_string(q[0]) + ", " + std::to_string(q[1]) + ", " + std::to_string(q[2]) + ", " +
               std::to_string(q[3]) + "), expected a finite unit quaternion (x, y, z, w)");
        }
      }
    }
  }
  std::set<std::pair<std::string, std::string>> entries;
  for (std::size_t k = 0; k < action_table.size(); ++k) {
    if (action_table[k].name.empty()) fail("action_table entry " + std::to_string(k) + " has an empty name");
    if (!entries.emplace(action_table[k].name, action_table[k].prop).second) {
      fail("action_table entry " + std::to_string(k) + " ('" + action_table[k].name + "', prop '" + action_table[k].prop +
           "') repeats an earlier entry");
    }
  }
  if (!actions.empty()) {
    if (actions.size() != T * N) {
      fail("actions hold " + std::to_string(actions.size()) + " values, expected frames × agents = " + std::to_string(T) +
           " × " + std::to_string(N));
    }
    if (action_table.empty()) fail("actions are given without an action_table naming them");
    for (std::size_t t = 0; t < T; ++t) {
      for (std::size_t n = 0; n < N; ++n) {
        const std::int32_t a = action(t, n);
        if (present(t, n) && (a < 0 || static_cast<std::size_t>(a) >= action_table.size())) {
          fail("agent " + std::to_string(ids[n]) + " at frame " + std::to_string(t) + " has action " + std::to_string(a) +
               ", expected 0.." + std::to_string(action_table.size() - 1) + " (an index into action_table)");
        }
      }
    }
  }
}

const std::vector<ActionKind>& standard_actions() {
  static const std::vector<ActionKind> table{{"walk", ""}, {"stand", ""}, {"run", ""}};
  return table;
}

std::optional<Eigen::Vector3d> path_velocity(const CrowdMotion& m, std::size_t t, std::size_t n) {
  if (!m.present(t, n)) return std::nullopt;
  if (!m.velocities.empty()) {
    const Eigen::Map<const Eigen::Vector3d> v(m.velocities.data() + m.index(t, n));
    if (v.allFinite()) return Eigen::Vector3d(v);
  }
  const bool before = t > 0 && m.present(t - 1, n);
  const bool after = t + 1 < m.frame_count() && m.present(t + 1, n);
  if (!before && !after) return std::nullopt;
  const std::size_t a = before ? t - 1 : t;
  const std::size_t b = after ? t + 1 : t;
  return Eigen::Vector3d((m.position(b, n) - m.position(a, n)) / (m.times[b] - m.times[a]));
}

// |(x, y)|: sqrt(x² + y²) where the squares neither overflow nor lose digits to underflow (every velocity a crowd
// has), std::hypot's careful scaling (several times slower) otherwise. The exporters ask this for every agent
// and frame.
namespace {
double ground_length(double x, double y) {
  const double squared = x * x + y * y;
  if (squared >= 0x1p-900 && squared <= 0x1p900) return std::sqrt(squared);
  return std::hypot(x, y);
}
}  // namespace

Eigen::Quaterniond facing_along(const Eigen::Vector3d& d) {
  const double ground = ground_length(d.x(), d.y());
  if (ground == 0.0 && d.z() == 0.0) return Eigen::Quaterniond::Identity();
  if (d.z() == 0.0) {
    // A yaw θ about +z: (w, z) = (cos θ/2, sin θ/2), the unit bisector of +x and u = (cos θ, sin θ), found without
    // trigonometry (the exporters ask this for every agent and frame). With g = |d|: g(u + x̂) = (g + x, y) is
    // along (cos θ/2, sin θ/2), but loses its digits as θ → π (x → −g), so for x < 0 the bisector comes from
    // g(u − x̂) = (x − g, y), along (−sin θ/2, cos θ/2): (w, z) along sign(y) (y, g − x). Either way the larger
    // component is h = g + |x| (no cancellation), and the pair is normalised by one square root. Branch-free (the
    // two cases are picked by selects): successive agents' directions are unpredictable, and a mispredicted branch
    // here cost more than the arithmetic.
    if (ground > 0x1p400 || ground < 0x1p-400) return facing_along(Eigen::Vector3d(d.x() / ground, d.y() / ground, 0.0));  // h² below
    const double x = d.x(), y = d.y();
    const double h = ground + std::abs(x);
    const double sign = y < 0 ? -1.0 : 1.0;  // sign of sin(θ/2) = sign of θ in (−π, π]
    const bool ahead = x >= 0;
    const double a = ahead ? h : std::abs(y), b = ahead ? y : sign * h;
    const double inverse = 1.0 / std::sqrt(h * h + y * y);
    const double w = a * inverse, z = b * inverse;
    return Eigen::Quaterniond(w, 0.0, 0.0, z);
  }
  const double yaw = ground > 0.0 ? std::atan2(d.y(), d.x()) : 0.0;
  const double pitch = std::atan2(d.z(), ground);
  // R_y(−pitch) lifts +x toward +z; R_z(yaw) then turns it about the vertical.
  return Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(-pitch, Eigen::Vector3d::UnitY()));
}

std::int32_t path_action(const CrowdMotion& m, std::size_t t, std::size_t n, const PathPoseRule& rule) {
  const auto v = path_velocity(m, t, n);
  const double speed = v ? v->norm() : 0.0;
  if (speed < rule.standing_speed) return action_stand;
  return speed >= rule.running_speed ? action_run : action_walk;
}

PathFacing::PathFacing(const CrowdMotion& motion, PathPoseRule rule)
    : motion_(motion), rule_(rule), last_(motion.agent_count(), Eigen::Quaterniond::Identity()),
      next_(motion.agent_count(), std::size_t(-1)) {}

std::optional<Eigen::Quaterniond> PathFacing::moving_facing(std::size_t t, std::size_t n) const {
  const auto v = path_velocity(motion_, t, n);
  if (!v || v->norm() < rule_.standing_speed) return std::nullopt;
  return facing_along(*v);
}

Eigen::Quaterniond PathFacing::at(std::size_t t, std::size_t n) {
  if (next_[n] != t) {
    // (Re)start: the facing before any frame is where the agent first moves (+x if it never does).
    last_[n] = Eigen::Quaterniond::Identity();
    for (std::size_t s = 0; s < motion_.frame_count(); ++s) {
      if (const auto f = moving_facing(s, n)) {
        last_[n] = *f;
        break;
      }
    }
    for (std::size_t s = 0; s < t; ++s) {
      if (const auto f = moving_facing(s, n)) last_[n] = *f;
    }
  }
  if (const auto f = moving_facing(t, n)) last_[n] = *f;
  next_[n] = t + 1;
  return last_[n];
}

}  // namespace throng
