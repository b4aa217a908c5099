#include <throng/core/facing_carry.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <vector>

namespace throng {
namespace {

// x wrapped to (−π, π].
double wrapped(double x) {
  x = std::remainder(x, 2.0 * std::numbers::pi);
  return x <= -std::numbers::pi ? x + 2.0 * std::numbers::pi : x;
}

bool is_standard(const ActionKind& kind) {
  return kind.prop.empty() && (kind.name == "walk" || kind.name == "stand" || kind.name == "run");
}

// The standard speed class of a path speed (path_action's rule).
StandardAction speed_class(const std::optional<Eigen::Vector3d>& v, const PathPoseRule& rule) {
  const double speed = v ? v->norm() : 0.0;
  if (speed < rule.standing_speed) return action_stand;
  return speed >= rule.running_speed ? action_run : action_walk;
}

// The index of the standard class `c` in `table`, appended when missing.
std::int32_t table_index(std::vector<ActionKind>& table, StandardAction c) {
  const ActionKind& kind = standard_actions()[static_cast<std::size_t>(c)];
  const auto at = std::find(table.begin(), table.end(), kind);
  if (at != table.end()) return static_cast<std::int32_t>(at - table.begin());
  table.push_back(kind);
  return static_cast<std::int32_t>(table.size() - 1);
}

}  // namespace

Eigen::Quaterniond turned_by_yaw(const Eigen::Quaterniond& q, double yaw) {
  return (Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())) * q).normalized();
}

double yaw_change(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  return wrapped(std::atan2(to.y(), to.x()) - std::atan2(from.y(), from.x()));
}

void carry_facing(const CrowdMotion& before, CrowdMotion& after, const CarriedSpan& span, const PathPoseRule& rule) {
  const bool facing = !before.orientations.empty() && !after.orientations.empty();
  const bool acting = !before.actions.empty() && !after.actions.empty();
  if ((!facing && !acting) || span.last < span.first || span.last >= after.frame_count()) return;
  const std::size_t L = span.last - span.first + 1;
  const std::size_t a = span.after_agent, b = span.before_agent;
  auto source_frame = [&](std::size_t f) -> std::optional<std::size_t> {
    const auto s = static_cast<std::ptrdiff_t>(f) + span.frame_offset;
    if (s < 0 || static_cast<std::size_t>(s) >= before.frame_count()) return std::nullopt;
    return static_cast<std::size_t>(s);
  };

  // Per frame of the span: the facing's turn where the agent moves in both (NaN elsewhere), and the speed classes.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> turn(L, nan);
  for (std::size_t i = 0; i < L; ++i) {
    const std::size_t f = span.first + i;
    const auto s = source_frame(f);
    if (!s || !after.present(f, a) || !before.present(*s, b)) continue;
    const auto vb = path_velocity(before, *s, b);
    const auto va = path_velocity(after, f, a);
    if (acting) {
      const std::int32_t input = before.action(*s, b);
      const bool known = input >= 0 && static_cast<std::size_t>(input) < before.action_table.size();
      after.action(f, a) = known && span.action_map ? (*span.action_map)[static_cast<std::size_t>(input)] : input;
      const StandardAction cb = speed_class(vb, rule), ca = speed_class(va, rule);
      if (known && is_standard(before.action_table[static_cast<std::size_t>(input)]) && ca != cb) {
        after.action(f, a) = table_index(after.action_table, ca);
      }
    }
    if (vb && va && vb->head<2>().norm() >= rule.standing_speed && va->head<2>().norm() >= rule.standing_speed) {
      turn[i] = span.rotation + wrapped(yaw_change(*vb, *va) - span.rotation);
    }
  }
  if (!facing) return;

  // Standing frames take the turn of the nearest moving frame (the earlier on a tie); none: the rigid rotation.
  std::vector<std::size_t> previous(L, L), next(L, L);
  for (std::size_t i = 0, last = L; i < L; ++i) {
    if (!std::isnan(turn[i])) last = i;
    previous[i] = last;
  }
  for (std::size_t i = L, last = L; i-- > 0;) {
    if (!std::isnan(turn[i])) last = i;
    next[i] = last;
  }
  for (std::size_t i = 0; i < L; ++i) {
    const std::size_t f = span.first + i;
    const auto s = source_frame(f);
    if (!s || !after.present(f, a)) continue;
    double yaw = span.rotation;
    if (!std::isnan(turn[i])) {
      yaw = turn[i];
    } else if (previous[i] < L && (next[i] == L || i - previous[i] <= next[i] - i)) {
      yaw = turn[previous[i]];
    } else if (next[i] < L) {
      yaw = turn[next[i]];
    }
    const Eigen::Quaterniond q = before.orientation(*s, b);
    if (!before.present(*s, b) || !std::isfinite(q.w()) || q.norm() == 0.0) continue;
    after.orientation(f, a) = turned_by_yaw(q, yaw);
  }
  // From the frame before the span (a clip's seam) on: no faster than a person turns.
  if (std::isfinite(span.max_turn_rate))
    limit_facing_rate(after, a, span.first > 0 ? span.first - 1 : 0, span.first + L - 1, span.max_turn_rate);
}

