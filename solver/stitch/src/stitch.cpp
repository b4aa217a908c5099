#include "text.h"
#include "window.h"

#include <throng/core/errors.h>
#include <throng/core/facing_carry.h>
#include <throng/core/parallel.h>
#include <throng/linalg/spd_solver.h>
#include <throng/stitch/schema.h>
#include <throng/stitch/stitch.h>
#include <throng/timewarp/guard.h>
#include <throng/timewarp/spline.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <string>

namespace throng::stitch {
namespace {

using Index = Eigen::Index;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// The agents present at every frame of a clip, and the ids of the others.
struct Presence {
  std::vector<std::size_t> agents;
  std::vector<std::int64_t> left_out;
};

Presence present_throughout(const CrowdMotion& crowd) {
  Presence p;
  for (std::size_t a = 0; a < crowd.agent_count(); ++a) {
    bool all = true;
    for (std::size_t f = 0; f < crowd.frame_count() && all; ++f) all = crowd.present(f, a);
    if (all) p.agents.push_back(a);
    else p.left_out.push_back(crowd.ids[a]);
  }
  return p;
}

Feature averaged(const Feature& a, const Feature& b) {
  Feature f = a;
  f.c = 0.5 * (a.c + b.c);
  f.offset = 0.5 * (a.offset + b.offset);
  f.weight = 0.5 * (a.weight + b.weight);
  return f;
}

// Facing and actions of the stitched clip (stitch.h "Facing"): frames 0..J from G's agents, J + 1.. from the
// matched agents of G′ turned by the alignment's `rotation`, both carried along the stitched paths. A clip without
// them while the other has them contributes the path's default. Nothing when neither clip has any.
void carry_clip_pose(const CrowdMotion& first, const CrowdMotion& second, CrowdMotion& out, const std::vector<std::size_t>& first_agents,
                     const std::vector<std::size_t>& partner, std::size_t J, double rotation) {
  const bool facing = !first.orientations.empty() || !second.orientations.empty();
  const bool acting = !first.actions.empty() || !second.actions.empty();
  if (!facing && !acting) return;
  std::optional<CrowdMotion> derived_first, derived_second;
  auto complete = [&](const CrowdMotion& clip, std::optional<CrowdMotion>& derived) -> const CrowdMotion& {
    if ((facing && clip.orientations.empty()) || (acting && clip.actions.empty())) {
      derived = clip;
      derive_path_pose(*derived);
      return *derived;
    }
    return clip;
  };
  const CrowdMotion& a = complete(first, derived_first);
  const CrowdMotion& b = complete(second, derived_second);
  const std::size_t T = out.frame_count(), n = out.agent_count();
  if (facing) out.orientations.assign(T * n * 4, absent);
  std::vector<std::int32_t> second_actions;
  if (acting) {
    out.actions.assign(T * n, -1);
    out.action_table = a.action_table;
    second_actions = merge_action_tables(b.action_table, out.action_table);
  }
  for (std::size_t j = 0; j < n; ++j) {
    carry_facing(a, out, CarriedSpan{first_agents[j], j, 0, J, 0, 0.0, nullptr});
    carry_facing(b, out, CarriedSpan{partner[j], j, J + 1, T - 1, -static_cast<std::ptrdiff_t>(J), rotation, &second_actions});
  }
}

}  // namespace

void validate(const Options& o) {
  check_options(describe, o, "");  // every range, guard's too (schema.cpp)
  timewarp::validate(o.guard, "guard");  // and the guard's rule between its two windows
}

double blend_weight(double distance, double window) noexcept {
  if (!(window > 0) || !detail::inside_window(distance, window)) return 0.0;
  const double x = std::max(distance, 0.0) / window;
  return 1.0 - 3.0 * x * x + 2.0 * x * x * x;
}

Result stitch_clips(const CrowdMotion& first, const CrowdMotion& second, const Options& options, Progress* progress) {
  validate(options);
  NoProgress quiet;
  Progress& report_to = progress ? *progress : quiet;
  const std::size_t t1 = first.frame_count(), t2 = second.frame_count();
  if (t1 < 2 || t2 < 2) {
    throw InputError("stitch: the " + std::string(t1 < 2 ? "first" : "second") + " clip has " + std::to_string(t1 < 2 ? t1 : t2) +
                     " frame(s); stitching needs at least 2 in each");
  }
  Result result;
  Report& report = result.report;
  const Presence pa = present_throughout(first), pb = present_throughout(second);
  report.left_out_first = pa.left_out;
  report.left_out_second = pb.left_out;
  if (pa.agents.empty() || pb.agents.empty()) {
    throw InputError(std::string("stitch: no agent of the ") + (pa.agents.empty() ? "first" : "second") +
                     " clip is present at all its frames; cut a shorter clip (throng split) first");
  }
  if (pa.agents.size() != pb.agents.size()) {
    throw InputError("stitch: the first clip has " + std::to_string(pa.agents.size()) + " agents present at all its frames, the second " +
                     std::to_string(pb.agents.size()) + " (left out: first " + detail::id_list(pa.left_out) + "; second " +
                     detail::id_list(pb.left_out) + "); stitching needs the same number in both");
  }
  const std::size_t n = pa.agents.size();
  const std::size_t J = t1 - 1;            // the joint, as a stitched frame
  const std::size_t T = t1 + t2 - 1;
  report.agents = n;
  report.frames_first = t1;
  report.frames_second = t2;
  report.frames = T;

  // 1–2. Correspondence and alignment.
  report_to.update(0.0, "matching agents");
  auto start = Clock::now();
  Points last_a(static_cast<Index>(n), 2), first_b(static_cast<Index>(n), 2);
  for (std::size_t j = 0; j < n; ++j) {
    last_a.row(static_cast<Index>(j)) = first.position(J, pa.agents[j]).head<2>().transpose();
    first_b.row(static_cast<Index>(j)) = second.position(0, pb.agents[j]).head<2>().transpose();
  }
  Headings headings;
  for (std::size_t j = 0; j < n; ++j) {
    headings.first += (first.position(J, pa.agents[j]) - first.position(J - 1, pa.agents[j])).head<2>() / static_cast<double>(n);
    headings.second += (second.position(1, pb.agents[j]) - second.position(0, pb.agents[j])).head<2>() / static_cast<double>(n);
  }
  const BoundaryFit fit = fit_boundary(last_a, first_b, headings, options.matching, options.alignment);
  const Correspondence& match = fit.correspondence;
  report.fit_starts = fit.starts;
  report.fit_rounds = fit.rounds;
  report.fit_start_rotation = fit.start_rotation;
  std::vector<std::size_t> partner(n);  // the agent of `second` (index into it) matched to result agent j
  for (std::size_t j = 0; j < n; ++j) {
    partner[j] = pb.agents[match.second_of_first[j]];
    result.second_ids.push_back(second.ids[partner[j]]);
    if (second.ids[partner[j]] == first.ids[pa.agents[j]]) ++report.matched_same_id;
  }
  report.matching_distance = match.total_distance;
  result.alignment = fit.alignment;
  const Eigen::Isometry2d& M = result.alignment;
  report.rotation = std::atan2(M.linear()(1, 0), M.linear()(0, 0));
  report.translation = M.translation();
  report.matching_seconds = seconds_since(start);

  // Input positions of the stitched clip (G, then aligned G′ from its second frame): the pins and the base of
  // the output.
  auto naive = [&](std::size_t F, std::size_t j) -> Eigen::Vector2d {
    if (F <= J) return first.position(F, pa.agents[j]).head<2>();
    return M * Eigen::Vector2d(second.position(F - J, partner[j]).head<2>());
  };
  auto aligned_second = [&](std::size_t f, std::size_t j) -> Eigen::Vector2d {
    return M * Eigen::Vector2d(second.position(f, partner[j]).head<2>());
  };
  std::vector<Eigen::Vector2d> joint_shift(n);  // D_j = w(J) − v(J) = (G′(0) − G(J)) / 2
  double gap_sum = 0;
  for (std::size_t j = 0; j < n; ++j) {
    const Eigen::Vector2d gap = aligned_second(0, j) - naive(J, j);
    joint_shift[j] = 0.5 * gap;
    gap_sum += gap.squaredNorm();
    report.gap_max = std::max(report.gap_max, gap.norm());
  }
  report.gap_rms = std::sqrt(gap_sum / static_cast<double>(n));

  // Samples of the stitched clip and the window that is solved.
  report_to.update(0.1, "building the blended graph");
  start = Clock::now();
  std::vector<double> times(T);
  for (std::size_t F = 0; F < T; ++F) times[F] = F <= J ? first.times[F] : first.times[J] + (second.times[F - J] - second.times[0]);
  // The window per side (seconds, never past the clip's outer frame, where f_a must reach 0: that frame is pinned
  // at its input) and the samples.
  const detail::SampledWindow window =
      detail::sample_window(times, J, options.sample_step, options.blend_window, n, options.max_blend_vertices);
  const std::vector<std::size_t>& samples = window.samples;
  const std::size_t joint_sample = window.joint_sample;
  report.window_first = window.first_frames;
  report.window_second = window.second_frames;
  report.window_first_s = window.first_s;
  report.window_second_s = window.second_s;
  report.window_limited = window.limited;
  report.whole_clip_vertices = window.whole_vertices;
  report.samples = samples.size();
  // Ḡ at any stitched frame (Eq. 11). Unlike the aligned input, which jumps by the whole gap from J to J + 1, Ḡ
  // is continuous across the joint (G's side reaches the midpoint at J, G′'s side leaves it), and it equals the
  // input wherever f_a = 0.
  auto intermediate = [&](std::size_t F, std::size_t j) -> Eigen::Vector2d {
    if (F == J) return naive(J, j) + joint_shift[j];
    if (F < J) return naive(F, j) + blend_weight(times[J] - times[F], window.first_s) * joint_shift[j];
    return naive(F, j) - blend_weight(times[F] - times[J], window.second_s) * joint_shift[j];
  };
  const std::size_t lo = window.first_solved, hi = window.last_solved;  // the pinned window edges
  const std::size_t L = hi - lo + 1;
  report.solved_samples = L;
  report.unknowns = 2 * L * n;

  // Ḡ (Eq. 11) and the aligned input over the solved samples; vertex l·n + j is agent j at sample lo + l.
  Clip blended;
  blended.first_frame = samples[lo];
  blended.last_frame = samples[hi];
  blended.frames.assign(samples.begin() + static_cast<std::ptrdiff_t>(lo), samples.begin() + static_cast<std::ptrdiff_t>(hi) + 1);
  for (std::size_t F : blended.frames) blended.times.push_back(times[F]);
  for (std::size_t j = 0; j < n; ++j) {
    blended.agents.push_back(j);
    blended.ids.push_back(first.ids[pa.agents[j]]);
  }
  blended.positions.resize(static_cast<Index>(L * n), 2);
  Points input(static_cast<Index>(L * n), 2);
  for (std::size_t l = 0; l < L; ++l) {
    const std::size_t F = blended.frames[l];
    for (std::size_t j = 0; j < n; ++j) {
      const Index v = blended.vertex(l, j);
      input.row(v) = naive(F, j).transpose();
      blended.positions.row(v) = intermediate(F, j).transpose();
    }
  }
  // Formation edits (by id of G, frames of the stitched clip) act at the solved samples in their range; one
  // whose range holds none changes nothing here (it may at another joint).
  FormationOptions formation = options.formation;
  formation.edits.clear();
  for (std::size_t k = 0; k < options.formation.edits.size(); ++k) {
    const EdgeEdit& e = options.formation.edits[k];
    for (std::int64_t id : {e.agent_a, e.agent_b}) {
      if (blended.agent_of_id(id) < 0) {
        throw ConfigError("formation.edits[" + std::to_string(k) + "]: agent " + std::to_string(id) +
                          " is not among the first clip's agents present at all its frames");
      }
    }
    const auto at = std::lower_bound(blended.frames.begin(), blended.frames.end(), e.first_frame);
    if (at != blended.frames.end() && *at <= e.last_frame) formation.edits.push_back(e);
  }
  report.formation_edits = formation.edits.size();
  const MotionGraph graph = build_motion_graph(blended, formation);
  FeatureSet features = compute_features(graph, options.features);  // spatial and spatiotemporal from Ḡ

  // Temporal features: G's before the joint, G′'s after, their average at the joint.
  features.temporal.clear();
  auto position_at = [&](std::size_t g, std::size_t j, bool from_second) -> Eigen::Vector2d {
    const std::size_t F = samples[g];
    return from_second ? aligned_second(F - J, j) : naive(F, j);
  };
  auto temporal = [&](std::size_t g, std::size_t j, bool from_second, std::size_t at) {
    // The feature of samples (g − 1, g, g + 1) of one clip, placed on the triple around local sample `at`.
    const int u = static_cast<int>(blended.vertex(at - 1, j)), v = static_cast<int>(blended.vertex(at, j)),
              w = static_cast<int>(blended.vertex(at + 1, j));
    return make_feature(u, v, w, position_at(g - 1, j, from_second), position_at(g, j, from_second),
                        position_at(g + 1, j, from_second), options.features);
  };
  for (std::size_t l = 1; l + 1 < L; ++l) {
    const std::size_t g = lo + l;
    for (std::size_t j = 0; j < n; ++j) {
      if (g != joint_sample) {
        features.temporal.push_back(temporal(g, j, g > joint_sample, l));
        continue;
      }
      const bool has_first = g >= 2, has_second = g + 2 < samples.size();
      if (has_first && has_second) {
        Feature before = temporal(g - 1, j, false, l);  // G's feature at the sample before the joint
        const Feature after = temporal(g + 1, j, true, l);  // G′'s feature at the sample after the joint
        features.temporal.push_back(averaged(before, after));
      } else if (has_first || has_second) {
        features.temporal.push_back(has_first ? temporal(g - 1, j, false, l) : temporal(g + 1, j, true, l));
      } else {
        const int u = static_cast<int>(blended.vertex(l - 1, j)), v = static_cast<int>(blended.vertex(l, j)),
                  w = static_cast<int>(blended.vertex(l + 1, j));
        features.temporal.push_back(make_feature(u, v, w, blended.positions.row(u).transpose(), blended.positions.row(v).transpose(),
                                                 blended.positions.row(w).transpose(), options.features));
      }
    }
  }
  report.spatial_features = features.spatial.size();
  report.temporal_features = features.temporal.size();
  report.spatiotemporal_features = features.spatiotemporal.size();

  // Pins: the two outer samples of the solved window, at their aligned input positions.
  std::vector<Index> pinned;
  for (std::size_t j = 0; j < n; ++j) pinned.push_back(blended.vertex(0, j));
  for (std::size_t j = 0; j < n; ++j) pinned.push_back(blended.vertex(L - 1, j));
  Points targets(static_cast<Index>(pinned.size()), 2);
  for (std::size_t k = 0; k < pinned.size(); ++k) targets.row(static_cast<Index>(k)) = input.row(pinned[k]);
  report.graph_seconds = seconds_since(start);

  // 4. One solve of the section-1 system.
  report_to.update(0.3, "solving the stitched graph");
  edit::FeatureDeformation solved;
  try {
    solved = edit::deform_with_features(features, blended.positions, pinned, targets, options.weights, options.solver);
  } catch (const linalg::SingularMatrixError& e) {
    throw NumericalError(std::string("stitch: the blended system is singular (") + e.what() +
                         "): nothing ties part of the graph to the pinned ends, for example an agent joined to no "
                         "neighbour (a single agent, or formation.max_edge_length too short) while weights.alpha or "
                         "weights.beta is 0; raise those weights or formation.max_edge_length");
  }
  report.factorization = solved.factorization;
  report.precompute_seconds = solved.precompute_seconds;
  report.solve_seconds = solved.solve_seconds;

  // The output at every source frame: the input outside the solved window; inside it the solved samples, and
  // between samples Ḡ plus a spline of the displacement from Ḡ (solved − Ḡ at the samples). Interpolating the
  // displacement from the aligned input instead would carry the input's jump at the joint into the frames
  // between samples whenever sample_step > 1.
  report_to.update(0.9, "resampling");
  CrowdMotion& out = result.crowd;
  out = CrowdMotion::with_shape(T, n);
  out.times = times;
  for (std::size_t j = 0; j < n; ++j) {
    out.ids[j] = first.ids[pa.agents[j]];
    out.radii[j] = first.radii[pa.agents[j]];
    out.species[j] = first.species[pa.agents[j]];
  }
  parallel_for(T, 64, [&](std::size_t begin, std::size_t end) {
    for (std::size_t F = begin; F < end; ++F) {
      for (std::size_t j = 0; j < n; ++j) {
        const double z = F <= J ? first.position(F, pa.agents[j]).z() : second.position(F - J, partner[j]).z();
        out.position(F, j) << naive(F, j), z;
      }
    }
  });
  timewarp::RowMatrix displacement(static_cast<Index>(L), static_cast<Index>(2 * n));
  for (std::size_t l = 0; l < L; ++l) {
    for (std::size_t j = 0; j < n; ++j) {
      const Index v = blended.vertex(l, j);
      displacement.block<1, 2>(static_cast<Index>(l), static_cast<Index>(2 * j)) = solved.positions.row(v) - blended.positions.row(v);
      report.max_change = std::max(report.max_change, (solved.positions.row(v) - input.row(v)).norm());
    }
  }
  const timewarp::CubicSpline spline(blended.times, displacement);
  const std::size_t first_frame = blended.first_frame, last_frame = blended.last_frame;
  parallel_for(last_frame - first_frame + 1, 16, [&](std::size_t begin, std::size_t end) {
    Eigen::RowVectorXd d(static_cast<Index>(2 * n));
    for (std::size_t F = first_frame + begin; F < first_frame + end; ++F) {
      const auto at = std::lower_bound(blended.frames.begin(), blended.frames.end(), F);
      if (*at == F) {
        const auto l = static_cast<std::size_t>(at - blended.frames.begin());
        for (std::size_t j = 0; j < n; ++j) out.position(F, j).head<2>() = solved.positions.row(blended.vertex(l, j)).transpose();
        continue;
      }
      spline.evaluate(times[F], 0, d);
      for (std::size_t j = 0; j < n; ++j) {
        out.position(F, j).head<2>() = intermediate(F, j) + d.segment<2>(static_cast<Index>(2 * j)).transpose();
      }
    }
  });
  carry_clip_pose(first, second, out, pa.agents, partner, J, report.rotation);
  // Plausibility: the guard, with the clips themselves as the source (stitch.h "Plausibility").
  report_to.update(0.95, "guarding speed and acceleration");
  timewarp::Source source;
  source.max_speed = std::max(timewarp::fastest_speed(first), timewarp::fastest_speed(second));
  const std::vector<double> first_acceleration = timewarp::accelerations(first), second_acceleration = timewarp::accelerations(second);
  source.acceleration.assign(T * n, 0.0);
  for (std::size_t F = 0; F < T; ++F) {
    for (std::size_t j = 0; j < n; ++j) {
      source.acceleration[F * n + j] = F < J   ? first_acceleration[F * first.agent_count() + pa.agents[j]]
                                       : F > J ? second_acceleration[(F - J) * second.agent_count() + partner[j]]
                                               : 0.0;
    }
  }
  timewarp::GuardResult guarded = timewarp::guard(out, source, options.guard);
  out = std::move(guarded.crowd);
  report.guard = guarded.report;
  report_to.update(1.0, "stitched");
  return result;
}

}  // namespace throng::stitch
