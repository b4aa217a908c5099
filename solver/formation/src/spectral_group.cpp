#include "spectral_group.h"

#include "dense.h"
#include "eigenbasis.h"

#include <algorithm>
#include <cassert>
#include <optional>
#include <set>

namespace throng::formation {
namespace {

// Frames evaluated per matrix product: bounds the working memory (3 · #items · d · chunk doubles).
constexpr std::size_t frames_per_chunk = 256;

Eigen::VectorXd mean_row(const Eigen::MatrixXd& points) { return points.colwise().mean().transpose(); }

}  // namespace

SpectralGroup::SpectralGroup(const GroupKeyframes& keyframes, const Options& options)
    : items_(static_cast<int>(keyframes.positions.front().rows())),
      dimension_(static_cast<int>(keyframes.positions.front().cols())),
      tension_(options.tension),
      product_(options.keyframe_product),
      sharp_(keyframes.sharp) {
  const std::size_t k_count = keyframes.positions.size();
  assert(k_count >= 2 && keyframes.anchors.size() == k_count && keyframes.edits.size() == k_count);
  assert(sharp_.empty() || sharp_.size() == k_count);

  // Graphs and eigenbases, keyframes in parallel (§3.1).
  graphs_.resize(k_count);
  std::vector<Eigenbasis> eigenbases(k_count);
  const double m = items_;
  dense::for_each(k_count, 10.0 * m * m * m + 2000.0 * m, [&](std::size_t k) {
    Adjacency graph = keyframe_graph(keyframes, k);
    eigenbases[k] = laplacian_eigenbasis(laplacian(graph));
    graphs_[k] = std::move(graph);
  });

  // Each basis aligned to the previous one (§3.2, §4.2), the previous one taken in its own eigenvalue order.
  bases_.resize(k_count);
  for (std::size_t k = 1; k < k_count; ++k) eigenbases[k] = align_basis(eigenbases[k - 1], std::move(eigenbases[k]), options.reordering);
  for (std::size_t k = 0; k < k_count; ++k) bases_[k] = std::move(eigenbases[k].vectors);

  // Orientation (PCA adjustment) and the coefficients of each keyframe in the common frame (Eq. 1).
  std::vector<Eigen::MatrixXd> centred(k_count);
  for (std::size_t k = 0; k < k_count; ++k)
    centred[k] = keyframes.positions[k].rowwise() - mean_row(keyframes.positions[k]).transpose();
  std::vector<Eigen::MatrixXd> rotations = keyframe_orientations(centred, options.orientation, options.isotropy_tolerance);
  std::vector<Eigen::MatrixXd> coefficients(k_count);
  for (std::size_t k = 0; k < k_count; ++k) {
    const Eigen::MatrixXd relative = keyframes.positions[k].rowwise() - keyframes.anchors[k].transpose();
    coefficients[k] = dense::multiply(bases_[k], true, relative * rotations[k]);
  }
  coefficients_ = CoefficientTrack(coefficients);
  orientation_ = OrientationTrack(std::move(rotations));

  // The rotations the intervals' Eq. 5 products use (between consecutive keyframes in the cumulative form; from
  // keyframe n−1 to n, n+1 and n+2 in the paper's), each decomposed once, in parallel.
  std::set<std::pair<int, int>> needed;
  for (int segment = 0; segment + 1 < static_cast<int>(k_count); ++segment)
    for (const Term& term : eq5(segment).terms) needed.insert(term.rotation);
  const std::vector<std::pair<int, int>> pairs(needed.begin(), needed.end());
  std::vector<std::optional<RotationPower>> decomposed(pairs.size());
  dense::for_each(pairs.size(), 30.0 * m * m * m, [&](std::size_t i) {
    const Eigen::MatrixXd g = dense::multiply(bases_[static_cast<std::size_t>(pairs[i].first)], true,
                                              bases_[static_cast<std::size_t>(pairs[i].second)]);
    decomposed[i].emplace(g);
  });
  for (std::size_t i = 0; i < pairs.size(); ++i) rotations_.emplace(pairs[i], std::move(*decomposed[i]));
}

SpectralGroup::Eq5 SpectralGroup::eq5(int segment) const {
  Eq5 out;
  out.keys = control_keys(segment, keyframe_count(), sharp_);
  const auto& k = out.keys.keys;
  auto add = [&](int a, int b, double sign, std::vector<int> weights) {
    if (a == b) return;
    if (!out.terms.empty() && out.terms.back().rotation == std::make_pair(a, b) && out.terms.back().sign == sign) {
      // The same rotation twice in a row (the paper's form at the last interval: n+2 duplicated as n+1): one
      // power with the exponents summed.
      out.terms.back().weights.insert(out.terms.back().weights.end(), weights.begin(), weights.end());
      return;
    }
    out.terms.push_back(Term{{a, b}, sign, std::move(weights)});
  };
  if (product_ == KeyframeProduct::cumulative) {
    // With R0, R1, R2 the rotations n−1→n, n→n+1, n+1→n+2 and the spline weights c−1..c2 (summing to 1),
    // M(t) = R2^{c2} R1^{c1+c2} R0^{c0+c1+c2} M_{n−1}, the rotational analogue of
    // p(t) = p_{n−1} + (c0+c1+c2)(p_n − p_{n−1}) + (c1+c2)(p_{n+1} − p_n) + c2(p_{n+2} − p_{n+1}). Written in
    // the keyframes' own bases (R0^{c0+c1+c2} M_{n−1} = R0^{−c−1} M_n, and so on):
    //   M(t) = M_{n+1} · G_{n+1,n+2}^{c2} · G_{n,n+1}^{−(c−1+c0)} · G_{n−1,n}^{−c−1}.
    // It equals the paper's (R2R1R0)^{c2} (R1R0)^{c1} R0^{c0} M_{n−1} when the rotations commute (always for two
    // keyframes), but every power is of a rotation between CONSECUTIVE keyframes: the paper's powers of products
    // take the principal logarithm of R1R0 and R2R1R0, which swings the basis the other way round once the
    // rotations add up past π in a plane, and for rotations that do not commute leaves the path between M_n and
    // M_{n+1} even at τ = 0. This is also the form of the 2-D coefficient and orientation splines (angles
    // unwrapped between consecutive keyframes).
    out.base = k[2];
    add(k[0], k[1], -1.0, {0});     // G_{n−1,n}^{−c−1}
    add(k[1], k[2], -1.0, {0, 1});  // G_{n,n+1}^{−(c−1+c0)}
    add(k[2], k[3], 1.0, {3});      // G_{n+1,n+2}^{c2}
  } else {
    // Eq. 5 as printed, M(t) = (R2R1R0)^{c2} (R1R0)^{c1} (R0)^{c0} M_{n−1}. R0 = M_n M_{n−1}ᵀ, R1R0 =
    // M_{n+1} M_{n−1}ᵀ, R2R1R0 = M_{n+2} M_{n−1}ᵀ, and (M_b M_aᵀ)^c = M_a G_{a,b}^c M_aᵀ, so
    //   M(t) = M_{n−1} · G_{n−1,n+2}^{c2} · G_{n−1,n+1}^{c1} · G_{n−1,n}^{c0}.
    // Every G_{a,b} has det +1 (a product of the consecutive ones, each made +1 by the alignment).
    out.base = k[0];
    add(k[0], k[1], 1.0, {1});  // G_{n−1,n}^{c0}
    add(k[0], k[2], 1.0, {2});  // G_{n−1,n+1}^{c1}
    add(k[0], k[3], 1.0, {3});  // G_{n−1,n+2}^{c2}
  }
  return out;
}

SpectralGroup::IntervalPlan SpectralGroup::plan_interval(int segment) const {
  const Eq5 equation = eq5(segment);
  IntervalPlan plan;
  plan.keys = equation.keys;
  for (const Term& term : equation.terms) {
    const RotationPower& rotation = rotations_.at(term.rotation);
    if (rotation.is_identity()) continue;
    plan.factors.push_back(Factor{&rotation, term.sign, term.weights});
  }
  for (std::size_t i = 1; i < plan.factors.size(); ++i)
    plan.links.push_back(dense::multiply(plan.factors[i].rotation->basis(), true, plan.factors[i - 1].rotation->basis()));
  const Eigen::MatrixXd& base = bases_[static_cast<std::size_t>(equation.base)];
  plan.final = plan.factors.empty() ? base : dense::multiply(base, false, plan.factors.back().rotation->basis());
  plan.coefficients = coefficients_.interval(plan.keys);
  return plan;
}

Eigen::MatrixXd SpectralGroup::apply_chain(const IntervalPlan& plan, const Eigen::MatrixXd& c,
                                           const std::vector<SplineWeights>& weights, int group) const {
  if (plan.factors.empty()) return dense::multiply(plan.final, false, c);
  auto exponents = [&](const Factor& factor) {
    std::vector<double> out(weights.size(), 0.0);
    for (std::size_t f = 0; f < weights.size(); ++f)
      for (int i : factor.weights) out[f] += factor.sign * weights[f].c[static_cast<std::size_t>(i)];
    return out;
  };
  Eigen::MatrixXd w = dense::multiply(plan.factors.front().rotation->basis(), true, c);
  plan.factors.front().rotation->rotate(w, exponents(plan.factors.front()), group);
  for (std::size_t i = 1; i < plan.factors.size(); ++i) {
    w = dense::multiply(plan.links[i - 1], false, w);
    plan.factors[i].rotation->rotate(w, exponents(plan.factors[i]), group);
  }
  return dense::multiply(plan.final, false, w);
}

Eigen::MatrixXd SpectralGroup::evaluate(const Timeline& timeline, const Eigen::MatrixXd& anchor_path) const {
  const std::size_t frames = timeline.frame_count();
  const int d = dimension_;
  assert(anchor_path.rows() == d && static_cast<std::size_t>(anchor_path.cols()) == frames);
  Eigen::MatrixXd out(static_cast<Eigen::Index>(items_) * d, static_cast<Eigen::Index>(frames));
  std::size_t first = 0;
  while (first < frames) {
    const int segment = timeline.segment[first];
    std::size_t end = first;
    while (end < frames && timeline.segment[end] == segment) ++end;
    const IntervalPlan plan = plan_interval(segment);
    for (std::size_t chunk = first; chunk < end; chunk += frames_per_chunk) {
      const std::size_t count = std::min(frames_per_chunk, end - chunk);
      std::vector<SplineWeights> weights(count);
      Eigen::MatrixXd c(items_, static_cast<Eigen::Index>(count) * d);
      dense::for_each(count, (dimension_ == 3 ? 200.0 : 60.0) * items_, [&](std::size_t f) {
        weights[f] = catmull_rom_weights(timeline.local[chunk + f], tension_);
        Eigen::MatrixXd local(items_, d);
        coefficients_.evaluate(plan.coefficients, weights[f], local);
        const Eigen::MatrixXd rotation = orientation_.evaluate(plan.keys, weights[f]);
        c.middleCols(static_cast<Eigen::Index>(f) * d, d) = local * rotation.transpose();
      });
      const Eigen::MatrixXd x = apply_chain(plan, c, weights, d);
      for (std::size_t f = 0; f < count; ++f) {
        const auto column = static_cast<Eigen::Index>(chunk + f);
        for (int j = 0; j < items_; ++j)
          for (int axis = 0; axis < d; ++axis)
            out(static_cast<Eigen::Index>(j) * d + axis, column) =
                x(j, static_cast<Eigen::Index>(f) * d + axis) + anchor_path(axis, column);
      }
    }
    first = end;
  }
  return out;
}

Eigen::MatrixXd SpectralGroup::eigenbasis_at(int segment, double t) const {
  const IntervalPlan plan = plan_interval(segment);
  return apply_chain(plan, Eigen::MatrixXd::Identity(items_, items_), {catmull_rom_weights(t, tension_)}, items_);
}

}  // namespace throng::formation
