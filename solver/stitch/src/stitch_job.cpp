// The stitch job's runner (jobs.h): clips played one after the other, ((A then B) then C) ...
#include <throng/core/errors.h>
#include <throng/core/format.h>
#include <throng/stitch/jobs.h>
#include <throng/stitch/schema.h>

#include <numbers>

namespace throng::stitch {
namespace {

// Maps [0, 1] of one joint into its share of the whole.
class JointProgress final : public Progress {
 public:
  JointProgress(Progress& whole, std::size_t joint, std::size_t joints) : whole_(whole), joint_(joint), joints_(joints) {}
  void update(double fraction, std::string_view stage) override {
    whole_.update((static_cast<double>(joint_) + fraction) / static_cast<double>(joints_),
                  "stitch joint " + std::to_string(joint_ + 1) + "/" + std::to_string(joints_) + ": " + std::string(stage));
  }

 private:
  Progress& whole_;
  std::size_t joint_, joints_;
};

// What a joint left out, and when its window was shortened.
void warn_about(const Report& r, std::size_t k, std::size_t budget, std::vector<std::string>& warnings) {
  const std::string which = "joint " + std::to_string(k + 1) + ": ";
  if (!r.left_out_first.empty()) {
    warnings.push_back(which + std::to_string(r.left_out_first.size()) +
                       " agent(s) of the clip so far absent from part of it were left out (" + id_list(r.left_out_first) + ")");
  }
  if (!r.left_out_second.empty()) {
    warnings.push_back(which + std::to_string(r.left_out_second.size()) + " agent(s) of input " + std::to_string(k + 2) +
                       " absent from part of it were left out (" + id_list(r.left_out_second) + ")");
  }
  if (r.window_limited) {
    warnings.push_back(which + "blending the whole clips would solve " + std::to_string(r.whole_clip_vertices) +
                       " vertices (agents × samples), over max_blend_vertices " + std::to_string(budget) +
                       ": the window is shortened to " + with_digits(r.window_first_s, 4) + " s / " +
                       with_digits(r.window_second_s, 4) + " s per side (set blend_window, raise sample_step or max_blend_vertices)");
  }
}

}  // namespace

void describe(OptionBinder& b, StitchJob& job) { describe(b, job.options); }

StitchRun run(const Crowds& inputs, const StitchJob& job, Progress& progress, const Communicator& communicator) {
  if (inputs.size() < 2) throw ConfigError("stitch needs at least two clips, got " + std::to_string(inputs.size()));
  StitchRun s;
  s.inputs = inputs.size();
  s.max_blend_vertices = job.options.max_blend_vertices;
  s.crowd.motion = inputs[0]->motion;
  s.crowd.scene = inputs[0]->scene;
  const std::size_t joints = inputs.size() - 1;
  for (std::size_t k = 1; k < inputs.size(); ++k) {
    JointProgress joint(progress, k - 1, joints);
    Result r;
    const std::string which = "joint " + std::to_string(k) + " (inputs 1.." + std::to_string(k) + " then input " + std::to_string(k + 1) + "): ";
    try {
      r = stitch_clips(s.crowd.motion, inputs[k]->motion, job.options, &joint);
    } catch (const InputError& e) {
      throw InputError(which + e.what());
    } catch (const NumericalError& e) {
      throw NumericalError(which + e.what());
    }
    warn_about(r.report, k - 1, s.max_blend_vertices, s.warnings);
    s.joint_frames.push_back(r.report.frames_first - 1);
    s.joint_ids.push_back(r.crowd.ids);
    s.crowd.motion = std::move(r.crowd);
    r.crowd = CrowdMotion{};
    s.joints.push_back(std::move(r));
  }
  const int ranks = communicator.size();
  if (ranks > 1 && job.options.solver.backend != "petsc") {
    s.warnings.push_back(std::to_string(ranks) + " ranks with the " + job.options.solver.backend +
                         " backend: every rank solves the whole problem (solver.backend petsc shares it)");
  }
  return s;
}

void describe(ReportWriter& w, const StitchRun& run) {
  const CrowdMotion& m = run.crowd.motion;
  w.count("inputs", run.inputs);
  w.count("agents", m.agent_count());
  w.count("frames", m.frame_count());
  w.numbers("times_s", {m.times.empty() ? 0.0 : m.times.front(), m.times.empty() ? 0.0 : m.times.back()});
  w.records("joints", "joint", run.joints.size(), [&](ReportWriter& j, std::size_t k) {
    const Report& r = run.joints[k].report;
    j.count("frame", run.joint_frames[k]);
    j.count("agents", r.agents);
    j.count("matched_same_id", r.matched_same_id);
    j.number("matching_distance_m", r.matching_distance);
    j.number("rotation", r.rotation);
    j.numbers("translation_m", {r.translation.x(), r.translation.y()});
    j.number("gap_rms_m", r.gap_rms);
    j.number("gap_max_m", r.gap_max);
    j.counts("window", {r.window_first, r.window_second});
    j.numbers("window_s", {r.window_first_s, r.window_second_s});
    j.flag("window_limited", r.window_limited);
    j.count("fit_starts", r.fit_starts);
    j.count("fit_rounds", r.fit_rounds);
    j.count("solved_samples", r.solved_samples);
    j.count("unknowns", r.unknowns);
    j.number("max_change_m", r.max_change);
    // The plausibility guard after the solve (stitch.h "Plausibility"): whether it slowed the clip down, and
    // the kinks left beyond the acceleration limit before and after its smoothing.
    timewarp::describe(j, r.guard);
    j.seconds("solve_s", r.matching_seconds + r.graph_seconds + r.precompute_seconds + r.solve_seconds);
  });
}

}  // namespace throng::stitch
