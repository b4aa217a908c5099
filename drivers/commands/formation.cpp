// throng formation JOB.yaml -o OUT.h5: a group moving through keyframe formations along rotating Laplacian
// eigenbases (spectral formation control, solver/formation). The job format is in
// io/formation/include/throng/io/formation_job.h; docs/commands/formation.md is the README section.
#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>
#include <throng/io/formation_job.h>

#include <functional>
#include <memory>
#include <sstream>

#include "factories.h"

namespace throng::cli {
namespace {

/// A finished run: the crowd to write, its method data, the report, and what it missed (empty: nothing).
struct Formed {
  CrowdFile crowd;
  ExtraWriter extra;
  Report report;
  std::string shortfall;
};

/// The work shared by `throng formation` and the `formation` step of `throng run`. `job` has its keyframes
/// resolved (resolve_formation_keyframes).
Formed form_crowd(FormationJob job, Context& context) {
  auto result = std::make_shared<formation::Result>(
      formation::animate_formation(job.problem, job.options, context.progress()));
  Formed f;
  f.crowd = formation_crowd(*result);
  const CrowdMotion& m = result->motion;
  f.report["agents"] = m.agent_count();
  f.report["frames"] = m.frame_count();
  f.report["duration_s"] = m.frame_count() ? m.times.back() - m.times.front() : 0.0;
  f.report["dimension"] = job.problem.keyframes.front().positions.cols();
  f.report["keyframes"] = job.problem.keyframes.size();
  f.report["keyframe_frames"] = result->keyframe_frames;
  std::size_t groups = 0;
  std::function<void(const formation::Group&)> count = [&](const formation::Group& g) {
    ++groups;
    for (const auto& s : g.subgroups) count(s);
  };
  count(result->hierarchy);
  f.report["groups"] = groups;
  f.report["formation_edges"] = f.crowd.formation_edges.size();
  if (result->collision.ran) {
    f.report["collision_satisfied"] = result->collision.satisfied;
    f.report["closest_m"] = result->collision.closest_m;
    f.report["largest_shift_m"] = result->collision.largest_shift_m;
    if (!result->collision.satisfied) {
      std::ostringstream s;
      s << "individuals " << result->collision.closest_pair[0] << " and " << result->collision.closest_pair[1] << " are "
        << result->collision.closest_m << " m apart at frame " << result->collision.closest_frame
        << ", closer than collision.min_distance " << job.options.collision.min_distance_m << " m";
      f.shortfall = s.str();
    }
  }
  auto data = std::make_shared<const FormationJob>(std::move(job));
  f.extra = [data, result](const h5::Group& g) { write_formation_data(g, *data, *result); };
  return f;
}

class FormationCommand final : public Command {
 public:
  std::string name() const override { return "formation"; }
  std::string summary() const override {
    return "Move a group through keyframe formations along rotating Laplacian eigenbases (spectral formation control)";
  }

  void setup(CLI::App& app) override {
    app.add_option("job", job_path_, "Formation job (.yaml): keyframes or from_crowd, edits, hierarchy, options")->required();
    app.add_option("-o,--output", output_, "Crowd file to write (.h5)")->required();
  }

  void run(Context& context) override {
    const ConfigNode job = context.load_job(job_path_);
    FormationJob parsed = read_formation_job(job);
    const YAML::Node effective = effective_formation_job(parsed);
    if (context.print_config_if_asked(effective)) return;
    check_distinct(job_path_, output_);
    std::optional<CrowdFile> input;
    std::vector<std::string> inputs{job_path_.string()};
    if (parsed.from_crowd) {
      if (parsed.from_crowd->file.empty()) job.at("from_crowd").fail("give from_crowd.file (the crowd to take the keyframes from)");
      check_distinct(parsed.from_crowd->file, output_);
      input = read_crowd_file(parsed.from_crowd->file);
      inputs.push_back(parsed.from_crowd->file);
    }
    resolve_formation_keyframes(parsed, input ? &*input : nullptr);
    context.limit_threads();

    Formed f = form_crowd(std::move(parsed), context);
    if (input) f.crowd.scene = input->scene;
    std::vector<const Provenance*> sources;
    if (input) sources.push_back(&input->provenance);
    f.crowd.provenance = context.provenance(effective, inputs, sources);
    write_crowd_file(output_, f.crowd, f.extra);

    Report r;
    r["output"] = output_.string();
    r.update(f.report);
    context.print(r);
    if (!f.shortfall.empty())
      throw NumericalError("formation: " + f.shortfall + "; the crowd was written to " + output_.string());
  }

  /// As a step: the step's keys are the job file's. With from_crowd and no file, the keyframes come from the
  /// step's one input crowd; otherwise the step starts a new crowd.
  std::optional<StepResult> run_step(const ConfigNode& step, const std::vector<const CrowdFile*>& inputs,
                                     Context& context) override {
    FormationJob parsed = read_formation_job(step);
    std::optional<CrowdFile> read;
    const CrowdFile* source = nullptr;
    if (parsed.from_crowd) {
      if (!parsed.from_crowd->file.empty()) {
        read = read_crowd_file(parsed.from_crowd->file);
        source = &*read;
      } else {
        if (inputs.size() != 1)
          step.fail("formation with from_crowd and no file takes one crowd, found " + std::to_string(inputs.size()));
        source = inputs.front();
      }
    }
    resolve_formation_keyframes(parsed, source);
    Formed f = form_crowd(std::move(parsed), context);
    if (source) {
      f.crowd.scene = source->scene;
      f.crowd.provenance.credits = source->provenance.credits;
    }
    if (!f.shortfall.empty()) context.warn("formation: " + f.shortfall);
    context.info("formation: " + f.report.dump());
    return StepResult{std::move(f.crowd), std::move(f.extra)};
  }

 private:
  std::filesystem::path job_path_;
  std::filesystem::path output_;
};

}  // namespace

std::unique_ptr<Command> make_formation_command() { return std::make_unique<FormationCommand>(); }

}  // namespace throng::cli
