// Per-agent parameters: weights (Eq. 2–3), target points (Eq. 4), correction draws (Eq. 13), avoidance
// distance (Eq. 15 as read).
#include <throng/core/errors.h>
#include <throng/core/parallel.h>
#include <throng/core/random.h>
#include <throng/sketch/sketch.h>

#include <cassert>
#include <sstream>

#include "polyline.h"

namespace throng::sketch {
namespace {

// Distances below this (metres) count as "on the stroke" (l = 0 in Eq. 2).
constexpr double on_stroke_m = 1e-12;

// Eq. 2–3 for one agent: o_i ∝ 1 / l_i², or shared equally among the strokes at l = 0. strokes: the main
// stroke, then the smoothed auxiliaries.
Eigen::RowVectorXd weights_for(const std::vector<detail::PolylineDistance>& strokes, const Eigen::Vector2d& p) {
  const auto n = static_cast<Eigen::Index>(strokes.size());
  Eigen::RowVectorXd l(n);
  for (Eigen::Index i = 0; i < n; ++i) l(i) = strokes[static_cast<std::size_t>(i)](p);
  const auto on = (l.array() <= on_stroke_m).count();
  if (on > 0) {
    return (l.array() <= on_stroke_m).cast<double>().matrix() / static_cast<double>(on);
  }
  const Eigen::RowVectorXd inverse = l.array().square().inverse();
  return inverse / inverse.sum();
}

}  // namespace

AgentParameters agent_parameters(const Course& course, const std::vector<Eigen::Vector2d>& start,
                                 const Options& options) {
  validate(options);
  for (std::size_t j = 0; j < start.size(); ++j) {
    if (!start[j].allFinite()) {
      std::ostringstream m;
      m << "sketch: initial position of agent " << j << " is (" << start[j].x() << ", " << start[j].y()
        << "), expected finite coordinates";
      throw InputError(m.str());
    }
  }
  AgentParameters a;
  a.start = start;
  a.first_target.assign(start.size(), 0);
  a.correction_draw.resize(start.size());
  a.weights.resize(static_cast<Eigen::Index>(start.size()), static_cast<Eigen::Index>(course.auxiliary_count() + 1));
  std::vector<detail::PolylineDistance> strokes{detail::PolylineDistance(course.main)};
  for (const auto& line : course.smoothed) strokes.emplace_back(line);
  // Each agent's row and draw depend on that agent only: any thread count gives the same values.
  parallel_for(start.size(), 64, [&](std::size_t begin, std::size_t end) {
    for (std::size_t j = begin; j < end; ++j) {
      a.weights.row(static_cast<Eigen::Index>(j)) = weights_for(strokes, start[j]);
      Rng rng(derive_seed(options.seed, j));
      a.correction_draw[j] = rng.uniform(0.5, 1.0);
    }
  });
  return a;
}

Eigen::Vector2d target_point(const Course& course, const AgentParameters& agents, std::size_t agent, std::size_t k) {
  assert(agent < agents.agent_count() && k < course.point_count());
  Eigen::Vector2d p = course.main[k];
  for (std::size_t i = 0; i < course.auxiliary_count(); ++i) {
    p += agents.weights(static_cast<Eigen::Index>(agent), static_cast<Eigen::Index>(i + 1)) * course.offset(i, k);
  }
  return p;
}

double avoidance_distance(const Course& course, const AgentParameters& agents, std::size_t agent, std::size_t k) {
  assert(agent < agents.agent_count() && k < course.point_count());
  return course.standard_distance[k] * (1.0 + agents.correction_draw[agent] * course.correction_scale[k]);
}

}  // namespace throng::sketch
