// throng tile JOB.yaml -o TILING.h5: fill a space-time region with deformable motion patches (solver/tiling);
// throng check-tiling TILING.h5: the independent checker, listing every failure.
// The job format is in io/tiling/include/throng/io/tiling_job.h; docs/commands/tile.md is the README section.
#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>
#include <throng/io/tiling_job.h>
#include <throng/linalg/mpi.h>
#include <throng/tiling/characters.h>
#include <throng/tiling/check.h>
#include <throng/tiling/tile.h>

#include <memory>

#include "factories.h"

namespace throng::cli {
namespace {

/// A finished tiling: the crowd of its characters, the tiling data, and the report.
struct Tiled {
  CrowdFile crowd;
  ExtraWriter extra;
  Report report;
  std::size_t dangling = 0;
  bool capped = false;          ///< the best chain's search stopped at search.max_steps
  std::size_t search_steps = 0;
  std::size_t max_steps = 0;
};

/// The work shared by `throng tile` and the `tile` step of `throng run`.
Tiled tile_crowd(TilingJob job, Context& context) {
  job.options.seed = context.global.seed;
  const Region& region = *job.environment.scene.region;
  if (region.periodic[0] && region.periodic[1] && region.periodic[2] && job.environment.sources.empty() &&
      job.environment.sinks.empty()) {
    context.warn("tile: the region is periodic in x, y and t and has no source or sink: no character can leave it, so "
                 "every one must close a loop; the search closes most (bridges, dropping open groups) but may stop "
                 "with dangling ends. More chains, fewer characters, or one axis left open make it reliable");
  }
  auto result = std::make_shared<tiling::TilingResult>(
      tiling::tile(job.library, job.environment, job.keyframes, job.options, context.progress()));
  auto laid = std::make_shared<tiling::Characters>(
      tiling::lay_out(job.library, result->tiling, *job.environment.scene.region, job.layout));
  Tiled t;
  t.crowd.motion = laid->motion;
  t.crowd.scene = laid_scene(job.environment, job.layout);
  t.crowd.provenance.credits = job.credits;
  const tiling::TilingReport& r = result->report;
  t.dangling = r.dangling;
  t.report["instances"] = r.instances;
  t.report["characters"] = r.characters;
  t.report["connections"] = r.connections;
  t.report["dangling"] = r.dangling;
  t.report["agents"] = t.crowd.motion.agent_count();
  t.report["frames"] = t.crowd.motion.frame_count();
  t.report["patch_types"] = job.library.types.size();
  t.report["unusable_types"] = r.unusable_types.size();
  t.report["chains"] = r.chains.size();
  t.report["best_chain"] = r.best_chain;
  const tiling::ChainReport& best = r.chains[r.best_chain];
  t.report["phase1_instances"] = best.phase1_instances;
  t.report["phase1_dangling"] = best.phase1_dangling;
  t.report["phase1_s"] = best.phase1_seconds;
  t.report["phase2_s"] = best.phase2_seconds;
  t.report["removals"] = best.removals;
  t.report["search_steps"] = best.search_steps;
  t.report["search_capped"] = best.search_capped;
  t.report["seconds"] = r.seconds;
  t.report["ranks"] = mpi::size();
  t.capped = best.search_capped;
  t.search_steps = best.search_steps;
  t.max_steps = job.options.search.max_steps;
  auto data = std::make_shared<const TilingJob>(std::move(job));
  t.extra = [data, result, laid](const h5::Group& g) {
    write_tiling_data(g, data->library, *result, data->environment, check_options_for(data->options), *laid,
                      data->layout);
  };
  return t;
}

/// Why dangling ends remain, worded by how the search stopped: at its cap, or because a whole sweep over the
/// dangling ends placed and removed nothing (every candidate at every end was tried and remembered).
std::string shortfall(const Tiled& t) {
  std::string m = std::to_string(t.dangling) + " dangling " + (t.dangling == 1 ? "end remains" : "ends remain");
  if (t.capped) {
    return m + " (the search stopped at search.max_steps = " + std::to_string(t.max_steps) +
           " placements: raise it, allow more chains, or loosen match/limits)";
  }
  return m + " (the search stopped after " + std::to_string(t.search_steps) +
         " placements because a sweep over the dangling ends changed nothing: no patch fits them; allow more chains, "
         "add patches whose ends match theirs, or loosen match/limits)";
}

class TileCommand final : public Command {
 public:
  std::string name() const override { return "tile"; }
  std::string summary() const override {
    return "Fill a space-time region with deformable motion patches, leaving no dangling entry or exit";
  }

