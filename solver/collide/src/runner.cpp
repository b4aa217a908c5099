#include <throng/collide/runner.h>
#include <throng/collide/schema.h>
#include <throng/core/errors.h>

namespace throng::collide {

void describe(OptionBinder& b, Job& job) {
  describe(b, job.options);
  b.field({.key = "allow_remaining", .flag = "--allow-remaining",
           .help = "collisions left at the end are a warning, not a failure (exit 5)"},
          job.allow_remaining);
}

Run run(const Crowds& inputs, const Job& job, Progress& progress, const Communicator& communicator) {
  const Crowd& input = *inputs.at(0);
  Run out;
  Scene scene = input.scene;
  scene.obstacles.insert(scene.obstacles.end(), job.scene.obstacles.begin(), job.scene.obstacles.end());
  if (job.scene.region) scene.region = job.scene.region;
  if (scene.region && (scene.region->periodic[0] || scene.region->periodic[1])) {
    out.warnings.push_back("the crowd's region is periodic; distances are not wrapped, so pairs across its periodic "
                           "boundary are not repaired");
  }
  Result result = resolve_collisions(input.motion, scene.obstacles, job.options, progress, communicator);
  out.crowd.motion = std::move(result.crowd);
  out.crowd.scene = std::move(scene);
  out.crowd.formation_edges = input.formation_edges;
  out.report = std::move(result.report);
  if (!out.report.converged) out.shortfall = summary(out.report);
  return out;
}

void describe(ReportWriter& w, const Run& run) {
  const Report& r = run.report;
  w.count("agents", run.crowd.motion.agent_count());
  w.count("frames", run.crowd.motion.frame_count());
  w.count("obstacles", run.crowd.scene.obstacles.size());
  w.flag("converged", r.converged);
  w.text("stop_reason", r.stop_reason);
  w.count("iterations", r.iterations);
  w.count("initial_pair_contacts", r.initial_pair_contacts);
  w.count("initial_obstacle_contacts", r.initial_obstacle_contacts);
  w.count("pair_contacts", r.pair_contacts);
  w.count("obstacle_contacts", r.obstacle_contacts);
  w.count("stuck_contacts", r.stuck_contacts);
  w.count("pushed_points", r.constraints);
  w.count("abandoned_contacts", r.abandoned_contacts);
  w.count("moved_agents", r.moved_agents);
  w.count("limited_steps", r.limited_steps);  // deformations shortened to keep within the limits (collide.h "Limits")
  w.count("held_steps", r.held_steps);        // deformations dropped: no room within the limits
  w.number("min_pair_gap_m", r.min_pair_gap);
  w.number("min_obstacle_gap_m", r.min_obstacle_gap);
  w.number("max_displacement_m", r.max_displacement);
  w.number("max_speed_in_m_s", r.input_motion.max_speed);
  w.number("max_speed_out_m_s", r.output_motion.max_speed);
  w.number("speed_p99_out_m_s", r.output_motion.speed_p99);
  w.number("max_acceleration_in_m_s2", r.input_motion.max_acceleration);
  w.number("max_acceleration_out_m_s2", r.output_motion.max_acceleration);
  w.ranks("ranks", r.ranks);
  w.seconds("detect_s", r.detect_seconds);
  w.seconds("solve_s", r.solve_seconds);
}

}  // namespace throng::collide
