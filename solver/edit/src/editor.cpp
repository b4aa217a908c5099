#include "direct_steps.h"
#include "edit_result.h"
#include "iterative_steps.h"
#include "request.h"
#include "resample.h"
#include "systems.h"

#include <throng/core/timer.h>
#include <throng/core/errors.h>
#include <throng/core/union_find.h>
#include <throng/edit/edit.h>
#include <throng/edit/schema.h>
#include <throng/edit/local_edit.h>
#include <throng/linalg/least_squares.h>
#include <throng/linalg/solver_schema.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <set>
#include <sstream>
#include <utility>

namespace throng::edit {
namespace {

using Index = Eigen::Index;
using Positions = Eigen::Matrix<double, Eigen::Dynamic, 2>;
using Clock = std::chrono::steady_clock;


using Components = UnionFind;  // over graph vertices

}  // namespace

void validate(const Options& o) {
  check_options(describe, o, "");
  // The ranges are edit's schema; words are checked by their users (throng/core/schema.h), solver.method here.
  const std::vector<std::string>& methods = linalg::method_names();
  if (std::find(methods.begin(), methods.end(), o.solver.method) == methods.end()) {
    throw ConfigError("solver.method '" + o.solver.method + "': expected auto, direct or iterative");
  }
  // The one rule that ties two options together.
  if (o.solver.method == "iterative" && o.solver.backend != "eigen") {
    throw ConfigError("solver.method iterative runs in this process on its own solvers: it needs solver.backend eigen, not '" +
                      o.solver.backend + "' (use solver.method direct to solve with " + o.solver.backend + ")");
  }
}

namespace {

// SolverOptions::method resolved for a system of `free_vertices` unknown positions.
bool uses_iterative_method(const Options& o, std::size_t free_vertices) {
  if (o.solver.method == "iterative") return true;
  if (o.solver.method == "direct" || o.solver.backend != "eigen") return false;
  return free_vertices > o.solver.auto_direct_vertices;
}

}  // namespace

struct Editor::State {
  explicit State(const Options& o) : options(o) {}

  Options options;
  std::vector<std::int64_t> crowd_ids;
  CrowdMotion source;  // the clip's frames and agents at the source rate
  MotionGraph graph;
  FeatureSet features;
  std::unique_ptr<EditSteps> steps;  // the direct or the iterative method (edit_steps.h)
  ResolvedRequest current;
  bool has_request = false;
  Request request;  // the one `current` was resolved from, for messages
  Positions x1, x2;
  Report report;

  [[nodiscard]] const Clip& clip() const { return graph.clip; }

  std::string vertex_name(Index v) const {
    const auto n = static_cast<Index>(clip().agent_count());
    return "agent " + std::to_string(clip().ids[static_cast<std::size_t>(v % n)]) + " at frame " +
           std::to_string(clip().frames[static_cast<std::size_t>(v / n)]);
  }

