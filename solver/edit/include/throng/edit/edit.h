// Group motion editing (Kwon, Lee, Lee, Takahashi, SIGGRAPH 2008, §3–4; docs/METHODS.md §1): deform
// a clip of a crowd by pinning and dragging agents while keeping its formations and trajectories.
//
// Method. The clip is sampled and turned into the space-time motion graph (throng/graph). Step 1 minimises
// E1 = ES + α ET + β EST (Eq. 4–7) over all sampled positions subject to the handles (pins and drags) and the
// general constraints. Step 2 (scale compensation, Eq. 8–10) fits each original formation triangle to its
// step-1 copy by a rotation and a translation (no scale) and minimises E2 = ESC + α′ ET + β′ EST, where ESC asks
// each edge of a spatial feature to match the fitted triangle's edge. Both are sparse linear least squares
// solved by throng/linalg with the handles eliminated and the general constraints through a Schur complement,
// so re-targeting handles (a drag) costs back-substitutions only.
//
// Decisions where the paper is open (see also throng/graph/features.h for features and weights):
//  * Igarashi et al.'s closed form for Eq. 8 (a similar copy of the original triangle, fitted in least squares,
//    then scaled back to the original size about its centroid) equals, in 2-D, the least-squares rigid fit of
//    the original triangle onto the step-1 triangle: the optimal similarity and the optimal rotation share
//    the angle arg Σ conj(p_k − p̄)(q_k − q̄). That formula is used; a collapsed step-1 triangle keeps angle 0.
//  * Unknowns are x and y interleaved per vertex (2 per vertex): R90 couples them (Eq. 1).
//  * A handle (pin or drag) sets a vertex; two handles on one vertex must agree (else: contradictory). Every
//    frame of a drag's range becomes a sample, so the output holds the rigid map at every frame it covers, not
//    only at the regular samples (the extra vertices are handles: eliminated, they add no unknowns).
//  * General constraints (the paper's "any linear constraint", §4): relative position of two agents (p_a − p_b =
//    offset, default the original offset), velocity at a frame ((p(f+1) − p(f)) / (t(f+1) − t(f)); at the clip's
//    last frame the backward difference), motion along a line (the normal component of p − point is 0),
//    acceleration at a frame (the three-point second difference over the actual frame times), a weighted sum
//    over agents (a centroid held on a path) and a user's own scalar row over any agents, frames and axes. Every
//    frame they cover becomes a sample, so the output meets them at every frame (a long constraint range adds
//    samples for every agent: unknowns).
//  * Every connected part of the graph (through features) needs two handled vertices at distinct original
//    places: otherwise its position, rotation and scale are free and the system is singular (NumericalError
//    naming the agents). Constraints do not count toward this.
//  * Output: the edited clip at the source frame rate, through every edited sample exactly. Between samples each
//    agent follows the natural cubic spline of its edited samples plus the original's detail off the spline of
//    its original samples, turned with the agent's local rotation (interpolated from its turn at the samples):
//    a rigid motion of every handle is then a rigid motion of every output frame, and the gait's sway stays
//    across the new heading (z is kept as is). The time warp is another method.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/core/progress.h>
#include <throng/graph/clip.h>
#include <throng/graph/features.h>
#include <throng/graph/motion_graph.h>
#include <throng/linalg/solver_options.h>

#include <Eigen/Core>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace throng::edit {

/// Local edits (throng/edit/local_edit.h): the space-time graph is split into METIS parts, and an edit solves
/// only the parts holding a moved handle or a general constraint plus the parts within `halo` hops of them, with
/// the rest pinned to its current positions. parts = 0 solves the whole graph (the Editor).
struct LocalOptions {
  /// `parts` value for parts of about vertices_per_part vertices each, cut along time and space separately
  /// (partition_time_blocks in throng/graph/partition.h: blocks of 2∛vertices_per_part samples × groups of
  /// agents), so a region's size, and a drag's cost, follow the part size and not the crowd's (job: auto).
  static constexpr int by_size = std::numeric_limits<int>::max();

