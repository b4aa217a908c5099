#include "facing.h"

#include "dense.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace throng::formation {
namespace {

// The chord of the window around frame f: its velocity and (3-D) acceleration.
struct Chord {
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d acceleration = Eigen::Vector3d::Zero();
};

class TravelWindow {
 public:
  TravelWindow(const CrowdMotion& motion, std::size_t half) : m_(motion), half_(half) {}

  [[nodiscard]] Chord at(std::size_t f, std::size_t n) const {
    const std::size_t last = m_.frame_count() - 1;
    const std::size_t width = std::min(2 * half_, last);
    const std::size_t a = std::min(f > half_ ? f - half_ : 0, last - width);
    const std::size_t b = a + width;
    Chord c;
    const Eigen::Vector3d pa = m_.position(a, n), pb = m_.position(b, n);
    c.velocity = (pb - pa) / (m_.times[b] - m_.times[a]);
    if (b - a >= 2) {
      const std::size_t mid = a + (b - a) / 2;
      const Eigen::Vector3d pm = m_.position(mid, n);
      const Eigen::Vector3d v0 = (pm - pa) / (m_.times[mid] - m_.times[a]);
      const Eigen::Vector3d v1 = (pb - pm) / (m_.times[b] - m_.times[mid]);
      c.acceleration = 2.0 * (v1 - v0) / (m_.times[b] - m_.times[a]);
    }
    return c;
  }

 private:
  const CrowdMotion& m_;
  std::size_t half_;
};

// Along the chord, rolled into the turn in 3-D (see the file comment).
Eigen::Quaterniond travel_orientation(const Chord& c, int dimension, const FacingOptions& o) {
  const Eigen::Quaterniond q = facing_along(c.velocity);
  if (dimension != 3 || !o.bank) return q;
  const Eigen::Vector3d left = q * Eigen::Vector3d::UnitY();
  const double bank = std::atan2(c.acceleration.dot(left), o.gravity_mps2);
  // Rolling about the body's forward axis by −bank lowers the wing on the inside of the turn.
  return (q * Eigen::Quaterniond(Eigen::AngleAxisd(-bank, Eigen::Vector3d::UnitX()))).normalized();
}

}  // namespace

void fill_facings(CrowdMotion& m, const Timeline& timeline, const std::vector<std::vector<Eigen::Quaterniond>>& given,
                  int dimension, const FacingOptions& o) {
  const std::size_t T = m.frame_count(), N = m.agent_count();
  m.orientations.assign(T * N * 4, 0.0);
  m.actions.assign(T * N, action_stand);
  m.action_table = standard_actions();
  // Half the window in frames: the frame rate of the timeline's first interval (intervals differ by rounding).
  const double step = T > 1 ? (timeline.times[1] - timeline.times[0]) : 1.0;
  const auto half = static_cast<std::size_t>(std::max(1.0, std::round(0.5 * o.smoothing_s / step)));
  const TravelWindow window(m, half);
  dense::for_each(N, 400.0 * static_cast<double>(T), [&](std::size_t n) {
    // Travel facing with the standing rule; the facing before the first frame of motion is that frame's.
    std::optional<Eigen::Quaterniond> last;
    for (std::size_t f = 0; f < T && !last; ++f) {
      const Chord c = window.at(f, n);
      if (c.velocity.norm() >= o.rule.standing_speed) last = travel_orientation(c, dimension, o);
    }
    Eigen::Quaterniond facing = last.value_or(Eigen::Quaterniond::Identity());
    for (std::size_t f = 0; f < T; ++f) {
      const Chord c = window.at(f, n);
      const double speed = c.velocity.norm();
      if (speed >= o.rule.standing_speed) {
        // Toward the travel orientation, by at most max_turn_rate over the frame interval.
        const Eigen::Quaterniond target = travel_orientation(c, dimension, o);
        const double turn = facing.angularDistance(target);
        const double allowed = f > 0 ? o.max_turn_rate_rad_s * (m.times[f] - m.times[f - 1]) : turn;
        facing = turn <= allowed ? target : facing.slerp(allowed / turn, target).normalized();
      }
      m.action(f, n) = speed < o.rule.standing_speed ? action_stand : speed >= o.rule.running_speed ? action_run : action_walk;
      const auto s = static_cast<std::size_t>(timeline.segment[f]);
      const double u = timeline.local[f];
      const std::vector<Eigen::Quaterniond>& g0 = given[s];
      const std::vector<Eigen::Quaterniond>& g1 = given[s + 1];
      Eigen::Quaterniond q = facing;
      if (!g0.empty() && u == 0.0) q = g0[n];
      else if (!g1.empty() && u == 1.0) q = g1[n];
      else if (!g0.empty() && !g1.empty()) q = g0[n].slerp(u, g1[n]);
      else if (!g0.empty()) q = g0[n].slerp(u, facing);
      else if (!g1.empty()) q = facing.slerp(u, g1[n]);
      m.orientation(f, n) = q;
    }
  });
}

}  // namespace throng::formation
