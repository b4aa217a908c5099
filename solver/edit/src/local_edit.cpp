// LocalEditor: the Editor's two steps over the region an edit reaches (see throng/edit/local_edit.h).
#include "edit_result.h"
#include "request.h"
#include "resample.h"
#include "systems.h"

#include <throng/core/timer.h>
#include <throng/core/errors.h>
#include <throng/edit/local_edit.h>
#include <throng/linalg/least_squares.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <list>
#include <set>
#include <string>

namespace throng::edit {
namespace {

using Index = Eigen::Index;
using Positions = Eigen::Matrix<double, Eigen::Dynamic, 2>;
using Clock = std::chrono::steady_clock;


// One factorised region: the subproblem over R's unknowns with its boundary and handles pinned.
//   vertices  local → graph vertex: R (increasing), then the boundary B (increasing)
//   pinned    local vertices pinned, in set_pinned order: the handles inside R (increasing), then B
// Pins go to the solvers as coordinates in a basis (linalg set_pin_basis, as the Editor does): the handles'
// rows of the request's handle basis, restricted to the coordinates they use (`columns`), and zero rows for
// B. B's current positions enter through the right-hand sides instead: b − A_B x_B (A_B: the objective's
// columns of B), which leaves the residual A x − b unchanged since A_B x_B is what B's rows would contribute.
// So a drag changes only the handle coordinates: step 1's right-hand side stays put (no back-substitution),
// step 2 costs one; a commit changes x_B, costing step 1 one back-substitution at the next drag, never a new Z.
struct Region {
  Region(const linalg::SolverOptions& solver) : step1_solver(solver), step2_solver(solver) {}

  // Key.
  std::vector<int> parts;
  std::vector<Index> handles;  // graph vertices of the handles inside R, increasing
  // State the key allows to change (updated in place: a new Schur complement or a new Z, no refactorisation).
  linalg::SparseMatrix C;      // the constraint rows on local unknowns
  linalg::SparseMatrix basis;  // 2·#pinned by #columns (empty: pin values, see use_basis)
  std::vector<Index> columns;  // the request's handle coordinates the basis uses
  bool use_basis = false;
  std::uint64_t resolution = 0;  // the State::resolution C and basis were made from
  // Subproblem.
  std::vector<int> vertices;
  std::size_t inside = 0;
  std::vector<Index> pinned;
  FeatureSet features;  // local indices
  Positions original;   // local original positions (the triangles step 2 restores)
  Objective step1, step2;
  linalg::SparseMatrix step1_boundary, step2_boundary;  // A_B of both steps (columns of B's unknowns)
  Eigen::VectorXd boundary_values;                       // x_B the shifts were computed for (interleaved)
  Eigen::VectorXd step1_b, step2_shift;                  // b₁ − A₁_B x_B, and A₂_B x_B
  linalg::ConstrainedLeastSquares step1_solver, step2_solver;
  std::uint64_t last_used = 0;
};

// A region whose handles have more basis coordinates than the solver precomputes solves pins as values.
constexpr Index max_basis_columns = linalg::ConstrainedLeastSquares::max_basis_columns;

// Local copy of the features touching R (any of u, v, w inside), in the global order; fills `local_of` for the
// boundary vertices they reach (appended to `vertices`).
std::vector<Feature> touching(const std::vector<Feature>& all, const std::vector<int>& inside_mark, std::vector<int>& local_of,
                              std::vector<int>& boundary) {
  std::vector<Feature> out;
  for (const Feature& f : all) {
    const auto u = static_cast<std::size_t>(f.u), v = static_cast<std::size_t>(f.v), w = static_cast<std::size_t>(f.w);
    if (!inside_mark[u] && !inside_mark[v] && !inside_mark[w]) continue;
    for (std::size_t x : {u, v, w}) {
      if (local_of[x] == -1) {
        local_of[x] = -2;  // boundary, numbered once all are known
        boundary.push_back(static_cast<int>(x));
      }
    }
    out.push_back(f);
  }
  return out;
}


// The rows of the request's handle basis for the handles `handle_rows` (indices into handle_vertices, in
// order), then `boundary` vertices' zero rows; the coordinates those rows use, in increasing order, become the
// columns (`columns[c]` is local column c's index into handle_coordinates).
void local_basis(const ResolvedRequest& resolved, const std::vector<Index>& handle_rows, std::size_t boundary,
                 linalg::SparseMatrix& basis, std::vector<Index>& columns) {
  const linalg::SparseMatrix& B = resolved.handle_basis;
  std::vector<Index> row_of(static_cast<std::size_t>(B.rows()), -1);
  for (std::size_t i = 0; i < handle_rows.size(); ++i) {
    row_of[static_cast<std::size_t>(2 * handle_rows[i])] = 2 * static_cast<Index>(i);
    row_of[static_cast<std::size_t>(2 * handle_rows[i] + 1)] = 2 * static_cast<Index>(i) + 1;
  }
  columns.clear();
  std::vector<Eigen::Triplet<double>> entries;
  for (Index c = 0; c < B.outerSize(); ++c) {
    bool used = false;
    for (linalg::SparseMatrix::InnerIterator it(B, c); it; ++it) {
      const Index row = row_of[static_cast<std::size_t>(it.row())];
      if (row < 0) continue;
      used = true;
      entries.emplace_back(row, static_cast<Index>(columns.size()), it.value());
    }
    if (used) columns.push_back(c);
  }
  basis.resize(2 * static_cast<Index>(handle_rows.size() + boundary), static_cast<Index>(columns.size()));
  basis.setFromTriplets(entries.begin(), entries.end());
  basis.makeCompressed();
}

}  // namespace

struct LocalEditor::State {
  explicit State(const Options& o) : options(o) {}

