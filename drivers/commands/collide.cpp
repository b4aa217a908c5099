// throng collide CROWD.h5 [--job COLLIDE.yaml] [flags] -o OUT.h5: push colliding trajectories apart, and out of
// obstacles, until every clearance holds (collision repair, solver/collide). Options come from the job file
// (io/collide/include/throng/io/collide_job.h), overridden by the flags, overridden by --set.
// docs/commands/collide.md is the README section.
//
// Collisions left at the end (iteration cap, or pinned frames that collide): the output and the report are
// written, then the command exits 5 (NumericalError) unless allow_remaining. As a `throng run` step the step
// fails (exit 5, the step writes nothing) unless allow_remaining, which turns it into a warning.
//
// Under mpiexec every rank runs the repair (the trajectories' solves are spread over the ranks and gathered,
// solver/collide), so every rank holds the result; rank 0 alone writes the output and prints the report.
#include <throng/collide/collide.h>
#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>
#include <throng/io/collide_job.h>
#include <throng/linalg/mpi.h>

#include <cmath>
#include <memory>
#include <optional>

#include "factories.h"

namespace throng::cli {
namespace {

/// A finished repair: the crowd to write, its method data, the report and the solver's report.
struct Collided {
  CrowdFile crowd;
  ExtraWriter extra;
  Report report;
  collide::Report result;
};

nlohmann::ordered_json metres(double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr); }

/// The work shared by `throng collide` and the `collide` step of `throng run`. Obstacles: the crowd's own, then
/// the job's.
Collided collide_crowd(const CrowdFile& input, const CollideJob& job, Context& context) {
  Scene scene = input.scene;
  scene.obstacles.insert(scene.obstacles.end(), job.scene.obstacles.begin(), job.scene.obstacles.end());
  if (job.scene.region) scene.region = job.scene.region;
  if (scene.region && (scene.region->periodic[0] || scene.region->periodic[1])) {
    context.warn("collide: the crowd's region is periodic; distances are not wrapped, so pairs across its "
                 "periodic boundary are not repaired");
  }
  auto result = std::make_shared<collide::Result>(collide::resolve_collisions(input.motion, scene.obstacles, job.options,
                                                                              context.progress()));
  const collide::Report& r = result->report;
  Collided c;
  c.crowd.motion = result->crowd;
  c.crowd.scene = scene;
  c.crowd.formation_edges = input.formation_edges;
  c.extra = [result](const h5::Group& g) { write_collide_data(g, result->report); };
  c.result = r;
  c.report["agents"] = result->crowd.agent_count();
  c.report["frames"] = result->crowd.frame_count();
  c.report["obstacles"] = scene.obstacles.size();
  c.report["converged"] = r.converged;
  c.report["stop_reason"] = r.stop_reason;
  c.report["iterations"] = r.iterations;
  c.report["initial_pair_contacts"] = r.initial_pair_contacts;
  c.report["initial_obstacle_contacts"] = r.initial_obstacle_contacts;
  c.report["pair_contacts"] = r.pair_contacts;
  c.report["obstacle_contacts"] = r.obstacle_contacts;
  c.report["stuck_contacts"] = r.stuck_contacts;
  c.report["pushed_points"] = r.constraints;
  c.report["abandoned_contacts"] = r.abandoned_contacts;
  c.report["moved_agents"] = r.moved_agents;
  c.report["min_pair_gap_m"] = metres(r.min_pair_gap);
  c.report["min_obstacle_gap_m"] = metres(r.min_obstacle_gap);
  c.report["max_displacement_m"] = r.max_displacement;
  c.report["max_speed_in_m_s"] = r.input_motion.max_speed;
  c.report["max_speed_out_m_s"] = r.output_motion.max_speed;
  c.report["speed_p99_out_m_s"] = r.output_motion.speed_p99;
  c.report["max_acceleration_in_m_s2"] = r.input_motion.max_acceleration;
  c.report["max_acceleration_out_m_s2"] = r.output_motion.max_acceleration;
  c.report["ranks"] = r.ranks;
  c.report["detect_s"] = r.detect_seconds;
  c.report["solve_s"] = r.solve_seconds;
  return c;
}

class CollideCommand final : public Command {
 public:
  std::string name() const override { return "collide"; }
  std::string summary() const override {
    return "Repair collisions: push trajectories apart and out of obstacles, keeping pinned frames";
  }

