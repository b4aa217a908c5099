// throng merge A.h5 B.h5 [C.h5 ...] -o OUT.h5: several groups in a shared time span become one crowd (one graph
// for editing and stitching: formation edges join the groups where they are neighbours; solver/stitch/merge.h).
// The job format is in io/stitch/include/throng/io/merge_job.h; docs/commands/stitch.md is the README section.
#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>
#include <throng/io/command_job.h>
#include <throng/io/merge_job.h>

#include <memory>

#include "factories.h"
#include "input_crowds.h"
#include "job_flags.h"

namespace throng::cli {
namespace {

struct MergeDone {
  CrowdFile crowd;
  ExtraWriter extra;
  Report report;
};

/// The work shared by `throng merge` and the `merge` step.
MergeDone merge_all(const std::vector<const CrowdFile*>& inputs, const MergeJob& job, Context& context) {
  context.progress().update(0.0, "merge");
  auto merged = std::make_shared<MergedCrowds>(merge_crowds(inputs, job));
  context.progress().update(1.0, "merge: done");
  MergeDone d;
  d.crowd = merged->crowd;
  d.extra = [merged](const h5::Group& g) { write_merge_data(g, *merged); };
  const CrowdMotion& m = d.crowd.motion;
  std::vector<std::size_t> cross, left_out;
  std::size_t interpolated = 0;
  bool dropped = false;
  for (std::size_t k = 0; k < merged->reports.size(); ++k) {
    const stitch::MergeReport& r = merged->reports[k];
    cross.push_back(r.cross_edges);
    interpolated += r.interpolated_frames_first + r.interpolated_frames_second;
    dropped = dropped || r.velocities_dropped;
    if (r.left_out_first + r.left_out_second > 0) {
      context.warn("merge: input " + std::to_string(k + 2) + ": " + std::to_string(r.left_out_first + r.left_out_second) +
                   " agent(s) present at no merged frame were left out");
    }
    left_out.push_back(r.left_out_first + r.left_out_second);
  }
  if (interpolated > 0) {
    context.info("merge: the crowds' frame times differ; " + std::to_string(interpolated) +
                 " crowd-frames were interpolated (cubic splines)");
  }
  d.report["inputs"] = inputs.size();
  d.report["agents"] = m.agent_count();
  d.report["frames"] = m.frame_count();
  d.report["times_s"] = {m.times.empty() ? 0.0 : m.times.front(), m.times.empty() ? 0.0 : m.times.back()};
  d.report["id_shifts"] = merged->id_shifts;
  d.report["cross_edges"] = cross;
  d.report["interpolated_frames"] = interpolated;
  d.report["left_out"] = left_out;
  d.report["velocities_dropped"] = dropped;
  d.report["obstacles"] = d.crowd.scene.obstacles.size();
  return d;
}

class MergeCommand final : public Command {
 public:
  std::string name() const override { return "merge"; }
  std::string summary() const override {
    return "Merge groups sharing a time span into one crowd (one formation graph across the groups)";
  }

  void setup(CLI::App& app) override {
    app.add_option("crowds", inputs_, "Crowd files to merge (.h5), two or more, in order")->required()->expected(2, -1);
    app.add_option("-o,--output", output_, "Crowd file to write (.h5)")->required();
    app.add_option("--job", job_path_, "Merge job (.yaml): options and obstacles to add; the flags below override its keys");
    flags_.value(app, "--span", "span", "overlap (the frames every crowd shares) | union (from the earliest start to the latest end)");
    flags_.value(app, "--on-id-clash", "on_id_clash", "shift (move a later crowd's ids above the earlier ones') | error");
    flags_.value(app, "--time-tolerance", "time_tolerance", "Seconds: frame times closer than this are one frame");
    flags_.value(app, "--max-edge-length", "max_edge_length", "Metres: drop stored formation edges longer than this (0: keep all)");
  }

  void run(Context& context) override {
    const ConfigNode job = command_job(job_path_, flags_.yaml(), context.global.set, "merge");
    const MergeJob parsed = read_merge_job(job);
    const YAML::Node effective = effective_merge_job(parsed);
    if (context.print_config_if_asked(effective)) return;
    for (const auto& in : inputs_) check_distinct(in, output_);
    if (!job_path_.empty()) check_distinct(job_path_, output_);
    context.limit_threads();
    (void)AtomicOutput(output_);  // a missing or read-only output folder fails now (exit 4), not after the work

    const InputCrowds in = read_input_crowds(inputs_, job_path_);
    MergeDone d = merge_all(in.crowds, parsed, context);
    d.crowd.provenance = context.provenance(effective, in.names, in.sources);
    write_crowd_file(output_, d.crowd, d.extra);
    Report r;
    r["output"] = output_.string();
    r.update(d.report);
    context.print(r);
  }

  /// As a step: merges the crowds it reads (`inputs: [a, b, ...]`), in order.
  std::optional<StepResult> run_step(const ConfigNode& step, const std::vector<const CrowdFile*>& inputs,
                                     Context& context) override {
    const MergeJob parsed = read_merge_job(step);
    if (inputs.size() < 2) step.fail("merge takes two or more crowds (inputs: [a, b, ...]), found " + std::to_string(inputs.size()));
    MergeDone d = merge_all(inputs, parsed, context);
    context.info("merge: " + d.report.dump());
    return StepResult{std::move(d.crowd), std::move(d.extra)};
  }

 private:
  std::vector<std::filesystem::path> inputs_;
  std::filesystem::path output_, job_path_;
  JobFlags flags_;
};

}  // namespace

std::unique_ptr<Command> make_merge_command() { return std::make_unique<MergeCommand>(); }

}  // namespace throng::cli