  void setup(CLI::App& app) override {
    app.add_option("job", job_path_, "Tiling job (.yaml): region, library, obstacles, keyframes, options")->required();
    app.add_option("-o,--output", output_, "Crowd file to write (.h5): the characters and the tiling")->required();
  }

  void run(Context& context) override {
    const ConfigNode job = context.load_job(job_path_);
    TilingJob parsed = read_tiling_job(job);
    const YAML::Node effective = effective_tiling_job(parsed);
    if (context.print_config_if_asked(effective)) return;
    check_distinct(job_path_, output_);
    context.limit_threads();

    const bool writer = mpi::rank() == 0;  // starts MPI when launched by mpiexec
    if (writer) {
      const AtomicOutput folder_check(output_);  // a missing or read-only folder fails now, not after the tiling
    }
    std::vector<std::string> inputs{job_path_.string()};
    if (!parsed.real_dataset.empty()) inputs.push_back(parsed.real_dataset);
    Tiled t = tile_crowd(std::move(parsed), context);
    const std::vector<std::string> credits = t.crowd.provenance.credits;  // of the real data used, if any
    t.crowd.provenance = context.provenance(effective, inputs);
    for (const std::string& c : credits) t.crowd.provenance.credits.push_back(c);
    if (writer) {
      write_crowd_file(output_, t.crowd, t.extra);
      Report r;
      r["output"] = output_.string();
      r.update(t.report);
      r["seed"] = context.global.seed;
      context.print(r);
    }
    if (t.dangling > 0) throw NumericalError("tile: " + shortfall(t) + "; the tiling was written to " + output_.string());
  }

  /// As a step: the step's keys are the job file's; it reads no crowd (it starts a new one).
  std::optional<StepResult> run_step(const ConfigNode& step, const std::vector<const CrowdFile*>&,
                                     Context& context) override {
    Tiled t = tile_crowd(read_tiling_job(step), context);
    if (t.dangling > 0) context.warn("tile: " + shortfall(t));
    context.info("tile: " + t.report.dump());
    return StepResult{std::move(t.crowd), std::move(t.extra)};
  }

 private:
  std::filesystem::path job_path_;
  std::filesystem::path output_;
};

class CheckTilingCommand final : public Command {
 public:
  std::string name() const override { return "check-tiling"; }
  std::string summary() const override {
    return "Check a tiling independently: no dangling end, no overlap, deformation within limits, seams matched";
  }

  void setup(CLI::App& app) override {
    // No ExistingFile check: a missing file is an I/O error (exit 4) from the reader, as for every other input.
    app.add_option("tiling", path_, "Tiling file written by `throng tile` (.h5)")->required();
    app.add_option("--max-failures", max_failures_, "List at most this many failures (all are counted)")
        ->check(CLI::NonNegativeNumber);
  }

  void run(Context& context) override {
    if (context.print_config_if_asked(YAML::Node(YAML::NodeType::Map))) return;
    context.limit_threads();
    const TilingData data = read_tiling_data(path_);
    const tiling::CheckReport c = tiling::check_tiling(data.library, data.tiling, data.environment, data.check, max_failures_);
    Report r;
    r["tiling"] = path_.string();
    r["perfect"] = c.perfect();
    r["instances"] = c.instances;
    r["connections"] = c.connections;
    r["character_ends"] = c.character_ends;
    r["pairs_tested"] = c.pairs_tested;
    Report totals = Report::object();
    for (std::size_t k = 0; k < tiling::failure_kind_count; ++k) {
      totals[tiling::to_string(static_cast<tiling::FailureKind>(k))] = c.totals[k];
    }
    r["failures"] = totals;
    Report listed = Report::array();
    for (const tiling::Failure& f : c.failures) listed.push_back(std::string(tiling::to_string(f.kind)) + ": " + f.message);
    r["listed"] = listed;
    context.print(r);
    if (!c.perfect()) {
      throw NumericalError("check-tiling: " + std::to_string(c.total()) + " failure(s) in " + path_.string() +
                           " (listed above)");
    }
  }

 private:
  std::filesystem::path path_;
  std::size_t max_failures_ = 1000;
};

}  // namespace

std::unique_ptr<Command> make_tile_command() { return std::make_unique<TileCommand>(); }
std::unique_ptr<Command> make_check_tiling_command() { return std::make_unique<CheckTilingCommand>(); }

}  // namespace throng::cli
