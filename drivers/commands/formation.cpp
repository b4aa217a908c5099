// throng formation JOB.yaml -o OUT.h5: a group moving through keyframe formations along rotating Laplacian
// eigenbases (spectral formation control, solver/formation/runner.h). The job format is in
// io/formation/include/throng/io/formation_job.h; docs/commands/formation.md is the README section.
// Keyframes from a crowd (from_crowd): its file, or in a `throng run` step without a file the step's one input.
#include "../method_command.h"
#include "factories.h"

#include <throng/io/formation_job.h>

namespace throng::cli {
namespace {

/// Keyframes from a crowd (from_crowd): its file, else (a step) the step's one input; then the method's runner.
formation::Run form(const Crowds& in, FormationJob& job, MethodRun& r) {
  std::optional<CrowdFile> read;
  const Crowd* source = nullptr;
  if (job.from_crowd && !job.from_crowd->file.empty()) {
    if (!r.output.empty()) check_distinct(job.from_crowd->file, r.output);
    read = read_crowd_file(job.from_crowd->file);
    r.files_read.push_back(job.from_crowd->file);
    r.credits = read->provenance.credits;
    source = &*read;
  } else if (job.from_crowd) {
    if (in.size() != 1) {
      throw ConfigError(r.where + ": " + (r.output.empty() ? "formation with from_crowd and no file takes one crowd, found " +
                                                                std::to_string(in.size())
                                                          : "give from_crowd.file (the crowd to take the keyframes from)"));
    }
    source = in.front();
    r.credits = static_cast<const CrowdFile*>(source)->provenance.credits;  // a step's inputs are crowd files
  }
  resolve_formation_keyframes(job, source);
  return formation::run(source ? Crowds{source} : Crowds{}, job, r.progress(), r.communicator());
}

}  // namespace

std::unique_ptr<Command> make_formation_command() {
  return std::make_unique<MethodCommand<FormationJob>>(
      MethodSpec{.name = "formation",
                 .summary = "Move a group through keyframe formations along rotating Laplacian eigenbases (spectral "
                            "formation control)",
                 .job = JobArgument::positional,
                 .job_help = "Formation job (.yaml): keyframes or from_crowd, edits, hierarchy, options",
                 .inputs = {.min = 0, .max = any_number, .count_text = "formation takes no crowd", .on_command_line = false},
                 .output_help = "Crowd file to write (.h5)"},
      MethodCommand<FormationJob>::Hooks{.run = form});
}

}  // namespace throng::cli
