// How far an edited clip at the source frame rate is from what the request asked, at every frame it covers.
// Independent of the solver's own check (which sees the samples only): this reads the output as a user would.
#include <throng/core/errors.h>
#include <throng/edit/edit.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

namespace throng::edit {
namespace {

struct Frames {
  std::size_t first = 0, last = 0;  // the clip's input frames
  [[nodiscard]] std::size_t absolute(Frame f) const {
    return static_cast<std::size_t>(f < 0 ? static_cast<long>(last) + 1 + f : f);
  }
  // [a, b] clamped to the clip, as the editor reads ranges (an empty range when it misses the clip).
  [[nodiscard]] std::pair<std::size_t, std::size_t> range(Frame a, Frame b) const {
    const long l = static_cast<long>(last);
    const long from = std::max(a < 0 ? l + 1 + a : a, static_cast<long>(first));
    const long to = std::min(b < 0 ? l + 1 + b : b, l);
    return from <= to ? std::pair{static_cast<std::size_t>(from), static_cast<std::size_t>(to)} : std::pair{std::size_t{1}, std::size_t{0}};
  }
};

}  // namespace

double max_request_residual(const CrowdMotion& crowd, const CrowdMotion& edited, std::size_t first_frame,
                            const Request& request) {
  if (edited.frame_count() == 0 || first_frame + edited.frame_count() > crowd.frame_count()) {
    throw std::invalid_argument("max_request_residual: the edited clip does not fit the crowd");
  }
  const Frames clip{first_frame, first_frame + edited.frame_count() - 1};
  std::unordered_map<std::int64_t, std::size_t> in_crowd, in_clip;
  for (std::size_t a = 0; a < crowd.agent_count(); ++a) in_crowd.emplace(crowd.ids[a], a);
  for (std::size_t a = 0; a < edited.agent_count(); ++a) in_clip.emplace(edited.ids[a], a);
  auto agent = [&](std::int64_t id) -> std::pair<std::size_t, std::size_t> {
    const auto c = in_crowd.find(id), e = in_clip.find(id);
    if (c == in_crowd.end() || e == in_clip.end()) {
      throw std::invalid_argument("max_request_residual: agent " + std::to_string(id) + " is not in the edited clip");
    }
    return {c->second, e->second};
  };
  auto original = [&](std::size_t frame, std::size_t a) -> Eigen::Vector2d { return crowd.position(frame, a).head<2>(); };
  auto result = [&](std::size_t frame, std::size_t a) -> Eigen::Vector2d {
    return edited.position(frame - first_frame, a).head<2>();
  };
  double worst = 0;
  auto record = [&](double value) { worst = std::max(worst, value); };

  for (const Pin& p : request.pins) {
    const auto [c, e] = agent(p.agent);
    const std::size_t f = clip.absolute(p.frame);
    record((result(f, e) - p.position.value_or(original(f, c))).norm());
  }
  for (const Drag& d : request.drags) {
    std::vector<std::pair<std::size_t, std::size_t>> agents;
    if (d.selection.agents.empty()) {
      for (std::size_t e = 0; e < edited.agent_count(); ++e) agents.push_back(agent(edited.ids[e]));
    } else {
      for (std::int64_t id : d.selection.agents) agents.push_back(agent(id));
    }
    const auto [from, to] = clip.range(d.selection.first_frame, d.selection.last_frame);
    if (from > to || agents.empty()) continue;
    Eigen::Vector2d pivot = Eigen::Vector2d::Zero();
    if (d.pivot) {
      pivot = *d.pivot;
    } else {
      for (std::size_t f = from; f <= to; ++f)
        for (const auto& [c, e] : agents) pivot += original(f, c);
      pivot /= static_cast<double>((to - from + 1) * agents.size());
    }
    const Eigen::Rotation2Dd turn(d.rotation);
    for (std::size_t f = from; f <= to; ++f) {
      for (const auto& [c, e] : agents) {
        const Eigen::Vector2d p = original(f, c);
        const Eigen::Vector2d target = d.rotation == 0.0 ? Eigen::Vector2d(p + d.offset) : Eigen::Vector2d(pivot + turn * (p - pivot) + d.offset);
        record((result(f, e) - target).norm());
      }
    }
  }
  for (const Constraint& constraint : request.constraints) {
    std::visit(
        [&](const auto& k) {
          using T = std::decay_t<decltype(k)>;
          if constexpr (std::is_same_v<T, Sum>) {
            std::vector<std::pair<std::size_t, std::size_t>> agents;
            for (std::int64_t id : k.agents) agents.push_back(agent(id));
            std::vector<double> weights = k.weights;
            if (weights.empty()) weights.assign(agents.size(), 1.0 / static_cast<double>(agents.size()));
            if (weights.size() != agents.size()) throw std::invalid_argument("max_request_residual: a sum's weights do not match its agents");
            const auto [from, to] = clip.range(k.first_frame, k.last_frame);
            for (std::size_t f = from; f <= to && from <= to; ++f) {
              Eigen::Vector2d sum = Eigen::Vector2d::Zero(), value = Eigen::Vector2d::Zero();
              for (std::size_t i = 0; i < agents.size(); ++i) {
                sum += weights[i] * result(f, agents[i].second);
                value += weights[i] * original(f, agents[i].first);
              }
              record((sum - k.value.value_or(value)).norm());
            }
          } else if constexpr (std::is_same_v<T, Row>) {
            // The distance of the output's coordinates to the row's hyperplane: |Σ c x − value| / ‖c‖.
            double sum = 0, norm2 = 0;
            for (const RowTerm& t : k.terms) {
              sum += t.coefficient * result(clip.absolute(t.frame), agent(t.agent).second)[t.axis];
              norm2 += t.coefficient * t.coefficient;
            }
            if (norm2 > 0) record(std::abs(sum - k.value) / std::sqrt(norm2));
          } else {
            const auto [ca, ea] = agent(k.agent);
            if constexpr (std::is_same_v<T, Acceleration>) {
              // The three frames the editor fits (edit.h), the row times h0 h1 (metres).
              if (clip.last < clip.first + 2) throw std::invalid_argument("max_request_residual: an acceleration in a clip of fewer than 3 frames");
              const std::size_t f1 = std::clamp(clip.absolute(k.frame), clip.first + 1, clip.last - 1);
              const std::size_t f0 = f1 - 1, f2 = f1 + 1;
              const double h0 = crowd.times[f1] - crowd.times[f0], h1 = crowd.times[f2] - crowd.times[f1];
              const double mean = 0.5 * (h0 + h1);
              const Eigen::Vector2d lhs = (h1 * result(f0, ea) - (h0 + h1) * result(f1, ea) + h0 * result(f2, ea)) / mean;
              record((lhs - k.acceleration * h0 * h1).norm());
            } else if constexpr (std::is_same_v<T, Velocity>) {
              const std::size_t f = clip.absolute(k.frame);
              const std::size_t f0 = f < clip.last ? f : f - 1, f1 = f0 + 1;
              const double dt = crowd.times[f1] - crowd.times[f0];
              record((result(f1, ea) - result(f0, ea) - k.velocity * dt).norm());
            } else {
              const auto [from, to] = clip.range(k.first_frame, k.last_frame);
              for (std::size_t f = from; f <= to && from <= to; ++f) {
                if constexpr (std::is_same_v<T, RelativePosition>) {
                  const auto [cb, eb] = agent(k.other);
                  const Eigen::Vector2d offset = k.offset.value_or(original(f, ca) - original(f, cb));
                  record((result(f, ea) - result(f, eb) - offset).norm());
                } else {
                  const Eigen::Vector2d normal = Eigen::Vector2d(-k.direction.y(), k.direction.x()).normalized();
                  record(std::abs(normal.dot(result(f, ea) - k.point)));
                }
              }
            }
          }
        },
        constraint);
  }
  return worst;
}

}  // namespace throng::edit
