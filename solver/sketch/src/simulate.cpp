// simulate(): strokes → course → agents → simulation, sampled into a CrowdMotion at the output rate.
#include <throng/core/errors.h>
#include <throng/sketch/sketch.h>

#include <cmath>
#include <limits>

namespace throng::sketch {

SimulationResult simulate(const Drawing& drawing, const Scene& scene, const Options& options, Progress& progress) {
  validate(options);
  progress.update(0.0, "analysing strokes");
  Course course = analyse_strokes(drawing.strokes, options);
  AgentParameters agents = drawing.initial_positions.empty()
                               ? place_agents(course, options.agent_count, scene, options)
                               : agent_parameters(course, drawing.initial_positions, options);
  const std::size_t N = agents.agent_count();
  Simulation sim(std::move(course), std::move(agents), scene, options);

  SimulationResult result;
  CrowdMotion& motion = result.motion;
  motion.ids.resize(N);
  for (std::size_t j = 0; j < N; ++j) motion.ids[j] = static_cast<std::int64_t>(j);
  motion.radii.assign(N, options.agent_radius_m);
  motion.species.assign(N, 0);

  const bool fixed = options.duration_s > 0;
  const double end = fixed ? options.duration_s : options.max_duration_s;
  const double dt = options.time_step_s;
  // Frame m is at m / rate; a frame within a billionth of a step of the end still counts.
  const auto last_frame = static_cast<std::size_t>(std::floor(end * options.output_rate_hz * (1 + 1e-12) + 1e-9));
  // Room for every frame up front (with duration 0, up to max_duration's): no reallocation, whose copy would
  // need the old and the new block at once. Pages that no frame reaches are never touched.
  motion.positions.reserve((last_frame + 1) * N * 3);
  motion.orientations.reserve((last_frame + 1) * N * 4);
  motion.actions.reserve((last_frame + 1) * N);
  motion.action_table = standard_actions();
  motion.times.reserve(last_frame + 1);

  double finish = sim.finished() ? 0.0 : std::numeric_limits<double>::quiet_NaN();
  double reported = 0.0;
  progress.update(0.0, "simulating crowd");
  for (std::size_t m = 0; m <= last_frame; ++m) {
    const double time = static_cast<double>(m) / options.output_rate_hz;
    // Without a fixed duration, stop after the first frame at or after the moment everyone finished.
    if (!fixed && m > 0 && motion.times.back() >= finish) break;
    while (sim.time() < time - 1e-9 * dt) {
      sim.step();
      if (std::isnan(finish) && sim.finished()) finish = sim.time();
      const double fraction = fixed ? sim.time() / end : sim.path_fraction();
      if (fraction >= reported + 0.01) {
        reported = fraction;
        progress.update(std::min(fraction, 1.0), "simulating crowd");
      }
    }
    motion.times.push_back(time);
    motion.positions.resize(motion.positions.size() + 3 * N);
    sim.sample(time, std::span<double>(motion.positions.data() + m * 3 * N, 3 * N));
    motion.orientations.resize(motion.orientations.size() + 4 * N);
    motion.actions.resize(motion.actions.size() + N);
    sim.take_pose(time, std::span<double>(motion.orientations.data() + m * 4 * N, 4 * N),
                  std::span<std::int32_t>(motion.actions.data() + m * N, N));
  }
  progress.update(1.0, "simulating crowd");

  result.course = sim.course();
  result.agents = sim.agents();
  result.arrival_time_s.resize(N);
  for (std::size_t j = 0; j < N; ++j) result.arrival_time_s[j] = sim.arrival_time(j);
  result.step_count = sim.step_count();
  result.unresolved_obstacle_contacts = sim.unresolved_obstacle_contacts();
  result.finished = sim.finished();
  return result;
}

SimulationResult simulate(const Drawing& drawing, const Scene& scene, const Options& options) {
  NoProgress quiet;
  return simulate(drawing, scene, options, quiet);
}

}  // namespace throng::sketch