  int parts = 0;                  ///< METIS parts, ≥ 0 (0: off, global solves; by_size: from vertices_per_part)
  int vertices_per_part = 500;    ///< part size when parts = by_size, ≥ 1 (ignored for a given part count)
  int halo = 1;                   ///< part hops around the reached parts, ≥ 0; −1: every connected part
  std::uint64_t seed = 1;         ///< METIS's seed (same seed, same parts)
  int max_cached_regions = 8;     ///< factorised regions kept for reuse across drags (least recently used go), ≥ 1
};

/// Everything that shapes the deformation. The paper gives no values for α, β, α′, β′; with the unit-free
/// feature weights of throng/graph/features.h, 1 balances the terms (tests/edit: the Figure 5 turn stays within
/// ~6° of the heading, the Figure 3 stretch shrinks tenfold in step 2).
struct Options {
  ClipOptions clip;            ///< frame range, agents, sampling step
  FormationOptions formation;  ///< long-edge threshold and edge edits
  FeatureOptions features;     ///< weight floor and degenerate-feature rule
  double alpha = 1.0;          ///< α: weight of the temporal term ET in step 1 (Eq. 4), ≥ 0
  double beta = 1.0;           ///< β: weight of the spatiotemporal term EST in step 1 (Eq. 4), ≥ 0
  double alpha_prime = 1.0;    ///< α′: weight of ET in step 2 (Eq. 9), ≥ 0
  double beta_prime = 1.0;     ///< β′: weight of EST in step 2 (Eq. 9), ≥ 0
  bool scale_compensation = true;  ///< run step 2 (off: the result is step 1's)
  linalg::SolverOptions solver;    ///< backend and its settings
  LocalOptions local;              ///< solve only the parts an edit reaches (throng/edit/local_edit.h); off by default
};

/// Frames in a request are input frame indices; a negative frame counts back from the clip's last frame
/// (−1 is the clip's last frame, −10 the tenth from the end), so a job can name the end of a clip it has not seen.
using Frame = long;

/// Vertices chosen by agents and frames.
struct Selection {
  std::vector<std::int64_t> agents;  ///< agent ids; empty = every agent of the clip
  Frame first_frame = 0;             ///< inclusive (clamped to the clip's first frame)
  Frame last_frame = -1;             ///< inclusive (default: the clip's last frame)
};

/// Keeps one agent at one frame at `position` (metres; default: where it is in the input).
struct Pin {
  std::int64_t agent = 0;
  Frame frame = 0;
  std::optional<Eigen::Vector2d> position;
};

/// Moves the selected vertices rigidly: p ↦ pivot + R(rotation) (p − pivot) + offset.
struct Drag {
  Selection selection;
  Eigen::Vector2d offset{0, 0};          ///< metres
  double rotation = 0.0;                 ///< radians, counter-clockwise
  std::optional<Eigen::Vector2d> pivot;  ///< metres; default: the centroid of the selected original positions
};

/// p(agent) − p(other) = offset at every sample of the frame range (default offset: the original one).
struct RelativePosition {
  std::int64_t agent = 0;
  std::int64_t other = 0;
  Frame first_frame = 0;
  Frame last_frame = -1;
  std::optional<Eigen::Vector2d> offset;
};

/// The agent's velocity at `frame` (m/s), measured as (p(frame + 1) − p(frame)) / Δt.
struct Velocity {
  std::int64_t agent = 0;
  Frame frame = 0;
  Eigen::Vector2d velocity{0, 0};
};

/// The agent stays on the line through `point` along `direction` at every sample of the frame range.
struct OnLine {
  std::int64_t agent = 0;
  Frame first_frame = 0;
  Frame last_frame = -1;
  Eigen::Vector2d point{0, 0};
  Eigen::Vector2d direction{1, 0};  ///< any non-zero length
};