  Options options;
  std::vector<std::int64_t> crowd_ids;
  CrowdMotion source;
  MotionGraph graph;
  FeatureSet features;
  Partition partition;
  // result equals current except over `region` (the last deform's solved vertices): a deform or a commit
  // touches the region's rows only, so a drag's cost does not grow with the crowd.
  Positions current, result;
  std::vector<int> region, region_parts;
  std::list<Region> cache;  // std::list: solvers stay put while others come and go
  std::uint64_t clock = 0;
  // The last request and its resolution (redrag: a drag that moves the same handles again resolves only its own
  // handles), numbered: a region made from the same numbered resolution keeps its C and basis unchecked.
  Request last_request;
  ResolvedRequest last_resolved;
  std::uint64_t resolution = 0;
  int retired_factorizations = 0, retired_analyses = 0, retired_schur_columns = 0;
  Report report;
  // Scratch over graph vertices, all −1 / 0 between calls.
  std::vector<int> local_of;
  std::vector<int> inside_mark;

  [[nodiscard]] const Clip& clip() const { return graph.clip; }

  std::string vertex_name(Index v) const {
    const auto n = static_cast<Index>(clip().agent_count());
    return "agent " + std::to_string(clip().ids[static_cast<std::size_t>(v % n)]) + " at frame " +
           std::to_string(clip().frames[static_cast<std::size_t>(v / n)]);
  }

  // The constraint rows on the region's local unknowns (local_of filled for the region).
  // Without constraints no column of C is visited (C has one per unknown of the whole crowd: walking them would
  // make every cached drag's cost grow with the crowd).
  linalg::SparseMatrix local_constraints(const linalg::SparseMatrix& C, Index local_vertices) const {
    if (C.nonZeros() == 0) return linalg::SparseMatrix(C.rows(), 2 * local_vertices);
    std::vector<Eigen::Triplet<double>> entries;
    for (Index k = 0; k < C.outerSize(); ++k) {
      for (linalg::SparseMatrix::InnerIterator it(C, k); it; ++it) {
        const int local = local_of[static_cast<std::size_t>(it.col() / 2)];
        entries.emplace_back(it.row(), 2 * static_cast<Index>(local) + it.col() % 2, it.value());
      }
    }
    linalg::SparseMatrix out(C.rows(), 2 * local_vertices);
    out.setFromTriplets(entries.begin(), entries.end());
    out.makeCompressed();
    return out;
  }

