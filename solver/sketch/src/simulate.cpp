// simulate(): strokes → course → agents → simulation, sampled at the output rate into a CrowdMotion or handed to a
// FrameSink frame by frame (a crowd file written as it goes).
#include <throng/core/errors.h>
#include <throng/sketch/sketch.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <span>

namespace throng::sketch {

namespace {

// The in-memory sink: every frame appended to a CrowdMotion, room for all of them reserved up front (with
// duration 0, up to max_duration's): no reallocation, whose copy would need the old and the new block at once.
// Pages that no frame reaches are never touched.
class MotionSink final : public FrameSink {
 public:
  explicit MotionSink(CrowdMotion& motion) : m_(motion) {}
  void start(std::size_t agents, std::size_t frames, bool) override {
    n_ = agents;
    m_.positions.reserve(frames * n_ * 3);
    m_.orientations.reserve(frames * n_ * 4);
    m_.actions.reserve(frames * n_);
  }
  Frame next_frame() override {
    const std::size_t m = m_.positions.size() / (3 * n_);
    m_.positions.resize(m_.positions.size() + 3 * n_);
    m_.orientations.resize(m_.orientations.size() + 4 * n_);
    m_.actions.resize(m_.actions.size() + n_);
    return {std::span<double>(m_.positions.data() + m * 3 * n_, 3 * n_),
            std::span<double>(m_.orientations.data() + m * 4 * n_, 4 * n_),
            std::span<std::int32_t>(m_.actions.data() + m * n_, n_)};
  }
  void commit() override {}

 private:
  CrowdMotion& m_;
  std::size_t n_ = 0;
};

}  // namespace

SimulationResult simulate(const Drawing& drawing, const Scene& scene, const Options& options, FrameSink& sink,
                          Progress& progress) {
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
  sink.start(N, last_frame + 1, fixed);
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
    const FrameSink::Frame frame = sink.next_frame();
    sim.sample(time, frame.positions);
    sim.take_pose(time, frame.orientations, frame.actions);
    sink.commit();
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

SimulationResult simulate(const Drawing& drawing, const Scene& scene, const Options& options, Progress& progress) {
  CrowdMotion motion;
  MotionSink sink(motion);
  SimulationResult result = simulate(drawing, scene, options, sink, progress);
  result.motion.positions = std::move(motion.positions);
  result.motion.orientations = std::move(motion.orientations);
  result.motion.actions = std::move(motion.actions);
  return result;
}

SimulationResult simulate(const Drawing& drawing, const Scene& scene, const Options& options) {
  NoProgress quiet;
  return simulate(drawing, scene, options, quiet);
}

}  // namespace throng::sketch
