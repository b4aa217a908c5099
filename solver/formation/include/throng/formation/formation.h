// Spectral formation control: keyframe formations of a group interpolated through rotating Laplacian eigenbases
// (Takahashi, Yoshida, Kwon, Lee, Lee & Shin, "Spectral-Based Group Formation Control", Eurographics 2009; read
// with docs/METHODS.md §2).
//
// The method, per group of n individuals and keyframes k = 0..K−1:
//   1. Graph of each keyframe (§3.1): Delaunay edges (3-D Delaunay for 3-D formations), weight 1/distance, then
//      the user's edits. Laplacian L_k (n×n, positive SEMI-definite); the graph must be connected.
//   2. Eigenbasis E_k of L_k, eigenvalues ascending, e1 = 1/√n set exactly. Coordinates x = Σ α_j e_j (Eq. 1).
//   3. Each basis is aligned to the previous one (§3.2, §4.2), the previous one taken in its own eigenvalue
//      order (so a pairing depends only on the two keyframes): target vectors reordered (greedy, or the max–min
//      refinement), signs flipped so <e^S_j, e^T_j> ≥ 0, det(M_{k−1}ᵀ M_k) made +1 by flipping the least aligned
//      vector. Beyond the paper: within a repeated eigenvalue (regular formations: circles, grids) the target
//      basis is rotated to match the source (orthogonal Procrustes), the many-dimensional form of the sign rule;
//      without it LAPACK's arbitrary basis of that eigenspace would spin the individuals needlessly.
//   4. Rotations between CONSECUTIVE aligned bases, G_{k,k+1} = M_kᵀ M_{k+1}, decomposed exactly as G = Z U Zᵀ,
//      U block diagonal with 2×2 rotations (the real Schur form of an orthogonal matrix; −1 pairs become
//      rotations by π). Powers G^c = Z U(c) Zᵀ, each block rotated by c·θ. (The paper approximated powers with
//      Denman–Beavers square roots.)
//   5. Several keyframes (§4.1, Eq. 5), in cumulative form: with spline weights c−1..c2 (Catmull-Rom, tension τ,
//      endpoints duplicated), in interval n → n+1,
//        M(t) = M_{n+1} · G_{n+1,n+2}^{c2} · G_{n,n+1}^{−(c−1+c0)} · G_{n−1,n}^{−c−1},
//      i.e. R2^{c2} R1^{c1+c2} R0^{c0+c1+c2} M_{n−1} with R0, R1, R2 the rotations n−1→n, n→n+1, n+1→n+2: the
//      rotational analogue of p_{n−1} + (c0+c1+c2)(p_n − p_{n−1}) + (c1+c2)(p_{n+1} − p_n) + c2(p_{n+2} − p_{n+1}).
//      This departs from METHODS.md §2 (the paper's (R2R1R0)^{c2} (R1R0)^{c1} R0^{c0} M_{n−1}) on purpose. It
//      equals the paper's when the rotations commute (always for two keyframes), but every power is of a rotation
//      between consecutive keyframes: the paper's powers of the products R1R0 and R2R1R0 take their principal
//      logarithm, which swings the basis the other way round once the rotations add up past π in a plane, and
//      for rotations that do not commute leave the path between M_n and M_{n+1} even at τ = 0; here τ = 0 gives
//      exactly the two-keyframe path of each interval. Two keyframes give the §3.2 path M(t) = R^{s(t)} S with
//      s = c1 + c2 (s(t) = t when τ = 1; the default τ = 0.5 eases in and out a little).
//      Options::keyframe_product = paper gives Eq. 5 as printed instead (KeyframeProduct below). A keyframe
//      marked sharp (Keyframe::sharp) is duplicated in the control keyframes like an endpoint (§4.1), so the
//      paths may turn there.
//   6. Coefficients (§3.3, Eq. 4): each (α_j, β_j) interpolated in polar form, length and angle with the same
//      spline weights, angles unwrapped the shorter way round between consecutive keyframes; in 3-D (§4.5) the
//      direction follows the same cumulative product of powers of the shortest rotations between consecutive
//      keyframes' directions (slerp for two keyframes) and the length the spline.
//      The barycentre (j = 1) follows the spline linearly.
//   7. Orientation (§3.3, PCA adjustment): each keyframe is rotated about its barycentre so its principal axes
//      match the previous keyframe's (the sign ambiguity of the axes is settled by the correspondence: the
//      candidate closest to the previous keyframe wins; nearly isotropic keyframes, whose axes are undefined, use
//      the least-squares rotation instead). The shapes are interpolated in this common frame and the keyframes'
//      own rotation is restored by a rotation interpolated with the same spline (2-D: the unwrapped angle; 3-D:
//      the same cumulative product of powers of the rotations between consecutive keyframes), so keyframes are
//      still hit exactly.
//   8. Positions x(t) = anchor(t) + M(t) C(t) O(t)ᵀ, all frames of a keyframe interval in one matrix product
//      chain over the (at most three) factors of step 5: w = Z1ᵀ C, rotate blocks (O(n) per frame),
//      w = (Z2ᵀ Z1) w, ..., x = (M_{n+1} Z_last) w.
//   9. Hierarchy (§4.4): a tree of groups; each group runs steps 1–8 on its items (its direct members and the
//      barycentres of its subgroups) relative to its own barycentre, whose path comes from the parent group.
//      Without a tree, one is built by spectral clustering (recursive Fiedler bisection of the graph summed
//      over the keyframes; sparse Lanczos beyond 400 items, fiedler.h) when there are more individuals than
//      Options::auto_group_size (default 2,000), with groups of at most Options::auto_cluster_size items
//      (default 250).
//  10. Collision avoidance (§4.3): social forces (Helbing & Molnár 1995) drive each individual along its spectral
//      path while individuals repel; then the paths are smoothed (keyframe frames pinned) while a minimum distance
//      is kept by projection at every frame.
//  11. Beyond the paper: individual matching between keyframes by minimum-cost assignment when rows are not in
//      correspondence; keyframes taken from an existing crowd at given frames.
//  12. The paper's baselines (Options::interpolation, Interpolation below): linear interpolation of positions and
//      simple polar interpolation, in place of steps 2–6 and 8 for each group, for comparisons like its Figures
//      3, 5 and 9.
//  13. Beyond the paper (issue 13): every individual's facing and action (CrowdMotion::orientations, actions):
//      the direction of travel, smoothed, with the standing rule; banking into turns in 3-D; facings a keyframe
//      gives (Keyframe::facings), held at the keyframe and interpolated along the shorter arc (FacingOptions).
//
// Cost: eigen-decompositions O(n³) per keyframe, one symmetric eigenproblem O(n³) per rotation (the rotation's
// planes are the eigenspaces of its symmetric part; clusters of nearly equal angles are resolved exactly by a
// small Hermitian eigenproblem; K−1 rotations in the cumulative form, up to 3 per interval in the paper's), and
// per frame O(n²·d) in matrix products. Memory O(K·n² + frames·n). With an automatic hierarchy (groups of at
// most m = 250 items) time is O(N·m·(K·m + frames·d)) and memory O(N·(K·m + frames)) for N individuals: linear
// in N. The baselines: O(N·(K·log N + frames)) time (graphs, then a few operations per individual and frame).
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/core/progress.h>
#include <throng/timewarp/guard.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