  void fill_local_of(const Region& r) {
    for (std::size_t i = 0; i < r.vertices.size(); ++i) local_of[static_cast<std::size_t>(r.vertices[i])] = static_cast<int>(i);
  }
  void clear_local_of(const std::vector<int>& vertices) {
    for (int v : vertices) local_of[static_cast<std::size_t>(v)] = -1;
  }

  // Gives both steps of r the pin basis (or takes it away: see max_basis_columns).
  void apply_basis(Region& r) {
    r.use_basis = !r.columns.empty() && static_cast<Index>(r.columns.size()) <= max_basis_columns;
    const linalg::SparseMatrix none(r.basis.rows(), 0);
    r.step1_solver.set_pin_basis(r.use_basis ? r.basis : none);
    if (options.scale_compensation) r.step2_solver.set_pin_basis(r.use_basis ? r.basis : none);
  }

  // Assembles and factorises the region of `parts` (vertices R, marked in inside_mark) for the handles inside
  // it (`handles`, their indices into the request's handle_vertices in `handle_rows`), at the cache's front. A
  // throw anywhere leaves neither the region in the cache nor local_of marked.
  Region& build(const std::vector<int>& parts, const std::vector<Index>& handles, const std::vector<Index>& handle_rows,
                const ResolvedRequest& resolved) {
    Region& r = cache.emplace_front(options.solver);
    try {
      assemble(r, parts, handles, handle_rows, resolved);
    } catch (...) {
      clear_local_of(region);
      clear_local_of(r.vertices);
      cache.pop_front();
      throw;
    }
    // Keep the cache within its limit (the new region is at the front and stays).
    while (cache.size() > static_cast<std::size_t>(options.local.max_cached_regions)) {
      auto oldest = std::min_element(std::next(cache.begin()), cache.end(),
                                     [](const Region& a, const Region& b) { return a.last_used < b.last_used; });
      retired_factorizations += oldest->step1_solver.report().factorizations + oldest->step2_solver.report().factorizations;
      retired_analyses += analyses_of(*oldest);
      retired_schur_columns += oldest->step1_solver.report().schur_columns + oldest->step2_solver.report().schur_columns;
      cache.erase(oldest);
    }
    return r;
  }