  // Every part of the graph tied together by features (of terms with a positive weight) needs two handles
  // at distinct original places, or a handle on its only vertex: otherwise the step is singular. Step 1 weighs
  // the temporal and spatiotemporal terms by α, β, step 2 by α′, β′ (`alpha_key`, `beta_key` name them); the
  // spatial term (ES, or ESC in step 2) always has weight 1.
  void check_determined(const std::vector<Index>& handles, double alpha, double beta, const char* step,
                        const char* alpha_key, const char* beta_key) const {
    const std::size_t vertices = graph.vertex_count();
    Components parts(vertices);
    auto join = [&](const std::vector<Feature>& set, double weight) {
      if (weight <= 0) return;
      for (const Feature& f : set) {
        parts.join(static_cast<std::size_t>(f.u), static_cast<std::size_t>(f.v));
        parts.join(static_cast<std::size_t>(f.v), static_cast<std::size_t>(f.w));
      }
    };
    join(features.spatial, 1.0);
    join(features.temporal, alpha);
    join(features.spatiotemporal, beta);
    // Per part: its size, and a handle and whether a second one sits elsewhere.
    std::vector<std::size_t> size(vertices, 0);
    std::vector<Index> first_handle(vertices, -1);
    std::vector<char> spread(vertices, 0);
    for (std::size_t v = 0; v < vertices; ++v) ++size[parts.root(v)];
    const double scale = 1e-9 * (1.0 + clip().positions.cwiseAbs().maxCoeff());
    for (Index h : handles) {
      const std::size_t r = parts.root(static_cast<std::size_t>(h));
      if (first_handle[r] < 0) {
        first_handle[r] = h;
      } else if ((clip().positions.row(h) - clip().positions.row(first_handle[r])).norm() > scale) {
        spread[r] = 1;
      }
    }
    for (std::size_t v = 0; v < vertices; ++v) {
      if (parts.root(v) != v) continue;
      const bool determined = spread[v] || (size[v] == 1 && first_handle[v] >= 0);
      if (determined) continue;
      std::set<std::int64_t> agents;
      std::size_t first_frame = clip().last_frame, last_frame = clip().first_frame;
      const auto n = clip().agent_count();
      for (std::size_t u = 0; u < vertices; ++u) {
        if (parts.root(u) != v) continue;
        agents.insert(clip().ids[u % n]);
        first_frame = std::min(first_frame, clip().frames[u / n]);
        last_frame = std::max(last_frame, clip().frames[u / n]);
      }
      std::ostringstream list;
      std::size_t shown = 0;
      for (std::int64_t id : agents) {
        if (shown++ == 10) {
          list << ", ...";
          break;
        }
        list << (shown > 1 ? ", " : "") << id;
      }
      const std::string held = first_handle[v] < 0 ? "no handle" : "handles at one place only";
      const std::string span = " over frames " + std::to_string(first_frame) + ".." + std::to_string(last_frame);
      const std::string fix = "pin or drag at least two of its vertices at different places";
      if (alpha <= 0 && beta <= 0 && clip().sample_count() > 1) {
        // Nothing ties the samples together in time: each sample's formation floats on its own.
        throw NumericalError(std::string("the system of ") + step + " is singular: " + alpha_key + " and " + beta_key +
                             " are 0, so no feature ties one sample to the next and every sample's formation needs "
                             "its own handles; agent" + std::string(agents.size() > 1 ? "s " : " ") + list.str() + span +
                             " " + (first_handle[v] < 0 ? "have no handle" : "have handles at one place only") +
                             ": give " + alpha_key + " or " + beta_key + " a positive weight");
      }
      if (size[v] == vertices) {
        throw NumericalError("the system is singular: the clip holds " + held +
                             ", so the group's position, rotation and scale are free: " + fix);
      }
      throw NumericalError("the system is singular: agent" + std::string(agents.size() > 1 ? "s " : " ") + list.str() +
                           span + (agents.size() > 1 ? " form" : " forms") + " a group joined to the rest by no feature (cut off by formation.max_edge_length "
                           "or edge edits) with " + held + ", so its position, rotation and scale are free: " + fix +
                           ", or join it to the others");
    }
  }

  void apply(ResolvedRequest resolved, const Request& from) {
    if (!has_request || resolved.handle_vertices != current.handle_vertices) {
      check_determined(resolved.handle_vertices, options.alpha, options.beta, "step 1", "weights.alpha", "weights.beta");
      if (options.scale_compensation) {
        check_determined(resolved.handle_vertices, options.alpha_prime, options.beta_prime, "step 2 (scale compensation)",
                         "weights.alpha_prime", "weights.beta_prime");
      }
    }
    steps->apply(resolved, has_request ? &current : nullptr);
    current = std::move(resolved);
    request = from;
    has_request = true;
    report.handles = current.handle_vertices.size();
    report.constraint_rows = static_cast<std::size_t>(current.C.rows());
  }

  // The last deform() solved directly (a DirectSteps of its own, released afterwards): the report's
  // direct_difference_m and direct_constraint_residual_m.
  void compare_direct() {
    Options direct_options = options;
    direct_options.solver.method = "direct";
    direct_options.solver.backend = "eigen";
    DirectSteps direct(features, graph.clip.positions, direct_options);
    Positions y1, y2;
    Report direct_report;
    in_user_terms([&] {
      direct.apply(current, nullptr);
      direct.precompute(current);
      direct.solve(current, y1, y2, direct_report);
    });
    report.direct_difference_m = (y2 - x2).rowwise().norm().maxCoeff();
    report.direct_constraint_residual_m = direct_report.max_constraint_residual;
  }