/// The agent's acceleration at `frame` (m/s²): the second derivative of the parabola through its positions at
/// three consecutive frames t0 < t1 < t2 (h0 = t1 − t0, h1 = t2 − t1; the three-point formula for unequal spacing),
///   a = 2 [(p2 − p1)/h1 − (p1 − p0)/h0] / (h0 + h1),   equal spacing: (p(f+1) − 2p(f) + p(f−1)) / Δt².
/// The frames are f − 1, f, f + 1; at the clip's first frame f, f + 1, f + 2 and at its last f − 2, f − 1, f
/// (one-sided: the same parabola's acceleration, first order accurate there). A clip of fewer than three frames
/// is a ConfigError. Its rows (x and y) are that formula times h0 h1 (in metres, like the others):
///   (h1 p0 − (h0 + h1) p1 + h0 p2) / h̄ = a h0 h1,  h̄ = (h0 + h1)/2;  equal spacing: p0 − 2p1 + p2 = a Δt²,
/// and the output residual is measured the same way.
struct Acceleration {
  std::int64_t agent = 0;
  Frame frame = 0;
  Eigen::Vector2d acceleration{0, 0};
};

/// Σ_k weights[k] · p(agents[k]) = value at every frame of the range: with the default weights 1/n, the agents'
/// centroid is held at `value` (default: the original's weighted sum at each frame, i.e. the centroid keeps its
/// path while the agents move around it). Agents distinct, weights finite and not all zero.
struct Sum {
  std::vector<std::int64_t> agents;         ///< at least one, each once
  std::vector<double> weights;              ///< one per agent; empty: 1/n each
  Frame first_frame = 0;
  Frame last_frame = -1;
  std::optional<Eigen::Vector2d> value;     ///< metres (for weights summing to 1); default: the original's sum
};

/// One term of a Row: coefficient · (the x or y coordinate of `agent` at `frame`).
struct RowTerm {
  std::int64_t agent = 0;
  Frame frame = 0;
  int axis = 0;  ///< 0: x, 1: y
  double coefficient = 1.0;
};

/// A user's own linear constraint, one scalar row: Σ_j terms[j].coefficient · p(agent_j, frame_j)[axis_j] = value.
/// Every term's frame becomes a sample. Terms distinct in (agent, frame, axis), coefficients finite and not all
/// zero. Its residual is measured as the distance to the row's hyperplane, |Σ c x − value| / ‖c‖ (metres).
struct Row {
  std::vector<RowTerm> terms;
  double value = 0.0;
};

using Constraint = std::variant<RelativePosition, Velocity, OnLine, Acceleration, Sum, Row>;

/// What the user asks for. Messages name entries as pins[k], drags[k], constraints[k].
struct Request {
  std::vector<Pin> pins;
  std::vector<Drag> drags;
  std::vector<Constraint> constraints;
};

