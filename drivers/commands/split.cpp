// throng split CROWD.h5 -o PART.h5 [--other REST.h5]: cut a crowd by time (at a frame, or a range of frames) or by
// agents (ids, species), keeping the data exactly (solver/stitch/jobs.h). The job format is in
// io/stitch/include/throng/io/split_job.h; every key also has a flag. docs/commands/stitch.md is the README section.
// With --other both parts are made before anything is written, and a failure writing the second removes the first.
#include "../method_command.h"
#include "factories.h"

#include <throng/io/split_job.h>

namespace throng::cli {
namespace {

/// The part the job keeps and, when asked, the other one.
struct Parts : stitch::SplitRun {
  std::optional<stitch::SplitRun> other;
};

/// The part the job keeps and, with --other, the other one; both before anything is written.
Parts split_parts(const Crowds& in, stitch::SplitJob& job, MethodRun& r) {
  Parts parts{stitch::split(*in.front(), job), std::nullopt};
  if (r.second_output) parts.other = stitch::split(*in.front(), job, true);
  return parts;
}

class SplitCommand final : public MethodCommand<stitch::SplitJob, Parts> {
 public:
  SplitCommand()
      : MethodCommand(MethodSpec{.name = "split",
                                 .summary = "Cut a crowd by time (at a frame, or a range) or by agents (ids, species) into clips",
                                 .job = JobArgument::optional,
                                 .job_help = "Split job (.yaml); the flags below override its keys",
                                 .inputs = {.min = 1, .max = 1, .help = "Crowd file to split (.h5)", .count_text = "split takes one crowd"},
                                 .output_help = "Crowd file to write (.h5): the part the job keeps"},
                      Hooks{.run = split_parts}) {}

 protected:
  void more_arguments(CLI::App& app) override {
    app.add_option("--other", other_, "Also write the other part here: the other half of a split by time, or the rest of a "
                                      "split by agents");
  }
  void check_outputs(const std::vector<std::filesystem::path>& inputs) override {
    if (other_.empty()) return;
    for (const auto& in : inputs) check_distinct(in, other_);
    check_distinct(output_, other_);
    (void)AtomicOutput(other_);  // a missing or read-only folder fails now (exit 4), not after the work
  }
  bool wants_second_output() const override { return !other_.empty(); }
  void write(const CrowdFile& out, const ExtraWriter& record, const Parts& parts, Context& context) override {
    MethodCommand::write(out, record, parts, context);
    if (!parts.other) return;
    const stitch::SplitRun& other = *parts.other;
    CrowdFile file;
    static_cast<Crowd&>(file) = other.crowd;
    file.provenance = out.provenance;
    try {
      write_crowd_file(other_, file, [&](const h5::Group& parameters) {
        const h5::Group g = parameters.create_group("split");
        write_data(g, other);
        ReportRecord fields(g);
        report_fields(other).replay(fields);
      }, context.global.storage);
    } catch (...) {
      std::error_code ec;
      std::filesystem::remove(output_, ec);  // no half-done split: both parts or neither
      throw;
    }
  }
  void amend(Report& report, const Parts& parts) override {
    if (!parts.other) return;
    Report other;
    other["output"] = other_.string();
    ReportJson json(other);
    report_fields(*parts.other).replay(json);
    report["other"] = other;
  }

 private:
  std::filesystem::path other_;
};

}  // namespace

std::unique_ptr<Command> make_split_command() { return std::make_unique<SplitCommand>(); }

}  // namespace throng::cli
