// Stitching two group motions in time (Kwon et al. 2008, §5; docs/METHODS.md §1.1): clip G (t frames)
// then clip G′ (t′ frames) with the same number of agents become one clip of t + t′ − 1 frames whose formation
// morphs smoothly across the joint while each trajectory keeps its detail.
//
// Method.
//  1. Correspondence: the minimum-total-distance matching between G's last frame and G′'s first frame (exact:
//     throng/core/planar_assignment.h, Jonker–Volgenant over nearest-neighbour candidates with a dual certificate).
//  2. Alignment: the rotation and translation (no scale) taking G′'s first frame onto G's last frame in least
//     squares (Eigen::umeyama without scaling), applied to all of G′. Steps 1 and 2 are iterated (re-matching in
//     the aligned frame) from a few start rotations, so a G′ turned by any angle is put back
//     (throng/stitch/boundary.h).
//  3. Blending: the stitched graph has the frames of G then G′ from its second frame on; the joint J is G's last
//     frame. Temporal features are copied from G before J and from G′ after J; at J they are the average of G's
//     feature at J − 1 and G′'s at J + 1 (the paper's linear interpolation at the midpoint). Spatial and
//     spatiotemporal features come from the intermediate graph Ḡ (Eq. 11): w(J) averages G's last and G′'s first
//     frame; before J, w(i) = v(i) + f_a(t(J) − t(i)) (w(J) − v(J)); after J, symmetrically with G′; with
//     f_a(d) = 1 − 3 (d/W)² + 2 (d/W)³ for d < W and 0 beyond, W the blending window in seconds.
//  4. One solve of the section-1 system (throng/edit/feature_deformation.h: E1, then scale compensation E2 fitting
//     Ḡ's triangles) with these features.
//
// Decisions where the paper is open:
//  * Window. W is a duration per side, in seconds from the joint (Eq. 11's Δt/t with the window as t), so that it
//    means the same motion at any frame rate (30 frames would be 1.25 s at 24 fps but 0.25 s at 120 fps); it is
//    capped at each clip's duration. The default (blend_window = 0) is the paper's and METHODS.md §1.1's: each
//    clip's whole duration, f_a reaching 0 exactly at its outer frame — as long as the solve stays within
//    max_blend_vertices (agents × solved samples, default 60,000: about 1.2 GB at the ~20 kB per vertex measured
//    by bench/stitch). Beyond that budget the longest common window that fits is used (at least one sample
//    step) and the report says so (window_limited); two 300-frame clips of 1,000 agents then blend over about
//    29 frames per side.
//    Reason: the solve covers every agent at every sample of the window, and its sparse factor grows faster
//    than the samples × agents (the frames are coupled in time, so the factor's separators are whole frames):
//    blending two 300-frame clips of 1,000 agents whole at every frame is a 600,000-vertex factor that needs
//    more than 17 GB (killed on a 23 GB machine); 61,000 vertices (a 30-frame window) peak at 1.1 GB of heap,
//    99,000 (49 frames) at 2.0 GB. Raising sample_step keeps the whole clips within the budget for longer (bench/stitch).
//  * Pins. The system's position, rotation and scale need fixing. Frames where f_a = 0 (outside the window) keep
//    their aligned input positions: they are pinned, and only the window between them is solved (one pinned
//    sample of the outside on each side suffices, since features join adjacent samples only). The outer frame of
//    each clip is always pinned. So stitching leaves the clips' far ends where they were, and a short window costs
//    a small solve.
//  * Matching frame. matching = world (default, the paper's): the first matching uses the positions as they are —
//    the user placed G′ where G should continue. matching = centred: both frames are moved to their centroids
//    first (for clips placed anywhere). Either is only the first start of the boundary fit: the final matching is
//    the one in the aligned frame (boundary.h).
//  * Alignment = rigid (default), translation (no rotation) or none. With one agent, or all of them at one place,
//    no rotation is determined and none is applied.
//  * Agents: only those present at every frame of their clip take part (others are left out and listed); both
//    clips must then have the same number (else InputError). Result agents are G's, with G's ids, radii and species.
//  * Sampling: every sample_step-th frame, counted from the joint outwards on both sides (so the joint's
//    neighbouring intervals are regular), plus each clip's outer frame and the window's edges J − W and J + W′
//    (the first frames where f_a = 0, pinned: frames outside the window keep their input whatever the step).
//    The output has every source frame: the samples' solved positions exactly; a frame F between them Ḡ(F)
//    plus a not-a-knot spline (in time, through the samples of the solved window) of the displacement solved − Ḡ.
//    The displacement is taken from Ḡ, not from the aligned input, because Ḡ is continuous across the joint
//    while the input jumps there by the whole gap (a spline of solved − input put that jump back between
//    samples: 54 m/s at sample_step 4 where the walkers' fastest was 1.2 m/s). The Editor interpolates its
//    displacement with a natural spline; here not-a-knot, the end condition of throng's other resamplings
//    (throng/timewarp/spline.h), since the displacement has no reason to stop curving at the window's ends.
//  * Times: G's, then G′'s shifted so that its first frame falls on G's last (frame rates may differ; a time warp
//    or transform resamples afterwards). z is kept from the inputs. Velocities are dropped.
//  * Facing and actions (when either clip has them; none when neither has): frames up to the joint carry G's, the
//    frames after it the matched agent's of G′ turned by the alignment's rotation, each kept at the same angle to
//    its stitched path as in its clip (throng/core/facing_carry.h: turned by the change of the path tangent's
//    yaw, standing frames by the nearest moving frame's turn). A walk/stand/run action follows the stitched speed
//    where the blend moved it into another class; other actions pass through (G′'s table entries are appended
//    to G's). A clip without facing joined to one with it contributes the path's default (PathFacing).
//  * At the joint, if G (or G′) has fewer than 3 samples it has no temporal feature next to the joint and the other
//    side's is used; with neither, Ḡ's own.
//
// Plausibility (beyond the paper; Options::guard, throng/timewarp/guard.h). Blending moves G's end and G′'s start
// toward each other, so agents whose two clips disagree (formations that differ, a G′ placed elsewhere) walk
// faster near the joint, and a short window makes the bend sharp. The output then goes through the guard with
// the clips themselves as the source: speed limit 1.25 × the faster clip's fastest agent, acceleration limit
// 3 m/s² or each clip's own at the frame it came from. Where some agent is too fast, one warp shared by all
// agents slows the stitched clip down there (its frame count then exceeds t + t′ − 1; frames are resampled at
// G's rate); frames still above the acceleration limit are smoothed over ±0.5 s. The report's `guard` says
// what acted; guard.enabled = false gives the paper's output.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/core/progress.h>
#include <throng/edit/feature_deformation.h>
#include <throng/graph/features.h>
#include <throng/graph/motion_graph.h>
#include <throng/linalg/solver_options.h>
#include <throng/stitch/boundary.h>
#include <throng/timewarp/guard.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>
#include <string>
#include <vector>