/// Sizes, timings (seconds) and solver facts of an edit, for logs, reports and benchmarks.
struct Report {
  std::size_t samples = 0, agents = 0, unknowns = 0;
  std::size_t spatial_features = 0, temporal_features = 0, spatiotemporal_features = 0;
  std::size_t handles = 0;           ///< handled vertices
  std::size_t constraint_rows = 0;   ///< scalar general-constraint rows
  std::vector<std::int64_t> left_out;  ///< agents absent somewhere in the clip (not edited, not in the output)
  double graph_seconds = 0;      ///< clip, Delaunay, features, both systems assembled
  double precompute_seconds = 0; ///< analyse and factorise both steps (and Schur complements)
  double analyze_seconds = 0;    ///< of which: assembling AᵀWA and the symbolic analyses, both steps
  double factorize_seconds = 0;  ///< of which: the numeric factorisations, both steps
  double solve_seconds = 0;      ///< last deform(): step 1, fitting, step 2
  double step1_seconds = 0;      ///< of which: step 1's solve
  double fit_seconds = 0;        ///< of which: the triangle fits (step 2's targets)
  std::string factorization;     ///< backend method of step 1 (for example "CHOLMOD supernodal LLᵀ (METIS)")
  std::string fallback;          ///< non-empty when the backend fell back, saying why
  double max_constraint_residual = 0;  ///< metres, general constraints at the samples, over both steps, last deform()
  /// metres: the largest violation of a handle or constraint at any output frame it covers (velocity: times
  /// Δt; acceleration: times h0 h1; a row: over its coefficients' norm), measured on the resampled output by
  /// max_request_residual(); set by edit_group_motion and the program
  double max_output_residual = 0;
  int factorizations = 0;              ///< numeric factorisations so far, both steps (a drag adds none)
  int analyses = 0;                    ///< symbolic analyses computed so far, both steps (step 2 reuses step 1's)
  int schur_columns = 0;               ///< back-substitutions spent on constraint columns so far, both steps
  double factor_nonzeros = 0;          ///< entries of both steps' Cholesky factors, last precompute (direct backends)
  /// The smaller of both steps' reciprocal condition estimates, last precompute (direct backends; 0 when the
  /// backend gives none). Rounding in a solve moves vertices by about unknowns · ε / reciprocal_condition times
  /// the scene's size: the tests derive their tolerances from it.
  double reciprocal_condition = 0;
  // Local edits only (Options::local.parts > 0), last deform():
  int parts = 0;                       ///< parts of the partition
  int region_parts = 0;                ///< parts solved
  std::size_t region_vertices = 0;     ///< vertices solved (the rest kept their current positions)
  std::size_t region_boundary = 0;     ///< vertices outside the region pinned because features tie them to it
  int regions_built = 0;               ///< regions assembled and factorised so far (a cached region adds none)
  double partition_seconds = 0;        ///< METIS
  // How the global systems were solved (Editor; SolverOptions::method):
  std::string method;                  ///< "direct" or "iterative" ("auto" resolved)
  int iterations = 0;                  ///< iterative: conjugate-gradient iterations of the last deform(), both steps
  int precompute_iterations = 0;       ///< iterative: the most any precompute solve took (handle bases, constraint columns, probe drags)
  /// iterative: the estimated error left by the last deform()'s conjugate gradients (metres; linalg's
  /// conjugate_gradients.h: the last step times ρ/(1 − ρ)), at most SolverOptions::position_tolerance (0: no
  /// iteration was needed)
  double solver_error_m = 0;
  std::size_t coarse_size = 0;         ///< iterative: functions in the preconditioner's coarse space
  /// With SolverOptions::compare_direct, the last deform() against the direct solve of the same request:
  /// the largest distance between a sample's position and the direct one (metres; −1: not compared) and the
  /// direct solve's own max_constraint_residual.
  double direct_difference_m = -1;
  double direct_constraint_residual_m = -1;
};

/// The stateful editor: build once, precompute once per handle set, deform per drag.
///   positions (samples)  #samples*#agents by 2, row = clip().vertex(sample, agent)
class Editor {
 public:
  /// Builds the clip (the request's frames become samples), the graph, the features and both systems.
  /// Throws ConfigError for options or a request that do not fit the crowd (unknown agent, frame outside the
  /// clip, an agent left out of the clip, bad values), naming the entry.
  Editor(const CrowdMotion& crowd, const Options& options, const Request& request);
  ~Editor();
  Editor(const Editor&) = delete;
  Editor& operator=(const Editor&) = delete;

  /// Analyses and factorises both steps for the current handles and constraints, and solves step 1's fixed
  /// right-hand side once (so no drag pays that back-substitution). Throws NumericalError when the system is
  /// singular (naming an agent and frame that are not determined) or the constraints contradict each other.
  /// `drags_follow`: more drags of these handles will come (an interactive editor): the iterative method then also
  /// solves a few probe drags so that the first drags start close (docs/commands/edit.md); false for one solve.
  void precompute(bool drags_follow = true);

  /// Deforms for `request`. Same handled vertices and constraint kinds as before: back-substitutions only;
  /// otherwise the handles or constraints are replaced first (refactorisation, or a new Schur complement).
  /// Every frame it names must be a sample of this editor's clip (the constructor's request decides them: its pin
  /// and velocity frames and every frame of its ranges).
  /// Returns the final sample positions; throws NumericalError for contradictory constraints or handles.
  [[nodiscard]] const Eigen::Matrix<double, Eigen::Dynamic, 2>& deform(const Request& request);

  /// Step 1's result of the last deform() (equal to the final result without scale compensation).
  [[nodiscard]] const Eigen::Matrix<double, Eigen::Dynamic, 2>& step1() const noexcept;

