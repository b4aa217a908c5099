// What every subcommand gets: the global flags, the command line, progress, reports, and the job helpers that
// make every method command behave the same (--print-config, --set, provenance in the output).
#pragma once

#include <throng/core/parallel.h>
#include <throng/core/progress.h>
#include <throng/io/config.h>
#include <throng/io/crowd_file.h>

#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
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
};

/// A report on stdout: key/value pairs, printed as "key: value" lines or as JSON (--json).
using Report = nlohmann::ordered_json;

class Context {
 public:
  Context(int argc, char** argv);
  ~Context();

  GlobalOptions global;

  /// The full command line, shell-quoted, for provenance.
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
  /// Applies --threads for the rest of the run (call once, before solving).
  void limit_threads();

  /// Loads a job file and applies the --set overrides.
  [[nodiscard]] ConfigNode load_job(const std::filesystem::path& path) const;
  /// Provenance for an output: version, command line, seed, the effective options, inputs; credits are merged
  /// from the inputs' provenance.
  [[nodiscard]] Provenance provenance(const YAML::Node& effective_options, const std::vector<std::string>& inputs,
                                      const std::vector<const Provenance*>& sources = {}) const;
  /// If --print-config was given: prints `effective_options` as YAML on stdout and returns true (the command
  /// then stops without running).
  bool print_config_if_asked(const YAML::Node& effective_options) const;

  /// Prints a report on stdout (as JSON with --json).
  void print(const Report& report) const;
  /// Logs on stderr unless --quiet.
  void info(const std::string& message) const;
  void warn(const std::string& message) const;

 private:
  spdlog::logger& log() const;
  mutable std::shared_ptr<spdlog::logger> logger_;
  std::string command_line_;
  std::unique_ptr<Progress> progress_;
  Progress* scoped_progress_ = nullptr;
  std::unique_ptr<ThreadLimit> threads_;
};

}  // namespace throng::cli
