// deform_with_features: the Editor's two least-squares steps (systems.h) over caller-made features and pins.
#include "systems.h"

#include <throng/core/timer.h>
#include <throng/core/errors.h>
#include <throng/edit/feature_deformation.h>
#include <throng/linalg/least_squares.h>

#include <chrono>
#include <cmath>
#include <utility>

namespace throng::edit {
namespace {

using Index = Eigen::Index;
using Positions = Eigen::Matrix<double, Eigen::Dynamic, 2>;
using Clock = std::chrono::steady_clock;



}  // namespace

FeatureDeformation deform_with_features(const FeatureSet& features, const Eigen::Ref<const Positions>& original,
                                        const std::vector<Index>& pinned, const Eigen::Ref<const Positions>& targets,
                                        const FeatureWeights& weights, const linalg::SolverOptions& solver) {
  for (auto [name, value] : {std::pair{"alpha", weights.alpha}, std::pair{"beta", weights.beta},
                             std::pair{"alpha_prime", weights.alpha_prime}, std::pair{"beta_prime", weights.beta_prime}}) {
    if (!std::isfinite(value) || value < 0) {
      throw ConfigError(std::string(name) + " " + std::to_string(value) + ": expected a finite weight ≥ 0");
    }
  }
  if (targets.rows() != static_cast<Index>(pinned.size())) {
    throw std::invalid_argument("deform_with_features: " + std::to_string(targets.rows()) + " targets for " +
                                std::to_string(pinned.size()) + " pinned vertices");
  }
  const Index vertices = original.rows();
  FeatureDeformation out;
  auto start = Clock::now();
  const Eigen::MatrixXd modes = similarity_modes(original);
  std::vector<Index> unknowns;
  unknowns.reserve(2 * pinned.size());
  Eigen::VectorXd pin_values(static_cast<Index>(2 * pinned.size()));
  for (std::size_t k = 0; k < pinned.size(); ++k) {
    unknowns.push_back(2 * pinned[k]);
    unknowns.push_back(2 * pinned[k] + 1);
    pin_values[static_cast<Index>(2 * k)] = targets(static_cast<Index>(k), 0);
    pin_values[static_cast<Index>(2 * k + 1)] = targets(static_cast<Index>(k), 1);
  }
  const Eigen::VectorXd no_constraints(0);

  Objective step1 = step1_objective(features, vertices, weights.alpha, weights.beta);
  out.assemble_seconds = seconds_since(start);

  // One solve per step, one after the other: step 1's factor (and objective) is released before step 2's is
  // built, so the peak memory is one factor, not two (the Editor keeps both for its drags; a one-shot solve
  // need not). The results are the same as factoring both first.
  auto solve_step = [&](const Objective& o, const Eigen::VectorXd& b, bool first) {
    linalg::ConstrainedLeastSquares s(solver);
    auto t = Clock::now();
    s.set_objective(o.A, o.weights);
    s.set_pinned(unknowns);
    s.set_near_null_space(modes, 2);
    s.set_complex_pairs(true);  // every feature row is complex-linear in (x, y) pairs
    s.precompute();
    out.precompute_seconds += seconds_since(t);
    if (first) out.factorization = s.report().factorization.method;
    t = Clock::now();
    Eigen::MatrixXd x = s.solve(b, pin_values, no_constraints);
    out.solve_seconds += seconds_since(t);
    return x;
  };
  out.step1 = as_positions(solve_step(step1, step1.b, true));
  step1 = Objective{};
  if (weights.scale_compensation) {
    start = Clock::now();
    Objective step2 = step2_objective(features, vertices, weights.alpha_prime, weights.beta_prime);
    set_step2_targets(features, original, out.step1, step2.b);
    out.assemble_seconds += seconds_since(start);
    out.positions = as_positions(solve_step(step2, step2.b, false));
  } else {
    out.positions = out.step1;
  }
  return out;
}

}  // namespace throng::edit
