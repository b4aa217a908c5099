// What every subcommand gets: the global flags, the command line, progress, reports, and the job helpers that
// make every method command behave the same (--print-config, --set, provenance in the output).
#pragma once

#include "report_json.h"

#include <throng/core/progress.h>
#include <throng/io/config.h>
#include <throng/io/crowd_file.h>
#include <throng/process/process.h>

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace spdlog {
class logger;
}

namespace throng::cli {

/// Flags every subcommand accepts (before or after its name).
struct GlobalOptions {
  std::size_t threads = 0;            ///< 0: all hardware threads
  std::uint64_t seed = 1;             ///< written to every output; each parallel task derives its own stream
  bool quiet = false;                 ///< no progress, warnings and errors only
  bool json = false;                  ///< reports on stdout as one JSON object
  bool print_config = false;          ///< print the effective options as YAML and stop
  std::vector<std::string> set;       ///< key.path=value overrides applied to the job
  /// How every crowd file the run writes stores its per-frame arrays (--compression deflate|none): deflated
  /// (the default: 2x to 10x fewer bytes) or plain (no compression work; see README "Global options").
  CrowdStorage storage = CrowdStorage::compressed;
};

class Context {
 public:
  /// `process` is the program's (main.cpp), set up before anything runs.
  Context(int argc, char** argv, Process& process);
  ~Context();

  GlobalOptions global;

  [[nodiscard]] Process& process() noexcept { return process_; }
  /// The ranks the methods spread their work over (Process::communicator).
  [[nodiscard]] const Communicator& communicator() const { return process_.communicator(); }
  /// True on the rank that writes outputs and prints reports (rank 0; the only one without mpiexec).
  [[nodiscard]] bool writer() const { return process_.world_rank() == 0; }

  /// The full command line, shell-quoted, for provenance: without the flags that only steer how a run proceeds
  /// (run's --resume and --checkpoint-dir), so a resumed run records what an uninterrupted one does.
  [[nodiscard]] const std::string& command_line() const noexcept { return command_line_; }
  /// Where solvers report progress (a bar on a terminal, PROGRESS lines on a pipe, nothing with --quiet).
  /// Inside a pipeline step, a view that maps the step's fraction into the whole run's.
  [[nodiscard]] Progress& progress();
  /// While alive, progress() reports into [first, first + span) of the whole run, stages prefixed by `label`.
  class ProgressScope {
   public:
    ProgressScope(Context& context, double first, double span, std::string label);
    ~ProgressScope();
    ProgressScope(const ProgressScope&) = delete;
    ProgressScope& operator=(const ProgressScope&) = delete;

   private:
    struct View;
    Context& context_;
    std::unique_ptr<View> view_;
    Progress* previous_;
  };
  /// Applies --threads for the rest of the run (before solving; later calls keep the first limit).
  void limit_threads();

  /// Loads a job file and applies the --set overrides.
  [[nodiscard]] ConfigNode load_job(const std::filesystem::path& path) const;
  /// A command's job: the job file (none when `path` is empty: an empty job named `name`), the flags the user
  /// gave over its keys, then --set. Messages about a value name the file's line, the flag or the --set argument.
  [[nodiscard]] ConfigNode job(const std::filesystem::path& path, const std::vector<Override>& flags,
                               const std::string& name) const;
  /// The options of a command that takes no job file (import, plot, export, check-tiling): its flags and --set,
  /// read through `describe` with every key accounted for. Returns the effective job (for --print-config and the
  /// provenance): `arguments`, the files the command line names (an empty one is left out), then the options.
  template <class Options>
  [[nodiscard]] YAML::Node options(const std::vector<Override>& flags, const std::string& name,
                                   void (*describe)(OptionBinder&, Options&), Options& values,
                                   const std::vector<std::pair<std::string, std::string>>& arguments) const {
    const ConfigNode node = job({}, flags, name);
    read_options(node, describe, values);
    node.finish();
    YAML::Node effective(YAML::NodeType::Map);
    for (const auto& [key, value] : arguments) {
      if (!value.empty()) effective[key] = value;
    }
    write_options(effective, describe, values);
    return effective;
  }
  /// Provenance for an output: version, command line, seed, the effective options, inputs, and `credits`
  /// (of every input the output derives from, each once).
  [[nodiscard]] Provenance provenance(const YAML::Node& effective_options, const std::vector<std::string>& inputs,
                                      const std::vector<std::string>& credits = {}) const;

  /// If --print-config was given: prints `effective_options` as YAML on stdout and returns true (the command
  /// then stops without running).
  bool print_config_if_asked(const YAML::Node& effective_options) const;

  /// Prints a report on stdout (as JSON with --json).
  void print(const Report& report) const;
  /// The text print() writes for `report`.
  [[nodiscard]] std::string render(const Report& report) const;
  /// Logs on stderr unless --quiet.
  void info(const std::string& message) const;
  void warn(const std::string& message) const;

 private:
  spdlog::logger& log() const;
  Process& process_;
  mutable std::shared_ptr<spdlog::logger> logger_;
  std::string command_line_;
  std::unique_ptr<Progress> progress_;
  Progress* scoped_progress_ = nullptr;
  bool threads_limited_ = false;
};

}  // namespace throng::cli