  /// The edited clip at the source frame rate (see "Output" above): clip frames × clip agents, with the ids,
  /// radii and species of the input.
  [[nodiscard]] CrowdMotion resample(const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& samples) const;

  [[nodiscard]] const MotionGraph& graph() const noexcept;
  [[nodiscard]] const FeatureSet& features() const noexcept;
  [[nodiscard]] const Report& report() const noexcept;
  [[nodiscard]] const Options& options() const noexcept;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// Where a local edit meets the motion it left alone: the region's edge in time, i.e. pairs of consecutive
/// samples of one agent of which one was solved and the other held. The vertex outside is pinned at its current
/// position, so whatever the edit moved the inside one by is added to that one step: the agent's velocity
/// changes within one sample interval. added_m measures it: |Δp_edited − Δp_input| per frame across the edge.
/// A jump is an added step larger than the agent could have made itself (jump_factor × its fastest input step,
/// floored at reference_floor × the clip's fastest, so that a standing agent nudged by millimetres is not one).
/// The pair reported is the edge pair with the largest added step against that reference.
struct BoundaryStep {
  /// An added step above this many times the agent's fastest input step is a jump a viewer sees: the agent's
  /// velocity changes by more than its own top speed within one frame (see docs/commands/scale.md, "Jumps at
  /// the region's edge", for the measurements behind it).
  static constexpr double jump_factor = 1.0;
  /// The reference is at least this fraction of the clip's fastest step (standing agents).
  static constexpr double reference_floor = 0.1;

  double added_m = 0;            ///< |Δp_edited − Δp_input| / frames across the edge, metres per frame (0: no edge)
  double edited_m = 0;           ///< the step there in the last result, metres per frame
  double input_m = 0;            ///< the input's step there, metres per frame
  double agent_input_max_m = 0;  ///< that agent's fastest input step over the clip, metres per frame
  double input_max_m = 0;        ///< the input's fastest step between consecutive samples, any agent, whole clip
  std::int64_t agent = -1;       ///< the agent id of that pair (−1: no agent crosses the edge)
  std::size_t frame = 0;         ///< the earlier input frame of that pair of samples

  /// The step an added step is judged against: max(agent_input_max_m, reference_floor · input_max_m).
  [[nodiscard]] double reference_m() const noexcept { return std::max(agent_input_max_m, reference_floor * input_max_m); }
  /// added_m > jump_factor · reference_m().
  [[nodiscard]] bool is_jump() const noexcept { return added_m > jump_factor * reference_m(); }
};

/// The result of a one-off edit.
struct Result {
  CrowdMotion crowd;  ///< the edited clip at the source frame rate: input frames first_frame..last_frame
  Report report;
  std::size_t first_frame = 0;             ///< the clip's first input frame
  std::size_t last_frame = 0;              ///< the clip's last input frame
  std::vector<std::size_t> sample_frames;  ///< the input frames the graph sampled
  std::optional<BoundaryStep> boundary;    ///< local edits: the step across the region's edge in time
};

/// One-off: build, precompute and deform once (what `throng edit` runs). With options.local.parts > 0 the edit
/// is local (a LocalEditor on the input positions): vertices outside the region keep their input positions.
/// `progress`, when given, hears each stage.
[[nodiscard]] Result edit_group_motion(const CrowdMotion& crowd, const Options& options, const Request& request,
                                       Progress* progress = nullptr);

/// The largest violation (metres) of `request` by `edited`, an edited clip at the source rate as Editor::resample
/// returns it (input frames first_frame.., agents by id): every pin, every drag target and every general
/// constraint at every frame it covers (a velocity as |Δp − v Δt|). `crowd` is the input the request refers to.
/// The request must fit (the editor checked it); otherwise std::invalid_argument.
[[nodiscard]] double max_request_residual(const CrowdMotion& crowd, const CrowdMotion& edited, std::size_t first_frame,
                                          const Request& request);

/// Checks option values (weights finite and ≥ 0, at least one term with a positive weight); throws ConfigError
/// naming the option. Called by Editor; exposed for job parsers that want to fail early.
void validate(const Options& options);

}  // namespace throng::edit
