// throng check-motion CROWD.h5 [--reference IN.h5] [limits]: the independent motion checker (solver/check):
// speeds, accelerations, turning rates, displacement from the reference, contacts; a JSON (or key: value)
// report; exit 5 when a limit is broken. docs/commands/check-motion.md is the README section.
// The limits and settings are check/schema.h (flags, --set, --print-config).
// Facings: the crowd file's orientations when it carries them (yaw of the forward axis +x), else none.
#include <throng/check/motion_check.h>
#include <throng/check/schema.h>
#include <throng/core/errors.h>

#include <memory>
#include <optional>

#include "../option_flags.h"
#include "factories.h"

namespace throng::cli {
namespace {

Report distribution(const check::Distribution& d) {
  return {{"samples", d.samples}, {"p50", d.p50}, {"p95", d.p95}, {"p99", d.p99}, {"max", d.max},
          {"max_agent", d.max_agent}, {"max_time_s", d.max_time}};
}

Report measures(const check::Statistics& s) {
  Report r = {{"agents", s.agents}, {"frames", s.frames}, {"speed_m_s", distribution(s.speed)},
              {"acceleration_m_s2", distribution(s.acceleration)},
              {"tangential_acceleration_m_s2", distribution(s.tangential_acceleration)},
              {"normal_acceleration_m_s2", distribution(s.normal_acceleration)},
              {"turning_rate_rad_s", distribution(s.turning_rate)},
              {"pair_contacts", s.contacts.pairs}, {"deepest_pair_overlap_m", s.contacts.deepest_pair},
              {"obstacle_contacts", s.contacts.obstacle}, {"deepest_obstacle_overlap_m", s.contacts.deepest_obstacle}};
  if (s.has_facing) r["facing_rate_rad_s"] = distribution(s.facing_rate);
  if (s.has_reference) {
    r["displacement_m"] = distribution(s.displacement);
    r["reference_unmatched_agents"] = s.reference_unmatched;
  }
  return r;
}

nlohmann::ordered_json bound(double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr); }

class CheckMotionCommand final : public Command {
 public:
  std::string name() const override { return "check-motion"; }
  std::string summary() const override {
    return "Check that a crowd moves as people can: speed, acceleration, turning, displacement, contacts";
  }

  void setup(CLI::App& app) override {
    app.add_option("crowd", crowd_, "Crowd file to check (.h5)")->required();
    app.add_option("--reference", reference_, "The input it was made from: displacement, and limits from its statistics");
    flags_.add(app, static_cast<void (*)(OptionBinder&, check::Job&)>(check::describe));
  }

  void run(Context& context) override {
    check::Job job;
    const YAML::Node effective = context.options(flags_.overrides(), name(), check::describe, job,
                                                 {{"crowd", crowd_.string()}, {"reference", reference_.string()}});
    if (context.print_config_if_asked(effective)) return;
    context.limit_threads();
    const CrowdFile crowd = read_crowd_file(crowd_);
    std::optional<CrowdFile> reference;
    if (!reference_.empty()) reference = read_crowd_file(reference_);
    const CrowdMotion* ref = reference ? &reference->motion : nullptr;
    const std::optional<check::FacingSeries> facing = check::facings_of(crowd.motion);
    const check::Statistics s = check::measure(crowd.motion, crowd.scene.obstacles, job.settings, ref, facing ? &*facing : nullptr);
    std::optional<check::Statistics> input;
    if (reference) input = check::measure(reference->motion, crowd.scene.obstacles, job.settings);
    const check::Limits limits = check::limits_of(job, input ? &*input : nullptr);
    const check::Verdict verdict = check::check(s, limits);
    Report r = {{"crowd", crowd_.string()}, {"passed", verdict.passed()}, {"measures", measures(s)}};
    if (input) r["reference"] = {{"file", reference_.string()}, {"measures", measures(*input)}};
    r["limits"] = {{"max_speed", bound(limits.max_speed)}, {"max_acceleration", bound(limits.max_acceleration)},
                   {"acceleration_p99", bound(limits.acceleration_p99)}, {"max_turning_rate", bound(limits.max_turning_rate)},
                   {"turning_rate_p99", bound(limits.turning_rate_p99)}, {"max_facing_rate", bound(limits.max_facing_rate)},
                   {"max_displacement", bound(limits.max_displacement)},
                   {"max_pair_contacts", limits.max_pair_contacts ? Report(*limits.max_pair_contacts) : Report(nullptr)},
                   {"max_obstacle_contacts", limits.max_obstacle_contacts ? Report(*limits.max_obstacle_contacts) : Report(nullptr)}};
    Report broken = Report::array();
    for (const check::Violation& v : verdict.violations) broken.push_back(check::describe(v));
    r["violations"] = broken;
    context.print(r);
    if (!verdict.passed()) {
      throw NumericalError("check-motion: " + std::to_string(verdict.violations.size()) + " limit(s) broken in " +
                           crowd_.string() + ": " + check::describe(verdict.violations.front()));
    }
  }

 private:
  std::filesystem::path crowd_, reference_;
  OptionFlags flags_;
};

}  // namespace

std::unique_ptr<Command> make_check_motion_command() { return std::make_unique<CheckMotionCommand>(); }

}  // namespace throng::cli
