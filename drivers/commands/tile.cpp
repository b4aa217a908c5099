// throng tile JOB.yaml -o TILING.h5: fill a space-time region with deformable motion patches
// (solver/tiling/runner.h); `throng check-tiling` (check_tiling.cpp) is the independent checker.
// The job format is in io/tiling/include/throng/io/tiling_job.h; docs/commands/tile.md is the README section.
// Dangling ends left: the tiling and the report are written, then exit 5; as a step of `throng run`, a warning.
// Under mpiexec the chains are spread over the ranks; rank 0 writes and reports.
#include "../method_command.h"
#include "factories.h"

#include <throng/io/import_crowd.h>
#include <throng/io/tiling_job.h>

namespace throng::cli {
namespace {

/// The recorded crowd of library.real is imported first, by import_crowd (whatever `throng import` reads, with
/// library.real's fps, columns, units and credit); what needs the library (built then) names the job.
tiling::Run tile(const Crowds&, TilingJob& job, MethodRun& r) {
  std::optional<CrowdFile> recorded;
  if (job.library.real) {
    try {
      recorded = import_crowd(job.real_dataset, job.real_import).crowd;
    } catch (const ConfigError& e) {  // a rate or column map the data needs: named by the job's keys
      throw ConfigError(r.where + ": library.real: " + e.what() +
                        " (in a tiling job: library.real.fps, .columns, .units, or the flags of the same names)");
    }
    r.files_read.push_back(job.real_dataset);
    r.credits = recorded->provenance.credits;
  }
  try {
    return tiling::run(recorded ? Crowds{&*recorded} : Crowds{}, job, r.progress(), r.communicator());
  } catch (const ConfigError& e) {
    throw ConfigError(r.where + ": " + e.what());
  }
}

}  // namespace

std::unique_ptr<Command> make_tile_command() {
  return std::make_unique<MethodCommand<TilingJob>>(
      MethodSpec{.name = "tile",
                 .summary = "Fill a space-time region with deformable motion patches, leaving no dangling entry or exit",
                 .job = JobArgument::positional,
                 .job_help = "Tiling job (.yaml): region, library, obstacles, keyframes, options",
                 .inputs = {.count_text = "tile reads no crowd"},
                 .output_help = "Crowd file to write (.h5): the characters and the tiling",
                 .record = "tiling",
                 .made = "tiling"},
      MethodCommand<TilingJob>::Hooks{.run = tile});
}

}  // namespace throng::cli
