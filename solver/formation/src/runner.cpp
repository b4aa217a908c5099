#include <throng/core/format.h>
#include <throng/formation/plausibility.h>
#include <throng/formation/runner.h>
#include <throng/formation/schema.h>

#include <algorithm>
#include <iterator>

namespace throng::formation {
namespace {

std::size_t group_count(const Group& g) {
  std::size_t n = 1;
  for (const Group& s : g.subgroups) n += group_count(s);
  return n;
}

}  // namespace

void describe(OptionBinder& b, Job& job) { describe(b, job.options); }

std::vector<std::array<std::int32_t, 2>> kept_edges(const Result& result) {
  const auto& graphs = result.keyframe_edges;
  std::vector<Pair> kept = graphs.empty() ? std::vector<Pair>{} : graphs.front();
  for (std::size_t k = 1; k < graphs.size(); ++k) {
    std::vector<Pair> both;
    std::set_intersection(kept.begin(), kept.end(), graphs[k].begin(), graphs[k].end(), std::back_inserter(both));
    kept = std::move(both);
  }
  std::vector<std::array<std::int32_t, 2>> out;
  for (const Pair& e : kept) out.push_back({e[0], e[1]});
  return out;
}

Run run(const Crowds& inputs, const Job& job, Progress& progress, const Communicator&) {
  Run out;
  if (!inputs.empty()) out.crowd.scene = inputs.front()->scene;
  out.problem = job.problem;
  out.result = animate_formation(job.problem, job.options, progress);
  guard_formation(out.problem, out.result, job.options, progress);  // plausible speed and acceleration (plausibility.h)
  out.crowd.motion = std::move(out.result.motion);
  out.result.motion = CrowdMotion{};
  out.crowd.formation_edges = kept_edges(out.result);
  const CollisionReport& c = out.result.collision;
  if (c.ran && !c.satisfied) {
    out.shortfall = "individuals " + std::to_string(c.closest_pair[0]) + " and " + std::to_string(c.closest_pair[1]) + " are " +
                    with_digits(c.closest_m, 6) + " m apart at frame " + std::to_string(c.closest_frame) +
                    ", closer than collision.min_distance " + with_digits(job.options.collision.min_distance_m, 6) + " m";
  }
  return out;
}

void describe(ReportWriter& w, const Run& run) {
  const CrowdMotion& m = run.crowd.motion;
  const Result& r = run.result;
  w.count("agents", m.agent_count());
  w.count("frames", m.frame_count());
  w.number("duration_s", m.frame_count() ? m.times.back() - m.times.front() : 0.0);
  w.count("dimension", static_cast<std::size_t>(run.problem.keyframes.front().positions.cols()));
  w.count("keyframes", run.problem.keyframes.size());
  w.counts("keyframe_frames", r.keyframe_frames);
  w.count("groups", group_count(r.hierarchy));
  w.count("formation_edges", run.crowd.formation_edges.size());
  if (r.guard.speed_limit > 0) {
    // The plausibility guard (plausibility.h): how much it re-timed the keyframes and smoothed the paths.
    // guard_warped: the keyframes were re-timed.
    timewarp::describe(w, r.guard);
    w.number("guard_speed_limit_m_s", r.guard.speed_limit);
    w.number("guard_max_speed_before_m_s", r.guard.max_speed_before);
  }
  if (!r.collision.ran) return;
  w.flag("collision_satisfied", r.collision.satisfied);
  w.number("closest_m", r.collision.closest_m);
  w.number("largest_shift_m", r.collision.largest_shift_m);
}

}  // namespace throng::formation