void limit_facing_rate(CrowdMotion& motion, std::size_t agent, std::size_t first, std::size_t last, double max_rate) {
  if (motion.orientations.empty()) return;
  last = std::min(last, motion.frame_count() - 1);
  for (std::size_t f = first + 1; f <= last && f > first; ++f) {
    if (!motion.present(f, agent) || !motion.present(f - 1, agent)) continue;
    const Eigen::Quaterniond from = motion.orientation(f - 1, agent), to = motion.orientation(f, agent);
    const double turn = from.angularDistance(to);
    const double allowed = max_rate * (motion.times[f] - motion.times[f - 1]);
    if (turn > allowed) motion.orientation(f, agent) = from.slerp(allowed / turn, to).normalized();
  }
}

void limit_facing_rate(CrowdMotion& motion, double max_rate) {
  if (motion.orientations.empty() || motion.frame_count() == 0) return;
  for (std::size_t n = 0; n < motion.agent_count(); ++n) limit_facing_rate(motion, n, 0, motion.frame_count() - 1, max_rate);
}

void derive_path_pose(CrowdMotion& m, const PathPoseRule& rule) {
  const std::size_t T = m.frame_count(), N = m.agent_count();
  if (m.orientations.empty()) {
    m.orientations.assign(T * N * 4, absent);
    PathFacing facing(m, rule);  // reads positions and velocities only
    for (std::size_t n = 0; n < N; ++n) {
      for (std::size_t t = 0; t < T; ++t) {
        if (m.present(t, n)) m.orientation(t, n) = facing.at(t, n);
      }
    }
  }
  if (m.actions.empty()) {
    m.action_table = standard_actions();
    m.actions.assign(T * N, -1);
    for (std::size_t t = 0; t < T; ++t) {
      for (std::size_t n = 0; n < N; ++n) {
        if (m.present(t, n)) m.action(t, n) = path_action(m, t, n, rule);
      }
    }
  }
}

std::vector<std::int32_t> merge_action_tables(const std::vector<ActionKind>& from, std::vector<ActionKind>& into) {
  std::vector<std::int32_t> map;
  map.reserve(from.size());
  for (const ActionKind& kind : from) {
    const auto index = static_cast<std::size_t>(std::find(into.begin(), into.end(), kind) - into.begin());
    if (index == into.size()) into.push_back(kind);
    map.push_back(static_cast<std::int32_t>(index));
  }
  return map;
}

void carry_facing_same_frames(const CrowdMotion& before, CrowdMotion& after, const std::vector<std::size_t>& changed_agents,
                              const PathPoseRule& rule, double max_turn_rate) {
  after.orientations = before.orientations;
  after.actions = before.actions;
  after.action_table = before.action_table;
  if ((before.orientations.empty() && before.actions.empty()) || after.frame_count() == 0) return;
  auto carry = [&](std::size_t agent) {
    CarriedSpan span{agent, agent, 0, after.frame_count() - 1, 0, 0.0};
    span.max_turn_rate = max_turn_rate;
    carry_facing(before, after, span, rule);
  };
  for (std::size_t n : changed_agents) carry(n);
}

}  // namespace throng
