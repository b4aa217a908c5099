// The spectral method on one group of items (§3, §4.1–4.2): analysis of the keyframes, then positions for any
// frames. Flat formations are one group; a hierarchy runs one per tree node.
#pragma once

#include "adjacency.h"
#include "coefficient_track.h"
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

/// One group's keyframes.
///   positions   K matrices #items by d (d = 2 or 3): the items (individuals, or subgroup barycentres)
///   anchors     K vectors of d: the group's reference point (its barycentre over all its individuals)
///   edits       K lists of graph edits on item indices
///   what        the group in messages ("formation", "group 'brass'"); item_names: "individual 7", ...
///   places      K: where each keyframe was given (Keyframe::where), in front of messages about its graph
struct GroupKeyframes {
  std::vector<Eigen::MatrixXd> positions;
  std::vector<Eigen::VectorXd> anchors;
  std::vector<std::vector<EdgeEdit>> edits;
  std::string what;
  std::vector<std::string> item_names;
  std::vector<std::string> places;
};

class SpectralGroup {
 public:
  /// Analysis: graphs, eigenbases, alignment, rotations, coefficient and orientation tracks. Throws InputError /
  /// ConfigError for bad graphs and edits (see formation.h).
  SpectralGroup(const GroupKeyframes& keyframes, const Options& options);

  [[nodiscard]] int item_count() const noexcept { return items_; }
  [[nodiscard]] int dimension() const noexcept { return dimension_; }
  [[nodiscard]] int keyframe_count() const noexcept { return static_cast<int>(bases_.size()); }

  /// Item positions at every frame of `timeline`, given the anchor's path (d by #frames):
  /// returns #items·d by #frames, column f = frame f's items, item-major (item j's coordinates at rows j·d...).
  [[nodiscard]] Eigen::MatrixXd evaluate(const Timeline& timeline, const Eigen::MatrixXd& anchor_path) const;

  /// M(t) (#items by #items) in interval `segment` at parameter t ∈ [0, 1]: the interpolated eigenbasis.
  [[nodiscard]] Eigen::MatrixXd eigenbasis_at(int segment, double t) const;
  /// The aligned eigenbasis of keyframe k (M_k).
  [[nodiscard]] const Eigen::MatrixXd& aligned_basis(int k) const { return bases_[static_cast<std::size_t>(k)]; }
  /// The graph of keyframe k after edits.
  [[nodiscard]] const Adjacency& graph(int k) const { return graphs_[static_cast<std::size_t>(k)]; }

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
    Eigen::MatrixXd final;               // M_{n+1} Z_last, or M_{n+1} without factors
    CoefficientTrack::Interval coefficients;
  };
  [[nodiscard]] IntervalPlan plan_interval(int segment) const;
  // w (#items by group·frames) ← chain applied to coefficient columns `c`; exponents per frame per factor.
  [[nodiscard]] Eigen::MatrixXd apply_chain(const IntervalPlan& plan, const Eigen::MatrixXd& c,
                                            const std::vector<SplineWeights>& weights, int group) const;

  int items_ = 0;
  int dimension_ = 2;
  double tension_ = 0.5;
  std::vector<Adjacency> graphs_;
  std::vector<Eigen::MatrixXd> bases_;                     // M_k
  std::map<std::pair<int, int>, RotationPower> rotations_;  // G_{k,k+1} = M_kᵀ M_{k+1}
  CoefficientTrack coefficients_;
  OrientationTrack orientation_;
};

}  // namespace throng::formation