  // build()'s work on the new region r.
  void assemble(Region& r, const std::vector<int>& parts, const std::vector<Index>& handles, const std::vector<Index>& handle_rows,
                const ResolvedRequest& resolved) {
    const auto start = Clock::now();
    r.parts = parts;
    r.handles = handles;
    r.vertices = region;
    r.inside = region.size();
    for (std::size_t i = 0; i < region.size(); ++i) local_of[static_cast<std::size_t>(region[i])] = static_cast<int>(i);
    std::vector<int> boundary;
    r.features.spatial = touching(features.spatial, inside_mark, local_of, boundary);
    r.features.temporal = touching(features.temporal, inside_mark, local_of, boundary);
    r.features.spatiotemporal = touching(features.spatiotemporal, inside_mark, local_of, boundary);
    std::sort(boundary.begin(), boundary.end());
    r.vertices.insert(r.vertices.end(), boundary.begin(), boundary.end());
    fill_local_of(r);
    for (auto* set : {&r.features.spatial, &r.features.temporal, &r.features.spatiotemporal}) {
      for (Feature& f : *set) {
        f.u = local_of[static_cast<std::size_t>(f.u)];
        f.v = local_of[static_cast<std::size_t>(f.v)];
        f.w = local_of[static_cast<std::size_t>(f.w)];
      }
    }
    for (Index h : handles) r.pinned.push_back(local_of[static_cast<std::size_t>(h)]);
    for (std::size_t i = r.inside; i < r.vertices.size(); ++i) r.pinned.push_back(static_cast<Index>(i));
    const auto n = static_cast<Index>(r.vertices.size());
    r.original.resize(n, 2);
    for (Index i = 0; i < n; ++i) r.original.row(i) = clip().positions.row(r.vertices[static_cast<std::size_t>(i)]);
    r.C = local_constraints(resolved.C, n);
    clear_local_of(r.vertices);
    local_basis(resolved, handle_rows, boundary.size(), r.basis, r.columns);

    std::vector<Index> pinned_unknowns;
    pinned_unknowns.reserve(2 * r.pinned.size());
    for (Index v : r.pinned) {
      pinned_unknowns.push_back(2 * v);
      pinned_unknowns.push_back(2 * v + 1);
    }
    const auto inside_unknowns = 2 * static_cast<Index>(r.inside), boundary_unknowns = 2 * n - inside_unknowns;
    const Eigen::MatrixXd modes = similarity_modes(r.original);
    r.step1 = step1_objective(r.features, n, options.alpha, options.beta);
    r.step1_boundary = r.step1.A.middleCols(inside_unknowns, boundary_unknowns);
    r.step1_solver.set_objective(r.step1.A, r.step1.weights);
    r.step1_solver.set_near_null_space(modes, 2);
    r.step1_solver.set_complex_pairs(true);
    r.step1_solver.set_pinned(pinned_unknowns);
    r.step1_solver.set_constraints(r.C);
    if (options.scale_compensation) {
      r.step2 = step2_objective(r.features, n, options.alpha_prime, options.beta_prime);
      r.step2_boundary = r.step2.A.middleCols(inside_unknowns, boundary_unknowns);
      r.step2_solver.set_objective(r.step2.A, r.step2.weights);
      r.step2_solver.set_near_null_space(modes, 2);
      r.step2_solver.set_complex_pairs(true);
      r.step2_solver.set_pinned(pinned_unknowns);
      r.step2_solver.set_constraints(r.C);
      // Same features, same pins: step 2's Q_FF has step 1's pattern, so it copies step 1's analysis.
      r.step2_solver.share_analysis(&r.step1_solver);
    }
    apply_basis(r);
    in_region_terms(r, [&] {
      r.step1_solver.analyze();
      if (options.scale_compensation) r.step2_solver.analyze();
      r.step1_solver.precompute();
      if (options.scale_compensation) r.step2_solver.precompute();
      return 0;
    }, nullptr);
    r.resolution = resolution;  // made from this resolution's constraints and basis
    ++report.regions_built;
    report.precompute_seconds = seconds_since(start);
    const linalg::LeastSquaresReport& one = r.step1_solver.report();
    const linalg::LeastSquaresReport& two = r.step2_solver.report();
    const bool both = options.scale_compensation;
    report.analyze_seconds = one.analyze_seconds + (both ? two.analyze_seconds : 0.0);
    report.factorize_seconds = one.factorize_seconds + (both ? two.factorize_seconds : 0.0);
    report.factorization = one.factorization.method;
    report.fallback = one.factorization.fallback_reason;
    report.factor_nonzeros = one.factorization.factor_nonzeros + (both ? two.factorization.factor_nonzeros : 0.0);
    report.reciprocal_condition = one.factorization.reciprocal_condition;
    if (both) {
      const double step2 = two.factorization.reciprocal_condition;
      if (step2 > 0 && (report.reciprocal_condition <= 0 || step2 < report.reciprocal_condition)) report.reciprocal_condition = step2;
    }
  }

  // The right-hand sides' boundary terms for B's current positions (recomputed only when those changed: the
  // first drag of a region and the first after a commit that moved B).
  void refresh_boundary(Region& r) const {
    const std::size_t nb = r.vertices.size() - r.inside;
    Eigen::VectorXd xb(2 * static_cast<Index>(nb));
    for (std::size_t i = 0; i < nb; ++i) xb.segment<2>(2 * static_cast<Index>(i)) = current.row(r.vertices[r.inside + i]).transpose();
    if (r.step1_b.size() > 0 && r.boundary_values.size() == xb.size() && r.boundary_values == xb) return;
    r.step1_b = r.step1.b;
    if (nb > 0) r.step1_b.noalias() -= r.step1_boundary * xb;
    if (options.scale_compensation) r.step2_shift = r.step2_boundary * xb;
    r.boundary_values = std::move(xb);
  }

