// throng tile JOB.yaml -o TILING.h5: fill a space-time region with deformable motion patches
// (solver/tiling/runner.h); `throng check-tiling` (check_tiling.cpp) is the independent checker.
// The job format is in io/tiling/include/throng/io/tiling_job.h; docs/commands/tile.md is the README section.
// Dangling ends left: the tiling and the report are written, then exit 5; as a step of `throng run`, a warning.
// Under mpiexec the chains are spread over the ranks; rank 0 writes and reports.
//
// With `window: seconds` the horizon is tiled window by window (tiling/windowed.h) and streamed to the output
// (io/tiling_stream.h): one rank, memory bounded by a window. After each window the partial file is flushed and
// a resume record (the writer's sizes and the tiler's state) is written atomically beside it, with Ctrl-C and
// SIGTERM held off until both are on disk; `--resume` continues from the last record. The partial file becomes
// the output when the last window is done.
#include "../method_command.h"
#include "factories.h"

#include <throng/core/bytes.h>
#include <throng/io/import_crowd.h>
#include <throng/io/input_file.h>
#include <throng/io/tiling_data.h>
#include <throng/io/tiling_job.h>
#include <throng/io/tiling_stream.h>

#include <chrono>
#include <cstring>

namespace throng::cli {
namespace {

/// The recorded crowd of library.real, imported by import_crowd (whatever `throng import` reads, with
/// library.real's fps, columns, units and credit); nullopt when the job takes no patches from data.
std::optional<CrowdFile> import_recorded(const TilingJob& job, MethodRun& r) {
  if (!job.library.real) return std::nullopt;
  std::optional<CrowdFile> recorded;
  try {
    recorded = import_crowd(job.real_dataset, job.real_import).crowd;
  } catch (const ConfigError& e) {  // a rate or column map the data needs: named by the job's keys
    throw ConfigError(r.where + ": library.real: " + e.what() +
                      " (in a tiling job: library.real.fps, .columns, .units, or the flags of the same names)");
  }
  r.files_read.push_back(job.real_dataset);
  r.credits.insert(r.credits.end(), recorded->provenance.credits.begin(), recorded->provenance.credits.end());
  return recorded;
}

/// library.file: the library of a file written by `throng tile`, read into the job (a file that is not one is
/// an InputError naming it, exit 3).
void load_saved_library(TilingJob& job, MethodRun& r) {
  if (job.library_file.empty()) return;
  job.library.saved = read_tiling_data(job.library_file).library;
  r.files_read.push_back(job.library_file);
  // Patches cut from recorded crowds keep their authors' credit in every file made from them.
  const std::vector<std::string> credits =
      open_throng_parameters(h5::File::open(job.library_file)).string_array_attribute("credits");
  r.credits.insert(r.credits.end(), credits.begin(), credits.end());
}

/// What needs the library (built then) names the job.
tiling::Run tile(const Crowds&, TilingJob& job, MethodRun& r) {
  load_saved_library(job, r);
  const std::optional<CrowdFile> recorded = import_recorded(job, r);
  try {
    return tiling::run(recorded ? Crowds{&*recorded} : Crowds{}, job, r.progress(), r.communicator());
  } catch (const ConfigError& e) {
    throw ConfigError(r.where + ": " + e.what());
  }
}

// The resume record beside a windowed run's partial file: "THRTILE1", then the fingerprint, the writer's record
// and the tiler's state, each as a byte vector (throng/core/bytes.h).
constexpr char record_magic[] = "THRTILE1";

class TileCommand final : public MethodCommand<TilingJob> {
 public:
  TileCommand()
      : MethodCommand<TilingJob>(
            MethodSpec{.name = "tile",
                       .summary = "Fill a space-time region with deformable motion patches, leaving no dangling entry or exit",
                       .job = JobArgument::positional,
                       .job_help = "Tiling job (.yaml): region, library, obstacles, keyframes, options",
                       .inputs = {.count_text = "tile reads no crowd"},
                       .output_help = "Crowd file to write (.h5): the characters and the tiling",
                       .record = "tiling",
                       .made = "tiling"},
            Hooks{.run = tile}) {}

  void run(Context& context) override {
    const ConfigNode node = context.job(job_path_, flags_.overrides(), spec_.name);
    TilingJob job{};
    read_job(node, job);
    if (job.window_s <= 0) {
      if (resume_) throw ConfigError("--resume continues a windowed tiling (a job with `window:`); " + job_path_.string() + " has none");
      MethodCommand<TilingJob>::run(context);
      return;
    }
    const YAML::Node effective = effective_job(job);
    if (context.print_config_if_asked(effective)) return;
    check_distinct(job_path_, output_);
    windowed(context, job, effective);
  }

 protected:
  void more_arguments(CLI::App& app) override {
    app.add_flag("--resume", resume_,
                 "Continue a windowed tiling (window:) stopped by Ctrl-C, SIGTERM or a crash from its last complete window");
  }

