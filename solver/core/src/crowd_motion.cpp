#include <throng/core/crowd_motion.h>
#include <throng/core/errors.h>

#include <algorithm>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
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

namespace {

// facing_along's ground case for `count` velocities (num_x / den, num_y / den): w and z of the yaw quaternion,
// whether the speed is at least `standing` (moving: !(speed < standing), as PathFacing's rule) and whether it lies
// in facing_along's direct range (else its value must come from facing_along itself). v.norm() and
// ground_length(x, y) are both sqrt(x² + y²) there (z is 0). Two agents at a time in SSE2 registers where the
// processor has them: the square roots and divisions, most of the time, run two at once, and every operation is
// the scalar one (IEEE-exact), so the values are facing_along's bit for bit.
void ground_facings(const double* num_x, const double* num_y, const double* den, std::size_t count, double standing,
                    double* w, double* z, unsigned char* moving, unsigned char* in_range) {
  std::size_t k = 0;
#if defined(__SSE2__)
  const __m128d sign_bit = _mm_set1_pd(-0.0), one = _mm_set1_pd(1.0), minus_one = _mm_set1_pd(-1.0), zero = _mm_setzero_pd();
  const __m128d low = _mm_set1_pd(0x1p-400), high = _mm_set1_pd(0x1p400), slow = _mm_set1_pd(standing);
  const auto select = [](__m128d mask, __m128d a, __m128d b) { return _mm_or_pd(_mm_and_pd(mask, a), _mm_andnot_pd(mask, b)); };
  for (; k + 2 <= count; k += 2) {
    const __m128d d = _mm_loadu_pd(den + k);
    const __m128d x = _mm_div_pd(_mm_loadu_pd(num_x + k), d), y = _mm_div_pd(_mm_loadu_pd(num_y + k), d);
    const __m128d ground = _mm_sqrt_pd(_mm_add_pd(_mm_mul_pd(x, x), _mm_mul_pd(y, y)));
    const int range = _mm_movemask_pd(_mm_and_pd(_mm_cmpge_pd(ground, low), _mm_cmple_pd(ground, high)));
    const int move = _mm_movemask_pd(_mm_cmpnlt_pd(ground, slow));
    const __m128d h = _mm_add_pd(ground, _mm_andnot_pd(sign_bit, x));
    const __m128d sign = select(_mm_cmplt_pd(y, zero), minus_one, one);
    const __m128d ahead = _mm_cmpge_pd(x, zero);
    const __m128d a = select(ahead, h, _mm_andnot_pd(sign_bit, y)), b = select(ahead, y, _mm_mul_pd(sign, h));
    const __m128d inverse = _mm_div_pd(one, _mm_sqrt_pd(_mm_add_pd(_mm_mul_pd(h, h), _mm_mul_pd(y, y))));
    _mm_storeu_pd(w + k, _mm_mul_pd(a, inverse));
    _mm_storeu_pd(z + k, _mm_mul_pd(b, inverse));
    moving[k] = move & 1, moving[k + 1] = (move >> 1) & 1;
    in_range[k] = range & 1, in_range[k + 1] = (range >> 1) & 1;
  }
#endif
  for (; k < count; ++k) {
    const double x = num_x[k] / den[k], y = num_y[k] / den[k];
    const double ground = std::sqrt(x * x + y * y);
    in_range[k] = ground >= 0x1p-400 && ground <= 0x1p400;
    moving[k] = !(ground < standing);
    const double h = ground + std::abs(x);
    const double sign = y < 0 ? -1.0 : 1.0;
    const bool ahead = x >= 0;
    const double a = ahead ? h : std::abs(y), b = ahead ? y : sign * h;
    const double inverse = 1.0 / std::sqrt(h * h + y * y);
    w[k] = a * inverse;
    z[k] = b * inverse;
  }
}

}  // namespace

void PathFacing::at_frame(std::size_t t, std::size_t first, std::size_t last, Eigen::Quaterniond* out) {
  // Batches of agents in three passes: their velocities as path_velocity has them (a difference of positions and
  // the time between, or the given velocity over 1), then facing_along's ground case for all of them
  // (ground_facings), then the state update. What the ground case does not cover (a first or replayed frame, no
  // velocity, a vertical component, a speed outside facing_along's direct range) goes through at(): the same
  // values either way, bit for bit.
  constexpr std::size_t batch = 64;
  const CrowdMotion& m = motion_;
  const std::size_t T = m.frame_count();
  const bool given = !m.velocities.empty();
  double num_x[batch], num_y[batch], den[batch], w[batch], z[batch];
  unsigned char ground[batch], moving[batch], in_range[batch];
  // The positions the next frame's call reads last (frame t + 2's): a caller that walks a few agents through
  // every frame (the glTF export) strides a whole frame from one call to the next, where the processor's own
  // prefetching does not follow, and waited on memory for most of its time here (a glTF export of 10,000 agents ×
  // 1,000 frames: 0.35-0.36 -> 0.29-0.30 s). Not for long ranges: a caller walking whole frames reads memory in
  // order, which the processor prefetches itself (a frame of 10,000 agents: 5 % slower with these).
  if (t + 2 < T && last > first && last - first <= 1024) {
    const auto* from = reinterpret_cast<const char*>(m.positions.data() + m.index(t + 2, first));
    const auto* to = reinterpret_cast<const char*>(m.positions.data() + m.index(t + 2, last));
    for (; from < to; from += 64) __builtin_prefetch(from);
  }
  for (std::size_t b0 = first; b0 < last; b0 += batch) {
    const std::size_t count = std::min(batch, last - b0);
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t n = b0 + k;
      ground[k] = 0;
      num_x[k] = num_y[k] = 0.0;
      den[k] = 1.0;
      if (next_[n] != t || !m.present(t, n)) continue;
      if (given) {
        const double* g = m.velocities.data() + m.index(t, n);
        if (std::isfinite(g[0]) && std::isfinite(g[1]) && std::isfinite(g[2])) {
          num_x[k] = g[0], num_y[k] = g[1];  // over 1: exactly the given velocity
          ground[k] = g[2] == 0.0;
          continue;
        }
      }
      const bool before = t > 0 && m.present(t - 1, n);
      const bool after = t + 1 < T && m.present(t + 1, n);
      if (!before && !after) continue;
      const std::size_t a = before ? t - 1 : t, b = after ? t + 1 : t;
      const double dt = m.times[b] - m.times[a];
      const double* pa = m.positions.data() + m.index(a, n);
      const double* pb = m.positions.data() + m.index(b, n);
      const double climb = pb[2] - pa[2];
      ground[k] = climb == 0.0 || climb / dt == 0.0;  // path_velocity's z, 0 (an underflow too: facing_along's test)
      num_x[k] = pb[0] - pa[0], num_y[k] = pb[1] - pa[1];
      den[k] = dt;
    }
    ground_facings(num_x, num_y, den, count, rule_.standing_speed, w, z, moving, in_range);
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t n = b0 + k;
      if (!ground[k] || !in_range[k]) {
        out[n - first] = at(t, n);
        continue;
      }
      if (moving[k]) last_[n] = Eigen::Quaterniond(w[k], 0.0, 0.0, z[k]);
      next_[n] = t + 1;
      out[n - first] = last_[n];
    }
  }
}

}  // namespace throng