  static int analyses_of(const Region& r) {
    const auto& one = r.step1_solver.report();
    const auto& two = r.step2_solver.report();
    return one.analyses + two.analyses - one.adopted_analyses - two.adopted_analyses;
  }

  // Runs a solver step of region r, turning its errors into messages in the user's terms.
  template <typename Step>
  auto in_region_terms(const Region& r, Step&& step, const Request* request, const ResolvedRequest* resolved = nullptr)
      -> decltype(step()) {
    try {
      return step();
    } catch (const linalg::SingularMatrixError& e) {
      const Index unknown = e.index();
      const std::string where =
          unknown >= 0 && static_cast<std::size_t>(unknown / 2) < r.vertices.size()
              ? " (first undetermined: " + vertex_name(r.vertices[static_cast<std::size_t>(unknown / 2)]) + ")"
              : std::string();
      throw NumericalError("the local region (" + std::to_string(r.parts.size()) + " parts, " + std::to_string(r.inside) +
                           " vertices) is singular: " + e.what() + where +
                           "; pin or drag two vertices of every group in it, or widen local.halo");
    } catch (const linalg::ConstraintError& e) {
      if (request == nullptr || resolved == nullptr) throw;
      std::set<std::size_t> sources;
      for (Index row : e.rows()) sources.insert(resolved->row_source[static_cast<std::size_t>(row)]);
      std::string names;
      for (std::size_t k : sources) names += (names.empty() ? "" : " and ") + describe(*request, k);
      throw NumericalError("contradictory constraints: " + names + " cannot all be met with the pins, the drags and the "
                           "local region's boundary [" + std::string(e.what()) + "]");
    }
  }