namespace throng::formation {

/// Without a given hierarchy, a group of more individuals than this is split automatically (Options::
/// auto_group_size, §4.4: the "built automatically by spectral clustering when not given"). Up to it
/// one flat group stays within the time targets (a flat 2,000 × 1,000 frames: about 5 s on the 2-core
/// machine with OpenBLAS's right kernels); beyond it the O(n³) eigen-analysis and O(n²) memory per keyframe of
/// one group grow quickly. The paper's limit of 60 per group is a limit of its eigensolver, not of the method,
/// so flat groups far larger are kept flat.
inline constexpr int default_auto_group_size = 2000;

/// The largest group the automatic clustering builds (Options::auto_cluster_size). A hierarchy of groups of m
/// items costs about N·(a·m² + b·m·frames) for N individuals: the eigen-analyses (a few m³ per group) and the
/// per-frame products (m² per group and frame). Measured on a 10,000-individual transition × 1,000 frames
/// (2 cores, shared, CPU time of the whole call): groups of 2,000 (the flat limit) 43 s, 1,000 12 s, 500 5.7 s,
/// 250 3.3 s, 100 2.8 s. 250 keeps 10,000 individuals well inside 5 s and groups large enough that
/// neighbourhoods of hundreds move as the spectral method moves them; smaller groups save little more.
inline constexpr int default_auto_cluster_size = 250;

/// How target eigenvectors are paired with source eigenvectors (§4.2).
enum class Reordering {
  none,    ///< by eigenvalue order
  greedy,  ///< source j = 2..n, in the source keyframe's own eigenvalue order, in turn takes the free target vector
           ///< with the largest |inner product| (the paper's)
  max_min  ///< maximise the smallest |inner product| over all pairs (exact bottleneck assignment), then the sum
};

/// What is interpolated between keyframes: the paper's method, or the baselines its figures compare it with.
/// Every method hits the keyframes exactly, runs per group of a hierarchy (items relative to the group's
/// barycentre, whose path comes from the parent group), uses the same Catmull-Rom weights (Options::tension,
/// sharp keyframes) and builds and checks the same keyframe graphs (edits, connectivity: the same job runs with
/// any method, and the output's graph edges are the same); the baselines do not use the graphs otherwise.
enum class Interpolation {
  spectral,  ///< the paper's method: rotating Laplacian eigenbases, coefficients in polar form (steps 1–8 above)
  linear,    ///< positions interpolated linearly: x(t) = Σ_i c_i(t) x_{k_i}, each individual on the spline of its
             ///< own keyframe positions — between two keyframes the straight segment, x(t) = (1 − s) x_0 + s x_1
             ///< with s = c1 + c2 (s = t for tension 1). The paper's "linear interpolation" (Figure 9(a), and
             ///< Figure 3(a): there the keyframes share a graph and interpolating the coefficients linearly is
             ///< the same thing). Options::orientation and reordering do not apply (a rotation is not linear).
  polar      ///< the paper's "simple polar interpolation" (§3.3, Figure 5(a)): each individual's position about
             ///< the group's barycentre, after the PCA adjustment (Options::orientation), interpolated in polar
             ///< coordinates without the spectral decomposition — Eq. 4 applied to (x_i, y_i) instead of
             ///< (α_k, β_k): length and angle each on the spline of the keyframes' values, angles unwrapped the
             ///< shorter way between consecutive keyframes; 3-D: the direction along the shortest rotations (slerp
             ///< for two keyframes, §4.5). The barycentre follows the spline linearly and the keyframes' own
             ///< rotation is restored as in the spectral method (step 7).
};

/// How the eigenbasis path joins several keyframes (Eq. 5; only the spectral method has it).
enum class KeyframeProduct {
  cumulative,  ///< M(t) = M_{n+1} G_{n+1,n+2}^{c2} G_{n,n+1}^{−(c−1+c0)} G_{n−1,n}^{−c−1}: powers of the rotations
               ///< between consecutive keyframes only (step 5 above)
  paper        ///< Eq. 5 as printed: M(t) = (R2 R1 R0)^{c2} (R1 R0)^{c1} (R0)^{c0} M_{n−1}, computed as
               ///< M_{n−1} G_{n−1,n+2}^{c2} G_{n−1,n+1}^{c1} G_{n−1,n}^{c0} with G_{a,b} = M_aᵀ M_b (R1 R0 is the
               ///< rotation from keyframe n−1 straight to n+1, and so on): powers of products, each the principal
               ///< power of the direct rotation. It hits every keyframe (t = 0: M_n, t = 1: M_{n+1}) and equals
               ///< the cumulative form with two keyframes; with more, the interval's path also depends on the
               ///< rotations to n−1 and n+2 even at tension 0, and swings back where rotations add up past π.
};

/// How keyframes are brought to a common orientation before their shapes are interpolated (§3.3).
enum class OrientationAlignment {
  none,       ///< coefficients interpolated as they are (rotation handled by the polar interpolation alone)
  pca,        ///< principal axes matched (the paper's PCA adjustment)
  procrustes  ///< least-squares rotation onto the previous keyframe (uses the correspondence)
};

/// Social forces and the minimum-distance smoothing that follow the spectral paths (§4.3).
struct CollisionOptions {
  bool enabled = false;
  double min_distance_m = 0.6;               ///< centre-to-centre minimum between any two individuals, every frame
  double relaxation_time_s = 0.3;            ///< τ of the driving force (v_desired − v)/τ
  double tracking_time_s = 0.3;              ///< desired velocity = path velocity + (path point − position)/this
  double repulsion_strength_m_per_s2 = 2.0;  ///< A in A·exp((min_distance − d)/B)
  double repulsion_range_m = 0.2;            ///< B, the range of the repulsion
  double time_step_s = 0.02;                 ///< largest simulation step; frames are sub-stepped to it
  double smoothing_time_s = 0.25;            ///< extent of the temporal smoothing (about the cut-off period)
  int smoothing_passes = 2;                  ///< smoothing/projection alternations after the simulation
  int projection_sweeps = 200;               ///< Gauss–Seidel sweeps per frame to restore the minimum distance
};

/// How the individuals face and what they do (step 13; facing.h in the sources has the whole rule).
struct FacingOptions {
  double smoothing_s = 0.5;  ///< the direction of travel is the chord of the path over this window centred on the
                             ///< frame (≥ 0; at least one frame each side): steady through the frame-to-frame
                             ///< jitter of collision avoidance, late by nothing on a straight path
  PathPoseRule rule;         ///< standing below rule.standing_speed (the facing is kept), running from
                             ///< rule.running_speed (core's defaults: 0.3 and 2 m/s)
  bool bank = true;          ///< 3-D formations (flying: the airshow) roll into turns as a coordinated turn
  double gravity_mps2 = 9.81;  ///< g of the coordinated turn: tan(bank) = lateral acceleration / g
  double max_turn_rate_rad_s = std::numbers::pi;  ///< > 0: the travel facing turns at most this fast (half a
                             ///< turn per second: a person turns about in a second), so an individual that
                             ///< reverses does not flip round in one frame; keyframe facings still hold exactly
};

struct Options {
  double frame_rate_hz = 30.0;   ///< output frames per second; a keyframe interval Δt gets max(1, round(Δt·rate))
                                 ///< equal frames, so every keyframe time is a frame
  double tension = 0.5;          ///< Catmull-Rom τ of Eq. 5, in [0, 1]
  Interpolation interpolation = Interpolation::spectral;  ///< the method, or one of the paper's baselines
  KeyframeProduct keyframe_product = KeyframeProduct::cumulative;  ///< Eq. 5's form for the eigenbases
  Reordering reordering = Reordering::greedy;
  OrientationAlignment orientation = OrientationAlignment::pca;
  double isotropy_tolerance = 0.05;  ///< PCA is used only when principal variances differ by more than this
                                     ///< fraction of their sum; otherwise the least-squares rotation
  bool match_individuals = false;    ///< rows of keyframes k ≥ 1 are not in correspondence with keyframe 0:
                                     ///< match them (minimum summed squared distance after alignment)
  int auto_group_size = default_auto_group_size;  ///< no hierarchy given and more individuals than this
                                     ///< (≥ 2): one is built by spectral clustering with at most
                                     ///< min(auto_group_size, auto_cluster_size) items per group; 0 = always flat
  int auto_cluster_size = default_auto_cluster_size;  ///< (≥ 2) the largest group of a hierarchy built
                                     ///< automatically (see default_auto_cluster_size)
  double radius_m = 0.25;            ///< radius written for every individual
  CollisionOptions collision;
  FacingOptions facing;
  /// Beyond the paper (issue 14), applied by the formation job after animate_formation (plausibility.h): the
  /// guard slows the formation where an individual is faster than guard.max_speed_ratio × the stated speed and
  /// smooths accelerations beyond guard.max_acceleration. guard.enabled = false: the paper's timing exactly.
  timewarp::GuardOptions guard;
  double max_speed_mps = 0;  ///< the stated speed (m/s, ≥ 0); 0: the keyframes' own (fastest straight-line speed
                             ///< an individual needs between two consecutive keyframes)
};

/// A pair of individuals (indices into the keyframes' rows, i.e. output agents).
using Pair = std::array<int, 2>;

/// Multiply the weights of existing edges: the listed pairs, and every edge between two listed members.
struct EdgeScale {
  std::vector<Pair> pairs;   ///< each must be an edge of the graph (after add/remove)
  std::vector<int> members;  ///< every existing edge with both ends among these
  double factor = 1.0;       ///< > 0
};

/// Edits of a keyframe graph (§3.1), applied in this order: remove, add, scale.
struct AdjacencyEdits {
  std::vector<Pair> remove;        ///< each must be an edge
  std::vector<Pair> add;           ///< connected with weight 1/distance (a pair already adjacent is left as is)
  std::vector<EdgeScale> scale;
  std::string where;               ///< where these edits were given ("job.yaml:7:8 (edits)"), put in front of
                                   ///< messages about them; empty: nowhere to name
};

/// One keyframe formation. Named members with defaults, so later ones (facings: issue 13) add to it without
/// touching the code that builds keyframes.
struct Keyframe {
  double time_s = 0.0;
  Eigen::MatrixXd positions;  ///< #individuals by 2 or 3 (metres); row i is individual i
  AdjacencyEdits edits;       ///< this keyframe only, after the problem-wide edits
  std::string where;          ///< where the keyframe was given ("job.yaml:12:5 (keyframes[1])"), put in front of
                              ///< messages about it (its graph, spacing, data); empty: nowhere to name
  bool sharp = false;         ///< a sharp corner (§4.1): the splines duplicate this keyframe as they duplicate
                              ///< the endpoints, so every path (positions, eigenbases, coefficients,
                              ///< orientation) may turn here instead of passing smoothly: velocities change
                              ///< direction at once, and size too when the two chords differ (as asked: a
                              ///< marching turn); no effect on the first and last keyframes
  /// Empty (the individuals face where they travel), or one facing per individual (row order of `positions`):
  /// a unit quaternion (x, y, z, w; |q| within orientation_tolerance of 1) turning the body frame (forward +x,
  /// left +y, up +z) into the world — in 2-D a yaw about +z, e.g. a marching band facing the audience while it
  /// walks sideways. Held exactly at this keyframe's frame (normalised), interpolated to the next keyframe's
  /// (FacingOptions, step 13).
  std::vector<Eigen::Quaterniond> facings;
};

/// A group of the hierarchy (§4.4). The root holds everyone; each individual is in exactly one group.
struct Group {
  std::string name;
  std::vector<int> members;      ///< individuals directly in this group
  std::vector<Group> subgroups;  ///< nested groups (their barycentres are this group's other items)
  std::string where;             ///< root only: where the tree was given ("job.yaml:3:12 (hierarchy)"), put in
                                 ///< front of messages about the tree; empty: nowhere to name
};

struct Problem {
  std::vector<Keyframe> keyframes;  ///< ≥ 2, strictly increasing times, the same count and dimension
  std::vector<std::int64_t> ids;    ///< #individuals, distinct; empty: 0..n−1
  AdjacencyEdits edits;             ///< applied to every keyframe's graph
  std::optional<Group> hierarchy;   ///< none: flat, or built automatically beyond Options::auto_group_size
};

/// What the collision stage achieved.
struct CollisionReport {
  bool ran = false;
  bool satisfied = true;           ///< every pair at least min_distance apart at every frame (to 1e-6 relative)
  double closest_m = 0.0;          ///< smallest centre distance over all frames and pairs, searched up to
                                   ///< 2 × min_distance (+infinity when no pair is that close)
  std::size_t closest_frame = 0;   ///< where it was found
  Pair closest_pair{0, 0};
  double largest_shift_m = 0.0;    ///< largest distance of a final position from its spectral position
};

struct Result {
  CrowdMotion motion;  ///< #frames by #individuals; species = index of the individual's innermost group
  std::vector<std::vector<int>> correspondence;  ///< per keyframe: row of that keyframe taken by individual i
  Group hierarchy;     ///< the tree used (given, built, or a single root group)
  std::vector<std::size_t> keyframe_frames;      ///< per keyframe: its frame in `motion`
  /// Per keyframe: the graph edges between two individuals (i < j, sorted), after edits — in a hierarchy the
  /// edges between two direct members of one group (edges to a subgroup's barycentre are left out).
  std::vector<std::vector<Pair>> keyframe_edges;
  CollisionReport collision;
  timewarp::GuardReport guard;  ///< what the plausibility guard did (plausibility.h; untouched by animate_formation)
};

/// Interpolates the keyframes of `problem`. Throws ConfigError for options out of range, InputError for bad data
/// (fewer than 2 keyframes, counts or dimensions that differ, times not increasing, NaN, duplicate positions in a
/// keyframe, a disconnected graph, edits naming non-edges or unknown individuals, a malformed hierarchy,
/// keyframes closer than the collision distance). Deterministic: the same input gives the same bits whatever
/// the thread count. Progress stages: "formation analysis", "formation frames", "formation collisions".
[[nodiscard]] Result animate_formation(const Problem& problem, const Options& options, Progress& progress);
[[nodiscard]] Result animate_formation(const Problem& problem, const Options& options);

/// Keyframes from an existing crowd at the given frames (times taken from the crowd). Every agent must be
/// present at those frames (InputError otherwise, naming the agent and frame). `dimension` 2 drops z.
[[nodiscard]] std::vector<Keyframe> keyframes_from_motion(const CrowdMotion& motion,
                                                          const std::vector<std::size_t>& frames, int dimension = 2);

}  // namespace throng::formation
