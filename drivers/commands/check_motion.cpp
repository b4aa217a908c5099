// throng check-motion CROWD.h5 [--reference IN.h5] [limits]: the independent motion checker (solver/check):
// speeds, accelerations, turning rates, displacement from the reference, contacts; a JSON (or key: value)
// report; exit 5 when a limit is broken. docs/commands/check-motion.md is the README section.
// Facings: the crowd file's orientations when it carries them (yaw of the forward axis +x), else none.
#include <throng/check/motion_check.h>
#include <throng/core/errors.h>

#include <memory>
#include <optional>

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
    app.add_option("--speed-ratio", speed_ratio_, "With --reference: max speed = this × the reference's")->check(CLI::PositiveNumber);
    app.add_option("--max-speed", max_speed_, "m/s")->check(CLI::PositiveNumber);
    app.add_option("--max-acceleration", max_acceleration_, "m/s²")->check(CLI::PositiveNumber);
    app.add_option("--acceleration-p99", acceleration_p99_, "m/s²")->check(CLI::PositiveNumber);
    app.add_option("--max-turning-rate", max_turning_, "rad/s")->check(CLI::PositiveNumber);
    app.add_option("--turning-rate-p99", turning_p99_, "rad/s")->check(CLI::PositiveNumber);
    app.add_option("--max-facing-rate", max_facing_, "rad/s")->check(CLI::PositiveNumber);
    app.add_option("--max-displacement", max_displacement_, "m from the reference")->check(CLI::PositiveNumber);
    app.add_option("--max-pair-contacts", max_pairs_, "Distinct pairs of agents in contact");
    app.add_option("--max-obstacle-contacts", max_obstacle_, "Distinct agent–obstacle pairs in contact");
    app.add_option("--margin", settings_.margin, "m added to the clearances")->check(CLI::NonNegativeNumber);
    app.add_option("--edge-frames", settings_.edge_frames, "Frames at each end of a presence run left out");
    app.add_option("--heading-min-speed", settings_.heading_min_speed, "m/s: no turning rate below")->check(CLI::PositiveNumber);
  }

  void run(Context& context) override {
    if (context.print_config_if_asked(YAML::Node(YAML::NodeType::Map))) return;
    context.limit_threads();
    const CrowdFile crowd = read_crowd_file(crowd_);
    std::optional<CrowdFile> reference;
    if (!reference_.empty()) reference = read_crowd_file(reference_);
    const CrowdMotion* ref = reference ? &reference->motion : nullptr;
    const std::optional<check::FacingSeries> facing = check::facings_of(crowd.motion);
    const check::Statistics s = check::measure(crowd.motion, crowd.scene.obstacles, settings_, ref, facing ? &*facing : nullptr);
    check::Limits limits;
    std::optional<check::Statistics> input;
    if (reference) {
      input = check::measure(reference->motion, crowd.scene.obstacles, settings_);
      limits = check::limits_from_reference(*input, limits, speed_ratio_);
    }
    for (auto [value, field] : {std::pair{max_speed_, &check::Limits::max_speed}, {max_acceleration_, &check::Limits::max_acceleration},
                                {acceleration_p99_, &check::Limits::acceleration_p99}, {max_turning_, &check::Limits::max_turning_rate},
                                {turning_p99_, &check::Limits::turning_rate_p99}, {max_facing_, &check::Limits::max_facing_rate},
                                {max_displacement_, &check::Limits::max_displacement}}) {
      if (value) limits.*field = *value;
    }
    if (max_pairs_) limits.max_pair_contacts = max_pairs_;
    if (max_obstacle_) limits.max_obstacle_contacts = max_obstacle_;
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
  double speed_ratio_ = 1.25;
  std::optional<double> max_speed_, max_acceleration_, acceleration_p99_, max_turning_, turning_p99_, max_facing_, max_displacement_;
  std::optional<std::size_t> max_pairs_, max_obstacle_;
  check::Settings settings_;
};

}  // namespace

std::unique_ptr<Command> make_check_motion_command() { return std::make_unique<CheckMotionCommand>(); }

}  // namespace throng::cli