  void setup(CLI::App& app) override {
    app.add_option("crowd", input_, "Crowd file to repair (.h5)")->required();
    app.add_option("-o,--output", output_, "Crowd file to write (.h5): the repaired crowd")->required();
    app.add_option("--job", job_path_, "Collide job (.yaml); the flags below override its keys");
    app.add_option("--margin", margin_, "Clearance beyond the radii (m)");
    app.add_option("--push-fraction", push_fraction_, "A push separates a pair by this fraction of its clearance");
    app.add_option("--max-iterations", max_iterations_, "Solves at most");
    app.add_option("--spread", spread_, "Frames over which a push fades along a trajectory");
    app.add_option("--obstacle-pull", obstacle_pull_, "back | sideways | nearest")->check(CLI::IsMember({"back", "sideways", "nearest"}));
    app.add_flag("--no-pin-ends", no_pin_ends_, "Let the first and last frames move too");
    app.add_option("--fixed-agents", fixed_agents_, "Ids of agents that must not move")->delimiter(',');
    app.add_flag("--allow-remaining", allow_remaining_, "Collisions left at the end are a warning, not exit 5");
  }

  void run(Context& context) override {
    const ConfigNode job = load(context);
    const CollideJob parsed = read_collide_job(job);
    const YAML::Node effective = effective_collide_job(parsed);
    if (context.print_config_if_asked(effective)) return;
    check_distinct(input_, output_);
    if (!job_path_.empty()) check_distinct(job_path_, output_);
    context.limit_threads();
    { const AtomicOutput probe(output_); }  // a missing or read-only output folder fails now, not after the solve

    const bool writer = mpi::rank() == 0;  // starts MPI when launched by mpiexec
    const CrowdFile input = read_crowd_file(input_);
    Collided c = collide_crowd(input, parsed, context);
    std::vector<std::string> inputs{input_.string()};
    if (!job_path_.empty()) inputs.push_back(job_path_.string());
    c.crowd.provenance = context.provenance(effective, inputs, {&input.provenance});
    if (writer) {
      write_crowd_file(output_, c.crowd, c.extra);
      Report r;
      r["output"] = output_.string();
      r.update(c.report);
      context.print(r);
    }
    finish(c.result, parsed, context);
  }

  /// As a step: repairs the one crowd it reads; the step's keys are the job file's.
  std::optional<StepResult> run_step(const ConfigNode& step, const std::vector<const CrowdFile*>& inputs,
                                     Context& context) override {
    const CollideJob parsed = read_collide_job(step);
    if (inputs.size() != 1) step.fail("collide takes one crowd, found " + std::to_string(inputs.size()));
    Collided c = collide_crowd(*inputs.front(), parsed, context);
    c.crowd.provenance.credits = inputs.front()->provenance.credits;
    context.info("collide: " + c.report.dump());
    finish(c.result, parsed, context);
    return StepResult{std::move(c.crowd), std::move(c.extra)};
  }

 private:
  /// The job file (or nothing), the flags written over its keys, then --set.
  ConfigNode load(const Context& context) const {
    YAML::Node root(YAML::NodeType::Map);
    std::string source = "command line";
    if (!job_path_.empty()) {
      const ConfigNode file = ConfigNode::load_file(job_path_);
      if (!file.is_null()) {
        if (!file.is_map()) file.fail("a collide job is a mapping of options");
        root = YAML::Clone(file.yaml());
      }
      source = job_path_.string();
    }
    if (margin_) root["margin"] = *margin_;
    if (push_fraction_) root["push_fraction"] = *push_fraction_;
    if (max_iterations_) root["max_iterations"] = *max_iterations_;
    if (spread_) root["spread"] = *spread_;
    if (!obstacle_pull_.empty()) root["obstacle_pull"] = obstacle_pull_;
    if (no_pin_ends_) root["pin_ends"] = false;
    if (!fixed_agents_.empty()) root["fixed_agents"] = fixed_agents_;
    if (allow_remaining_) root["allow_remaining"] = true;
    apply_overrides(root, context.global.set);
    return ConfigNode(root, source);
  }

  /// Collisions left: a warning with allow_remaining, else a NumericalError (exit 5) naming what is left.
  static void finish(const collide::Report& r, const CollideJob& job, Context& context) {
    if (r.converged) return;
    if (job.allow_remaining) {
      context.warn("collide: " + collide::summary(r));
      return;
    }
    throw NumericalError("collide: " + collide::summary(r));
  }

  std::filesystem::path input_, output_, job_path_;
  std::optional<double> margin_, push_fraction_, spread_;
  std::optional<std::size_t> max_iterations_;
  std::string obstacle_pull_;
  bool no_pin_ends_ = false;
  std::vector<std::int64_t> fixed_agents_;
  bool allow_remaining_ = false;
};

}  // namespace

std::unique_ptr<Command> make_collide_command() { return std::make_unique<CollideCommand>(); }

}  // namespace throng::cli