  void update_counts() {
    report.factorizations = retired_factorizations;
    report.analyses = retired_analyses;
    report.schur_columns = retired_schur_columns;
    for (const Region& r : cache) {
      report.factorizations += r.step1_solver.report().factorizations + r.step2_solver.report().factorizations;
      report.analyses += analyses_of(r);
      report.schur_columns += r.step1_solver.report().schur_columns + r.step2_solver.report().schur_columns;
    }
  }
};

LocalEditor::LocalEditor(const CrowdMotion& crowd, const Options& options, const Request& request)
    : state_(std::make_unique<State>(options)) {
  validate(options);
  if (options.local.parts < 1) {
    throw ConfigError("local.parts " + std::to_string(options.local.parts) + ": expected ≥ 1 for a local edit (or auto: "
                      "parts of about local.vertices_per_part vertices)");
  }
  if (options.local.vertices_per_part < 1) {
    throw ConfigError("local.vertices_per_part " + std::to_string(options.local.vertices_per_part) + ": expected ≥ 1");
  }
  State& s = *state_;
  const auto start = Clock::now();
  s.crowd_ids = crowd.ids;
  const Clip bounds = make_clip(crowd, options.clip);
  const std::vector<std::size_t> frames = required_frames(request, bounds, crowd.ids);
  s.graph = build_motion_graph(make_clip(crowd, options.clip, frames), options.formation);
  s.features = compute_features(s.graph, options.features);
  s.source = slice_clip(crowd, s.graph.clip);
  s.current = s.graph.clip.positions;
  s.result = s.current;
  const std::size_t vertices = s.graph.vertex_count();
  const bool by_size = options.local.parts == LocalOptions::by_size;
  if (!by_size && static_cast<std::size_t>(options.local.parts) > vertices) {
    throw ConfigError("local.parts " + std::to_string(options.local.parts) + ": the clip's graph has only " +
                      std::to_string(vertices) + " vertices");
  }
  s.last_resolved = resolve(request, s.graph.clip, s.crowd_ids);  // fails early on a request that does not fit
  s.last_request = request;
  s.resolution = 1;
  Report& r = s.report;
  r.graph_seconds = seconds_since(start);
  const auto partition_start = Clock::now();
  // By size: blocks of samples × groups of agents (partition_time_blocks: linear in the samples, parts whose
  // extent does not depend on the crowd's size); by count: METIS on the whole space-time graph.
  s.partition = by_size ? partition_time_blocks(s.graph, options.local.vertices_per_part, {.seed = options.local.seed})
                        : partition_graph(space_time_adjacency(s.graph), {.parts = options.local.parts, .seed = options.local.seed});
  r.partition_seconds = seconds_since(partition_start);
  s.local_of.assign(vertices, -1);
  s.inside_mark.assign(vertices, 0);
  r.samples = s.graph.sample_count();
  r.agents = s.graph.agent_count();
  r.unknowns = 2 * vertices;
  r.spatial_features = s.features.spatial.size();
  r.temporal_features = s.features.temporal.size();
  r.spatiotemporal_features = s.features.spatiotemporal.size();
  r.left_out = s.graph.clip.left_out;
  r.parts = s.partition.part_count();
}

LocalEditor::~LocalEditor() = default;

const Eigen::Matrix<double, Eigen::Dynamic, 2>& LocalEditor::deform(const Request& request) {
  State& s = *state_;
  Request next = request;  // copied first: the request and its resolution change together or not at all
  if (!redrag(s.last_resolved, s.last_request, next, s.graph.clip)) {
    s.last_resolved = resolve(next, s.graph.clip, s.crowd_ids);
    ++s.resolution;
  }
  s.last_request = std::move(next);
  const ResolvedRequest& resolved = s.last_resolved;
  Report& report = s.report;
  report.handles = resolved.handle_vertices.size();
  report.constraint_rows = static_cast<std::size_t>(resolved.C.rows());

  // The last result back to the current positions (over its region only).
  for (int v : s.region) s.result.row(v) = s.current.row(v);
  s.region.clear();
  s.region_parts.clear();

  // 1. Reached parts: moved handles and constrained vertices.
  std::vector<int> seeds;
  for (std::size_t k = 0; k < resolved.handle_vertices.size(); ++k) {
    const Index v = resolved.handle_vertices[k];
    if (resolved.handle_targets.row(static_cast<Index>(k)) != s.current.row(v)) seeds.push_back(s.partition.part_of[static_cast<std::size_t>(v)]);
  }
  for (Index k = 0; resolved.C.nonZeros() > 0 && k < resolved.C.outerSize(); ++k) {
    for (linalg::SparseMatrix::InnerIterator it(resolved.C, k); it; ++it) {
      seeds.push_back(s.partition.part_of[static_cast<std::size_t>(it.col() / 2)]);
    }
  }
  std::sort(seeds.begin(), seeds.end());
  seeds.erase(std::unique(seeds.begin(), seeds.end()), seeds.end());
  const auto start = Clock::now();
  report.region_parts = 0;
  report.region_vertices = report.region_boundary = 0;
  report.max_constraint_residual = 0;
  report.step1_seconds = report.fit_seconds = 0;
  if (seeds.empty()) {
    report.solve_seconds = seconds_since(start);
    return s.result;
  }

  // 2. The region: reached parts and their halo.
  s.region_parts = parts_within(s.partition, seeds, s.options.local.halo);
  for (int part : s.region_parts) {
    const auto& list = s.partition.parts[static_cast<std::size_t>(part)];
    s.region.insert(s.region.end(), list.begin(), list.end());
  }
  std::sort(s.region.begin(), s.region.end());
  for (int v : s.region) s.inside_mark[static_cast<std::size_t>(v)] = 1;
  std::vector<Index> handles;  // handles inside R (increasing, as handle_vertices)
  std::vector<Index> handle_rows;
  for (std::size_t k = 0; k < resolved.handle_vertices.size(); ++k) {
    if (s.inside_mark[static_cast<std::size_t>(resolved.handle_vertices[k])]) {
      handles.push_back(resolved.handle_vertices[k]);
      handle_rows.push_back(static_cast<Index>(k));
    }
  }

  // 3. A cached region of the same parts and handles (its constraints and pin basis brought up to date:
  // a new Schur complement or a new Z, never a refactorisation), or a new one.
  Region* region = nullptr;
  for (Region& r : s.cache) {
    if (r.parts == s.region_parts && r.handles == handles) {
      region = &r;
      break;
    }
  }
  try {
    if (region == nullptr) {
      region = &s.build(s.region_parts, handles, handle_rows, resolved);
    } else if (region->resolution != s.resolution) {
      Region& r = *region;
      s.fill_local_of(r);
      linalg::SparseMatrix C = s.local_constraints(resolved.C, static_cast<Index>(r.vertices.size()));
      s.clear_local_of(r.vertices);
      if (!same_matrix(C, r.C)) {
        r.step1_solver.set_constraints(C);
        if (s.options.scale_compensation) r.step2_solver.set_constraints(C);
        r.C = std::move(C);
      }
      linalg::SparseMatrix basis;
      std::vector<Index> columns;
      local_basis(resolved, handle_rows, r.vertices.size() - r.inside, basis, columns);
      if (columns != r.columns || !same_matrix(basis, r.basis)) {
        std::swap(r.basis, basis);
        std::swap(r.columns, columns);
        try {
          s.apply_basis(r);
        } catch (...) {  // the old basis back, so that the next deform finds the change and applies it again
          std::swap(r.basis, basis);
          std::swap(r.columns, columns);
          throw;
        }
      }
      r.resolution = s.resolution;  // only once both are up to date (a throw above leaves it to be done again)
    }
  } catch (...) {
    for (int v : s.region) s.inside_mark[static_cast<std::size_t>(v)] = 0;
    throw;
  }
  for (int v : s.region) s.inside_mark[static_cast<std::size_t>(v)] = 0;
  Region& r = *region;
  r.last_used = ++s.clock;

  // 4. Pins: the handles' coordinates (or their targets), B at zero with its current positions in the
  // right-hand sides (see Region); solve both steps.
  const auto solve_start = Clock::now();
  s.refresh_boundary(r);
  Eigen::VectorXd pins;
  if (r.use_basis) {
    pins.resize(static_cast<Index>(r.columns.size()));
    for (std::size_t c = 0; c < r.columns.size(); ++c) pins[static_cast<Index>(c)] = resolved.handle_coordinates[r.columns[c]];
  } else {
    pins = Eigen::VectorXd::Zero(2 * static_cast<Index>(r.pinned.size()));
    for (std::size_t k = 0; k < handle_rows.size(); ++k) {
      pins.segment<2>(2 * static_cast<Index>(k)) = resolved.handle_targets.row(handle_rows[k]).transpose();
    }
  }
  auto solve = [&](linalg::ConstrainedLeastSquares& solver, const Eigen::VectorXd& b) {
    return as_positions(s.in_region_terms(
        r, [&] { return r.use_basis ? solver.solve_in_basis(b, pins, resolved.d) : solver.solve(b, pins, resolved.d); },
        &request, &resolved));
  };
  Positions x = solve(r.step1_solver, r.step1_b);
  report.max_constraint_residual = r.step1_solver.report().max_constraint_residual;
  report.step1_seconds = seconds_since(solve_start);
  if (s.options.scale_compensation) {
    const auto fit_start = Clock::now();
    // The fits read B's triangles at their current positions (the solver holds B at zero).
    for (std::size_t i = r.inside; i < r.vertices.size(); ++i) x.row(static_cast<Index>(i)) = s.current.row(r.vertices[i]);
    set_step2_targets(r.features, r.original, x, r.step2.b);
    Eigen::VectorXd b = r.step2.b;
    if (r.step2_shift.size() > 0) b -= r.step2_shift;
    report.fit_seconds = seconds_since(fit_start);
    x = solve(r.step2_solver, b);
    report.max_constraint_residual = std::max(report.max_constraint_residual, r.step2_solver.report().max_constraint_residual);
  }
  for (std::size_t i = 0; i < r.inside; ++i) s.result.row(r.vertices[i]) = x.row(static_cast<Index>(i));

  report.region_parts = static_cast<int>(s.region_parts.size());
  report.region_vertices = r.inside;
  report.region_boundary = r.vertices.size() - r.inside;
  report.solve_seconds = seconds_since(solve_start);
  s.update_counts();
  return s.result;
}

void LocalEditor::commit() {
  State& s = *state_;
  for (int v : s.region) s.current.row(v) = s.result.row(v);
}

const Eigen::Matrix<double, Eigen::Dynamic, 2>& LocalEditor::current() const noexcept { return state_->current; }
const std::vector<int>& LocalEditor::region() const noexcept { return state_->region; }
const std::vector<int>& LocalEditor::region_parts() const noexcept { return state_->region_parts; }

BoundaryStep LocalEditor::boundary_step() const {
  const State& s = *state_;
  const Clip& clip = s.clip();
  const Positions& input = clip.positions;
  const std::size_t agents = clip.agent_count();
  std::vector<char> inside(static_cast<std::size_t>(input.rows()), 0);
  for (int v : s.region) inside[static_cast<std::size_t>(v)] = 1;
  auto gap = [&](std::size_t i) { return static_cast<double>(clip.frames[i + 1] - clip.frames[i]); };
  // Each agent's fastest input step, and the clip's.
  BoundaryStep b;
  std::vector<double> fastest(agents, 0.0);
  for (std::size_t i = 0; i + 1 < clip.frames.size(); ++i) {
    for (std::size_t j = 0; j < agents; ++j) {
      const double step = (input.row(clip.vertex(i + 1, j)) - input.row(clip.vertex(i, j))).norm() / gap(i);
      fastest[j] = std::max(fastest[j], step);
    }
  }
  for (double f : fastest) b.input_max_m = std::max(b.input_max_m, f);
  // The edge pair whose added step is the largest against its agent's reference (see BoundaryStep).
  double worst = 0;
  for (std::size_t i = 0; i + 1 < clip.frames.size(); ++i) {
    for (std::size_t j = 0; j < agents; ++j) {
      const auto v0 = static_cast<Index>(clip.vertex(i, j)), v1 = static_cast<Index>(clip.vertex(i + 1, j));
      if (inside[static_cast<std::size_t>(v0)] == inside[static_cast<std::size_t>(v1)]) continue;
      const Eigen::RowVector2d before = input.row(v1) - input.row(v0), after = s.result.row(v1) - s.result.row(v0);
      const double added = (after - before).norm() / gap(i);
      const double reference = std::max(fastest[j], BoundaryStep::reference_floor * b.input_max_m);
      const double ratio = reference > 0 ? added / reference : (added > 0 ? std::numeric_limits<double>::infinity() : 0.0);
      if (b.agent < 0 || ratio > worst) {
        worst = ratio;
        b.added_m = added;
        b.edited_m = after.norm() / gap(i);
        b.input_m = before.norm() / gap(i);
        b.agent_input_max_m = fastest[j];
        b.agent = clip.ids[j];
        b.frame = clip.frames[i];
      }
    }
  }
  return b;
}

CrowdMotion LocalEditor::resample(const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& samples) const {
  if (samples.rows() != static_cast<Index>(state_->graph.vertex_count())) {
    throw std::invalid_argument("LocalEditor::resample: " + std::to_string(samples.rows()) + " rows for " +
                                std::to_string(state_->graph.vertex_count()) + " vertices");
  }
  return resample_clip(state_->source, state_->graph.clip, samples);
}

const MotionGraph& LocalEditor::graph() const noexcept { return state_->graph; }
const FeatureSet& LocalEditor::features() const noexcept { return state_->features; }
const Partition& LocalEditor::partition() const noexcept { return state_->partition; }
const Report& LocalEditor::report() const noexcept { return state_->report; }
const Options& LocalEditor::options() const noexcept { return state_->options; }

Result edit_locally(const CrowdMotion& crowd, const Options& options, const Request& request, Progress* progress) {
  NoProgress quiet;
  Progress& p = progress ? *progress : quiet;
  p.update(0.0, "edit: graph and partition");
  LocalEditor editor(crowd, options, request);
  p.update(0.3, "edit: local solve");
  const auto& samples = editor.deform(request);
  p.update(0.95, "edit: resample");
  return edit_result(editor, samples);
}

}  // namespace throng::edit
