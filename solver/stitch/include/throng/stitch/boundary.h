// The boundary fit of a stitch (Kwon et al. 2008 §5 steps 1–2; docs/METHODS.md §1.1): which agent of
// clip G′ continues which agent of clip G, and the rigid motion that puts G′'s first frame onto G's last.
//
// Step 1 alone (match_boundary) is the exact minimum-total-distance assignment between the two frames
// (throng/core/planar_assignment.h); step 2 alone (align) the least-squares rotation and translation without scale
// (Eigen::umeyama). Done once each, in that order (the paper's reading), they only work when G′ already lies
// near where G ends and turned the same way: the matching of a clip turned by 90° pairs agents by where they
// happen to be, and the alignment of that matching recovers a few degrees, not the 90° (a gap of metres stays).
// fit_boundary therefore iterates: match, align, re-match in the aligned frame, … (an assignment-based iterative
// closest point), from several start rotations. Decisions:
//  * Starts. The matching option's own frame first (world: G′ as placed; centred: G′'s centroid moved onto G's),
//    then, for rigid alignment, G′ turned about its centroid (and moved onto G's centroid) by
//      - the heading difference: the angle from G′'s mean first step (frame 0 → 1) to G's mean last step (J − 1 →
//        J), when both groups move;
//      - the principal-axis differences: the angle from G′'s first frame's principal axis to G's last frame's,
//        and that plus 180° (an axis has no sign), when both frames are spread out (not at one point).
//    A start within 10° of an earlier one is skipped (both lead to the same fit).
//  * Screening: from each start, the same iteration with nearest neighbours in place of the matching (a point may
//    be chosen twice; a k-d tree, O(n log n) a round; among equally near points the tree's order decides, the same
//    on every run), to convergence. The screened fits within 25 % of the best screen score
//    (the screen is only a proxy of the matching's distance), one per rotation (10°), are refined exactly; so
//    is the paper's single matching and alignment in the option's own frame (one round).
//  * Refinement: at most 30 rounds of match (world distances, in the current aligned frame) then align; stop
//    when the matching repeats or the summed distance stops falling (relative 1e-12).
//  * Choice: the least summed distance in the aligned frame (ties keep the earlier: the paper's round, then the
//    order of the starts) among the fits that keep the group walking forward — the aligned G′'s first step
//    within 90° of G's last — when both groups move and any fit does; otherwise among all. Reason: a
//    near-symmetric formation (a block, a line) fits about as well turned by 180°, and a stitch continues the
//    walk; the town's clips gave a turned-around fit 16 % closer than the forward one. A deliberate U-turn keeps
//    its placement with alignment translation or none.
//  * Alignment = translation: the translation is the mean difference whatever the matching, so the refinement
//    from the own frame ends after one re-match (world and centred give the same fit); no screening.
//    Alignment = none: one matching in the option's frame, nothing moved.
//  * Runs: the paper's round and each refined start are independent and run side by side (the paper's, far apart
//    in the option's frame, is the slowest matching); within a run, each matching starts from the one before
//    (assign_planar's state: the agents moved a little), which pays in the last rounds.
//  * Cost: each round is one exact assignment (n agents): the paper's one, then typically 2–7 (the last confirms
//    the matching); two 1,000-agent clips took 4 in bench/stitch. Matching in all: 0.11 s at 1,000 agents, 21.6 s
//    at 10,000 (bench/scale/bench_methods; the dense O(n³) solver took 1.8 s and 45.5 s at 1,000 and 2,000).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstddef>
#include <vector>

namespace throng::stitch {

enum class Matching { world, centred };
enum class Alignment { rigid, translation, none };

/// Points in the plane, one per row (metres).
using Points = Eigen::Matrix<double, Eigen::Dynamic, 2>;

/// The matching between `last_of_first` (G's last frame) and `first_of_second` (G′'s first frame), same count n,
/// minimising the summed distance (centred first when matching = centred).
///   second_of_first  n: the row of first_of_second matched to each row of last_of_first
struct Correspondence {
  std::vector<std::size_t> second_of_first;
  double total_distance = 0;  ///< metres, in the frame the matching used
};
[[nodiscard]] Correspondence match_boundary(const Eigen::Ref<const Points>& last_of_first,
                                            const Eigen::Ref<const Points>& first_of_second, Matching matching);

/// The rotation and translation (no scale) taking `from` onto `to` (rows correspond) in least squares, or only
/// the translation (mean difference), or the identity.
[[nodiscard]] Eigen::Isometry2d align(const Eigen::Ref<const Points>& from, const Eigen::Ref<const Points>& to,
                                      Alignment alignment);

/// The mean frame-to-frame step of a group next to the joint (metres per frame): G's last step, G′'s first.
/// Zero when unknown or when the group stands still; then no heading start is tried.
struct Headings {
  Eigen::Vector2d first{0, 0};   ///< G: mean of p(J) − p(J − 1)
  Eigen::Vector2d second{0, 0};  ///< G′: mean of p(1) − p(0)
};

struct BoundaryFit {
  Correspondence correspondence;  ///< total_distance: summed distance in the aligned frame (none: the matching's)
  Eigen::Isometry2d alignment = Eigen::Isometry2d::Identity();  ///< applied to G′
  std::size_t starts = 0;         ///< start rotations screened
  std::size_t rounds = 0;         ///< assignments solved
  double start_rotation = 0;      ///< radians: the start the winning fit came from (0: the option's own frame)
};

/// Steps 1–2 together (see above). InputError when the counts differ.
[[nodiscard]] BoundaryFit fit_boundary(const Eigen::Ref<const Points>& last_of_first,
                                       const Eigen::Ref<const Points>& first_of_second, const Headings& headings,
                                       Matching matching, Alignment alignment);

}  // namespace throng::stitch