  // Runs a solver step, turning its errors into messages in the user's terms.
  template <typename Step>
  auto in_user_terms(Step&& step) -> decltype(step()) {
    try {
      return step();
    } catch (const linalg::SingularMatrixError& e) {
      const Index unknown = e.index();
      throw NumericalError(std::string(e.what()) +
                           (unknown >= 0 ? " (first undetermined: " + vertex_name(unknown / 2) + ")" : std::string()));
    } catch (const linalg::ConstraintError& e) {
      std::set<std::size_t> sources;
      for (Index row : e.rows()) sources.insert(current.row_source[static_cast<std::size_t>(row)]);
      std::string names;
      for (std::size_t k : sources) names += (names.empty() ? "" : " and ") + describe(request, k);
      throw NumericalError("contradictory constraints: " + names +
                           (sources.size() == 1 ? " cannot be met together with the pins and drags"
                                                : " cannot all be met (with the pins and drags)") +
                           " [" + e.what() + "]");
    }
  }
};

Editor::Editor(const CrowdMotion& crowd, const Options& options, const Request& request)
    : state_(std::make_unique<State>(options)) {
  validate(options);
  State& s = *state_;
  const auto start = Clock::now();
  s.crowd_ids = crowd.ids;
  const Clip bounds = make_clip(crowd, options.clip);
  const std::vector<std::size_t> frames = required_frames(request, bounds, crowd.ids);
  s.graph = build_motion_graph(make_clip(crowd, options.clip, frames), options.formation);
  s.features = compute_features(s.graph, options.features);
  s.source = slice_clip(crowd, s.graph.clip);
  ResolvedRequest resolved = resolve(request, s.graph.clip, s.crowd_ids);
  const std::size_t free_vertices = s.graph.vertex_count() - resolved.handle_vertices.size();
  if (uses_iterative_method(options, free_vertices)) {
    s.steps = std::make_unique<IterativeSteps>(s.graph, s.features, options);
  } else {
    s.steps = std::make_unique<DirectSteps>(s.features, s.graph.clip.positions, options);
  }
  s.apply(std::move(resolved), request);

  Report& r = s.report;
  r.samples = s.graph.sample_count();
  r.agents = s.graph.agent_count();
  r.unknowns = 2 * s.graph.vertex_count();
  r.spatial_features = s.features.spatial.size();
  r.temporal_features = s.features.temporal.size();
  r.spatiotemporal_features = s.features.spatiotemporal.size();
  r.left_out = s.graph.clip.left_out;
  s.steps->describe(r);
  r.graph_seconds = seconds_since(start);
}

Editor::~Editor() = default;

void Editor::precompute(bool drags_follow) {
  State& s = *state_;
  s.steps->expect_drags(drags_follow);
  s.in_user_terms([&] { s.steps->precompute(s.current); });
  s.steps->expect_drags(true);  // a later precompute (new handles in a session) is for drags
  s.steps->describe(s.report);
}

const Eigen::Matrix<double, Eigen::Dynamic, 2>& Editor::deform(const Request& request) {
  State& s = *state_;
  s.apply(resolve(request, s.graph.clip, s.crowd_ids), request);
  if (!s.steps->is_ready()) precompute();
  s.in_user_terms([&] { s.steps->solve(s.current, s.x1, s.x2, s.report); });
  if (s.options.solver.compare_direct) s.compare_direct();
  return s.x2;
}

const Eigen::Matrix<double, Eigen::Dynamic, 2>& Editor::step1() const noexcept { return state_->x1; }

CrowdMotion Editor::resample(const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& samples) const {
  if (samples.rows() != static_cast<Index>(state_->graph.vertex_count())) {
    throw std::invalid_argument("Editor::resample: " + std::to_string(samples.rows()) + " rows for " +
                                std::to_string(state_->graph.vertex_count()) + " vertices");
  }
  return resample_clip(state_->source, state_->graph.clip, samples);
}

const MotionGraph& Editor::graph() const noexcept { return state_->graph; }
const FeatureSet& Editor::features() const noexcept { return state_->features; }
const Report& Editor::report() const noexcept { return state_->report; }
const Options& Editor::options() const noexcept { return state_->options; }

Result edit_group_motion(const CrowdMotion& crowd, const Options& options, const Request& request, Progress* progress) {
  NoProgress quiet;
  Progress& p = progress ? *progress : quiet;
  Result result;
  if (options.local.parts > 0) {
    result = edit_locally(crowd, options, request, &p);
  } else {
    p.update(0.0, "edit: graph");
    Editor editor(crowd, options, request);
    p.update(0.2, "edit: factorise");
    editor.precompute(false);  // one solve: no probe drags
    p.update(0.8, "edit: solve");
    const auto& samples = editor.deform(request);
    p.update(0.95, "edit: resample");
    result = edit_result(editor, samples);
  }
  result.report.max_output_residual = max_request_residual(crowd, result.crowd, result.first_frame, request);
  p.update(1.0, "edit: done");
  return result;
}

}  // namespace throng::edit
