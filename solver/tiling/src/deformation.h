// Patch deformation (paper §3 "Patch Deformation" and "Stitching Patches", Kim et al. 2009's Laplacian path
// editing): each path is an elastic string; interpersonal constraints hold characters together; entries and
// exits are handles; stitched patches share their end samples (Eq. 1–3).
//
// Per patch type, two independent channels — space (x, y per sample) and time (t per sample) — each
//
//   minimise  Σ_interior |L_i(x) − l_i|²  +  w_a Σ_all |x_j − anchor_j|²     subject to  C x = d(φ)
//
//   space  L_i(p) = p_i − (p_{i−1} + p_{i+1})/2 − a_i c_i − b_i J c_i,  c_i = p_{i+1} − p_{i−1}, J = rotation by 90°,
//          with (a_i, b_i) the coordinates of the patch's own Laplacian in its local chord frame: rotation-
//          and translation-invariant, l_i = 0. Where the patch's chord is degenerate (|c_i| < 1 µm: a character
//          standing still), the row keeps the Laplacian itself, rotated with the instance: L_i = δ_i,
//          l_i = R(φ) δ_i^patch.
//   time   L_i(t) = t_i − (t_{i−1} + t_{i+1})/2,  l_i = the patch's own value (0 for uniform sampling).
//   C      interpersonal constraints: p_b − p_a = R(φ) (p_b − p_a)^patch and t_b − t_a = (t_b − t_a)^patch.
//          Relative position is kept in the instance's frame (rotation φ of its placement): a rotation-
//          invariant form would need a direction of travel, and interacting characters often stand still.
//   w_a    DeformationOptions::anchor_weight: keeps the system positive definite (no free similarity motion)
//          and holds the parts no handle pulls near their placement.
//
// The system of a type is the same for every instance: only the anchor (the placement, or the current paths of
// an instance being re-deformed) and φ change. So each channel is precomputed once per type with
// throng::linalg::ConstrainedLeastSquares (objective, interpersonal constraints) as the linear map
//
//   x = G (w_a · anchor) + cos φ · g_c + sin φ · g_s + g_0,
//
// G the constrained inverse (columns: solutions for unit right-hand sides), g_c, g_s, g_0 the responses to the
// rotated and fixed parts of l and d. Stitching several instances adds coupling rows E x = e (Eq. 1–3 between
// instances that deform together, pins and fixed tangents towards instances that stay) through a Schur
// complement on the members' G: S λ = E x0 − e, S = Σ_k E_k G_k E_kᵀ, x_k = x0_k − G_k E_kᵀ λ. This equals
// concatenating the members' systems and constraints into one (the paper's "single larger system": tests/tiling/
// test_deformation.cpp solves that KKT system densely and compares), without a factorisation per stitch.
#pragma once

#include <throng/tiling/options.h>
#include <throng/tiling/patch.h>
#include <throng/tiling/tiling.h>

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace throng::tiling {

/// One channel of a type's precomputed system (see the file comment).
struct Channel {
  int width = 1;                ///< unknowns per sample: 2 (space, x y interleaved) or 1 (time)
  Eigen::Index unknowns = 0;    ///< width × samples of the type
  Eigen::MatrixXd G;            ///< unknowns × unknowns, symmetric
  Eigen::VectorXd g_cos, g_sin, g_fixed;
  double anchor_weight = 0;

  /// The solution without coupling rows, for an anchor (unknowns) and the instance angle φ.
  [[nodiscard]] Eigen::VectorXd free_solution(const Eigen::VectorXd& anchor, double angle) const;
};

/// A patch type's deformation system.
class PatchSystem {
 public:
  PatchSystem(const PatchType& type, const DeformationOptions& options);

  Channel space;
  Channel time;

  /// Index of sample `s` of fragment `f` among the type's samples (fragments concatenated in order).
  [[nodiscard]] Eigen::Index sample(std::size_t f, std::size_t s) const noexcept {
    return offsets_[f] + static_cast<Eigen::Index>(s);
  }
  [[nodiscard]] Eigen::Index samples() const noexcept { return offsets_.back(); }

  /// The anchors (space: x y interleaved; time) of a set of paths, one per fragment.
  [[nodiscard]] Eigen::VectorXd space_anchor(const std::vector<Path>& paths) const;
  [[nodiscard]] Eigen::VectorXd time_anchor(const std::vector<Path>& paths) const;

 private:
  std::vector<Eigen::Index> offsets_;  // #fragments + 1
};

/// The paths of a type placed by `transform` without deformation.
[[nodiscard]] std::vector<Path> place(const PatchType& type, const Transform& transform);

/// Paths from solved unknowns. Headings: the patch's heading turned by the instance angle and by how much the
/// path's local chord turned (the chord p_{i+1} − p_{i−1}, one-sided at the ends; where the patch's or the
/// deformed chord is shorter than 1 mm, the nearest sample's turn, or none).
[[nodiscard]] std::vector<Path> paths_from(const PatchType& type, const PatchSystem& system, double angle,
                                           const Eigen::VectorXd& space, const Eigen::VectorXd& time);

/// A term of a coupling row: coefficient × unknown `unknown` of member `member`.
struct Term {
  std::uint32_t member = 0;
  Eigen::Index unknown = 0;
  double coefficient = 0;
};

/// One coupling row: Σ terms = value.
struct Row {
  std::array<Term, 4> terms{};
  int size = 0;
  double value = 0;
  void add(std::uint32_t member, Eigen::Index unknown, double coefficient) {
    terms[static_cast<std::size_t>(size++)] = {member, unknown, coefficient};
  }
};

/// An instance taking part in a joint solve.
struct Member {
  const PatchSystem* system = nullptr;
  Eigen::VectorXd space_anchor;
  Eigen::VectorXd time_anchor;
  double angle = 0;
};

struct JointProblem {
  std::vector<Member> members;
  std::vector<Row> space_rows;  ///< unknowns index the members' space channels
  std::vector<Row> time_rows;   ///< ... and time channels
};

struct JointSolution {
  std::vector<Eigen::VectorXd> space;  ///< per member
  std::vector<Eigen::VectorXd> time;
  double max_residual = 0;             ///< largest |E x − e| over both channels
};

/// Solves a joint problem (see the file comment). Redundant coupling rows are fine; the caller compares
/// max_residual with its tolerance to find contradictory ones.
[[nodiscard]] JointSolution solve_joint(const JointProblem& problem);

}  // namespace throng::tiling