namespace throng::stitch {

struct Options {
  std::size_t sample_step = 1;   ///< frames between graph samples (≥ 1)
  double blend_window = 0;        ///< W in seconds from the joint, per side (capped at each clip); 0: automatic
  std::size_t max_blend_vertices = 60000;  ///< the automatic window's budget (agents × solved samples); 0: none
  Matching matching = Matching::world;
  Alignment alignment = Alignment::rigid;
  FormationOptions formation;    ///< Ḡ's formation edges: long-edge threshold; edits by agent id of G and stitched
                                 ///< frame, acting at the solved samples in their range
  FeatureOptions features;       ///< weight floor and degenerate-feature rule
  edit::FeatureWeights weights;  ///< α, β, α′, β′, scale compensation (Eq. 4, 9)
  linalg::SolverOptions solver;
  timewarp::GuardOptions guard;  ///< the plausibility guard after the solve (see "Plausibility"); enabled: false off
};

/// Checks option values; ConfigError naming the option.
void validate(const Options& options);

/// Eq. 11's blending function: 1 − 3 (d/W)² + 2 (d/W)³ for 0 ≤ d < W, 0 for d ≥ W (and for d within a relative
/// 1e-9 of W, where frame times round: a frame on the window's edge is outside it).
[[nodiscard]] double blend_weight(double distance, double window) noexcept;

struct Report {
  std::size_t agents = 0;
  std::size_t frames_first = 0, frames_second = 0, frames = 0;  ///< t, t′, t + t′ − 1
  std::vector<std::int64_t> left_out_first, left_out_second;     ///< ids absent somewhere in their clip
  double matching_distance = 0;        ///< metres, summed over agents, in the aligned frame (none: the matching's)
  std::size_t fit_starts = 0, fit_rounds = 0;  ///< boundary fit: start rotations tried, assignments solved
  double fit_start_rotation = 0;       ///< radians: the start the chosen fit came from
  std::size_t matched_same_id = 0;     ///< agents matched to the agent of G′ with the same id
  double rotation = 0;                 ///< radians, applied to G′
  Eigen::Vector2d translation{0, 0};   ///< metres, applied to G′ after the rotation
  double gap_rms = 0, gap_max = 0;     ///< metres between G's last and aligned G′'s first frame
  std::size_t window_first = 0, window_second = 0;  ///< frames from the joint to each window edge
  double window_first_s = 0, window_second_s = 0;    ///< W used on each side (seconds)
  bool window_limited = false;         ///< the automatic window was shortened to max_blend_vertices
  std::size_t whole_clip_vertices = 0; ///< automatic window: agents × solved samples the whole clips would need
  std::size_t samples = 0, solved_samples = 0, unknowns = 0;
  std::size_t spatial_features = 0, temporal_features = 0, spatiotemporal_features = 0;
  std::size_t formation_edits = 0;     ///< formation edits whose range holds a solved sample
  double max_change = 0;               ///< metres: largest move of a vertex from the aligned input
  std::string factorization;
  double matching_seconds = 0, graph_seconds = 0, precompute_seconds = 0, solve_seconds = 0;
  timewarp::GuardReport guard;         ///< what the guard did (its warp lengthens the clip when it acts)
};

struct Result {
  CrowdMotion crowd;                        ///< t + t′ − 1 frames, G's agents
  std::vector<std::int64_t> second_ids;     ///< per result agent, the id of its matched agent in G′
  Eigen::Isometry2d alignment = Eigen::Isometry2d::Identity();  ///< applied to G′
  Report report;
};

/// Stitches `first` then `second` (see above). Throws InputError for clips with fewer than 2 frames, no agent
/// present throughout, or different agent counts; ConfigError for bad options; NumericalError when the system is
/// singular (nothing ties some free samples to the pins: an agent with no formation neighbour while α or β is 0).
[[nodiscard]] Result stitch_clips(const CrowdMotion& first, const CrowdMotion& second, const Options& options,
                            Progress* progress = nullptr);

}  // namespace throng::stitch
