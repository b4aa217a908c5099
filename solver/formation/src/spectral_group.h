// The spectral method on one group of items (§3, §4.1–4.2): analysis of the keyframes, then positions for any
// frames. Flat formations are one group; a hierarchy runs one per tree node.
#pragma once

#include "adjacency.h"
#include "coefficient_track.h"
#include "group_keyframes.h"
#include "orientation.h"
#include "rotation_power.h"
#include "spline.h"

#include <throng/formation/formation.h>

#include <Eigen/Core>

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace throng::formation {

/// The spectral method (Interpolation::spectral).
class SpectralGroup final : public GroupInterpolation {
 public:
  /// Analysis: graphs, eigenbases, alignment, rotations, coefficient and orientation tracks. Throws InputError /
  /// ConfigError for bad graphs and edits (see formation.h).
  SpectralGroup(const GroupKeyframes& keyframes, const Options& options);

  [[nodiscard]] int item_count() const noexcept { return items_; }
  [[nodiscard]] int dimension() const noexcept { return dimension_; }
  [[nodiscard]] int keyframe_count() const noexcept { return static_cast<int>(bases_.size()); }

  [[nodiscard]] Eigen::MatrixXd evaluate(const Timeline& timeline, const Eigen::MatrixXd& anchor_path) const override;

  /// M(t) (#items by #items) in interval `segment` at parameter t ∈ [0, 1]: the interpolated eigenbasis.
  [[nodiscard]] Eigen::MatrixXd eigenbasis_at(int segment, double t) const;
  /// The aligned eigenbasis of keyframe k (M_k).
  [[nodiscard]] const Eigen::MatrixXd& aligned_basis(int k) const { return bases_[static_cast<std::size_t>(k)]; }
  [[nodiscard]] const Adjacency& graph(int k) const override { return graphs_[static_cast<std::size_t>(k)]; }

 private:
  // The product chain of one interval: x = final · U_last(c) · links... · U_1(c) · first_transposedᵀ · C.
  struct Factor {
    const RotationPower* rotation = nullptr;
    double sign = 1.0;         // exponent = sign · Σ c[weights]
    std::vector<int> weights;  // indices into SplineWeights::c summed into this factor's exponent
  };
  struct IntervalPlan {
    ControlKeys keys;
    std::vector<Factor> factors;
    std::vector<Eigen::MatrixXd> links;  // links[i] = Z_{i+1}ᵀ Z_i, for i + 1 < factors.size()
    Eigen::MatrixXd final;               // M_base Z_last, or M_base without factors
    CoefficientTrack::Interval coefficients;
  };
  [[nodiscard]] IntervalPlan plan_interval(int segment) const;
  // w (#items by group·frames) ← chain applied to coefficient columns `c`; exponents per frame per factor.
  [[nodiscard]] Eigen::MatrixXd apply_chain(const IntervalPlan& plan, const Eigen::MatrixXd& c,
                                            const std::vector<SplineWeights>& weights, int group) const;

  // Interval `segment`'s Eq. 5 (Options::keyframe_product): M(t) = M_base · ... · G_{a,b}^{sign · Σ c[weights]}
  // · ..., the terms listed in the order they apply to the coefficients (rightmost first); a term with a = b
  // (a duplicated keyframe: the identity) is left out.
  struct Term {
    std::pair<int, int> rotation;  // (a, b): G_{a,b} = M_aᵀ M_b
    double sign = 1.0;
    std::vector<int> weights;
  };
  struct Eq5 {
    ControlKeys keys;
    int base = 0;
    std::vector<Term> terms;
  };
  [[nodiscard]] Eq5 eq5(int segment) const;

  int items_ = 0;
  int dimension_ = 2;
  double tension_ = 0.5;
  KeyframeProduct product_ = KeyframeProduct::cumulative;
  std::vector<bool> sharp_;
  std::vector<Adjacency> graphs_;
  std::vector<Eigen::MatrixXd> bases_;                     // M_k
  std::map<std::pair<int, int>, RotationPower> rotations_;  // G_{a,b} = M_aᵀ M_b for every pair an interval uses
  CoefficientTrack coefficients_;
  OrientationTrack orientation_;
};

}  // namespace throng::formation