 private:
  void windowed(Context& context, TilingJob& job, const YAML::Node& effective) {
    const std::string where = job_path_.string();
    if (context.communicator().size() > 1) {
      throw ConfigError(where + ": window: a windowed tiling runs on one rank (its windows follow one another); run it "
                        "without mpiexec, or spread several shots over ranks with a batch");
    }
    if (job.layout.repeat != std::array<int, 3>{1, 1, 1}) {
      throw ConfigError(where + ": output.repeat: a windowed tiling is laid once; repeat a tile with a job without `window`");
    }
    check_output_target(output_);
    context.limit_threads();
    const auto started = std::chrono::steady_clock::now();
    job.options.seed = context.global.seed;
    MethodRun r{context, where, false, output_, {}, {}};
    load_saved_library(job, r);
    const std::optional<CrowdFile> recorded = import_recorded(job, r);

    std::optional<tiling::Prepared> prepared;
    std::optional<tiling::WindowedTiler> tiler;
    const ResumablePaths paths = resumable_paths(output_);
    const std::string name = output_.filename().string();
    TilingStreamSetup setup;
    setup.provenance = context.provenance(effective, r.files_read, r.credits);
    // What the resume record is tied to: the program, the seed and the job as loaded (with --set and flags).
    const std::string fingerprint = setup.provenance.program_version + "\n" + std::to_string(context.global.seed) + "\n" + YAML::Dump(effective);
    std::optional<TilingStreamWriter> writer;
    try {
      prepared = tiling::prepare(job, recorded ? &recorded->motion : nullptr);
      setup.library = &prepared->library;
      setup.environment = &job.environment;
      setup.check = tiling::check_options_for(job.options);
      setup.frames_per_window = static_cast<std::size_t>(std::max(1.0, std::round(job.window_s * job.layout.frame_rate_hz)));
      setup.density_tolerance = job.options.density.tolerance;
      if (!prepared->keyframes.empty()) {
        throw ConfigError("keyframes: a windowed tiling takes none yet; tile a job with keyframes without `window`");
      }
      const tiling::WindowOptions window = tiling::window_options(job);
      if (resume_ && std::filesystem::exists(paths.state) && std::filesystem::exists(paths.partial)) {
        MemoryBudget budget{ReadLimits{}};
        const std::string text = read_text_file(paths.state, budget, "a throng tile resume record");
        if (text.compare(0, 8, record_magic) != 0) throw InputError(paths.state.string() + ": not a throng tile resume record");
        const std::vector<std::byte> bytes(reinterpret_cast<const std::byte*>(text.data()) + 8,
                                           reinterpret_cast<const std::byte*>(text.data()) + text.size());
        std::size_t at = 0;
        ByteReader in(bytes, at, paths.state.string());
        const std::vector<char> stored = in.get_vector<char>();
        if (std::string(stored.begin(), stored.end()) != fingerprint) {
          throw ConfigError(paths.state.string() + ": the interrupted run was made with another job, seed or program version; "
                            "run without --resume to start over");
        }
        const std::vector<std::byte> record_bytes = in.get_vector<std::byte>();
        std::size_t record_at = 0;
        const TilingStreamRecord record = TilingStreamRecord::load(record_bytes, record_at, paths.state.string());
        tiler.emplace(prepared->library, job.environment, job.options, window, in.get_vector<std::byte>());
        if (record.windows != tiler->next_window()) {
          throw InputError(paths.state.string() + ": the resume record's file part (" + std::to_string(record.windows) +
                           " windows) and tiler part (" + std::to_string(tiler->next_window()) + ") disagree: damaged record");
        }
        writer.emplace(paths.partial, name, setup, record);
        context.info("tile: resuming " + name + " after window " + std::to_string(record.windows) + " of " +
                     std::to_string(tiler->windows()));
      } else {
        if (resume_ && std::filesystem::exists(paths.state)) {
          // A record left by a run stopped after its output was in place: that run had finished.
          context.info("tile: the interrupted run of " + name + " had finished (" + name + " is complete); tiling again");
        } else if (resume_) {
          context.info("tile: no interrupted run of " + name + " to resume: starting from the first window");
        }
        std::filesystem::remove(paths.state);
        tiler.emplace(prepared->library, job.environment, job.options, window);
        writer.emplace(paths.partial, name, setup);
      }
    } catch (const ConfigError& e) {
      throw ConfigError(where + ": " + e.what());
    }

    tiling::tile_windows(
        *tiler,
        [&](const tiling::WindowOutput& out, const tiling::WindowedTiler& t) {
          const DeferredInterrupts hold;  // the window's data, flushed, and its record: both or neither
          writer->append(out);
          sync_file(paths.partial);  // on disk before the record that names it
          std::vector<std::byte> bytes, record;
          ByteWriter w(bytes);
          w.put_vector(std::vector<char>(fingerprint.begin(), fingerprint.end()));
          writer->record().save(record);
          w.put_vector(record);
          w.put_vector(t.state());
          AtomicOutput file(paths.state);
          file.write(std::string(record_magic, 8));
          file.write(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
          file.commit();
        },
        context.progress());

    WindowedSummary summary;
    summary.record = writer->record();
    const std::uint64_t lost = summary.record.lost_dangling;
    summary.patch_types = prepared->library.types.size();
    summary.density_asked = job.options.density.per_m2 > 0 || !job.options.density.zones.empty();
    summary.density_tolerance = job.options.density.tolerance;
    summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    {
      const DeferredInterrupts hold;
      writer->finish(summary);
      move_into_place(paths.partial, output_);
      std::filesystem::remove(paths.state);
    }
    if (summary.density_asked && !summary.record.density_met) {
      context.warn("tile: the density per area is off its target by up to " + std::to_string(100 * summary.record.density_worst) +
                   " % in a window (tolerance " + std::to_string(100 * summary.density_tolerance) +
                   " %): raise density.rounds or chains, or lower density.per_m2");
    }
    Report report;
    report["output"] = output_.string();
    ReportJson json(report);
    describe(json, summary);
    report["seed"] = context.global.seed;
    context.print(report);
    if (lost > 0) {
      throw NumericalError("tile: " + std::to_string(lost) + " dangling " + (lost == 1 ? "end remains" : "ends remain") +
                           " across the windows; the tiling was written to " + output_.string());
    }
  }

  bool resume_ = false;
};

}  // namespace

std::unique_ptr<Command> make_tile_command() { return std::make_unique<TileCommand>(); }

}  // namespace throng::cli
