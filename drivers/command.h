// One subcommand of the `throng` program: its flags (bound to its own members in setup) and its run.
// Each subcommand lives in its own file under commands/ and is listed once in commands/registry.cpp.
#pragma once

#include "context.h"

#include <throng/io/config.h>
#include <throng/io/crowd_file.h>

#include <CLI/CLI.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace throng::cli {

/// What a step of `throng run` makes: a crowd, and the method data to store with it when it is written.
struct StepResult {
  CrowdFile crowd;
  ExtraWriter extra;  ///< may be empty; must own what it writes (it runs after the step returns)
};

class Command {
 public:
  virtual ~Command() = default;
  [[nodiscard]] virtual std::string name() const = 0;
  [[nodiscard]] virtual std::string summary() const = 0;
  /// Adds this command's positional arguments and flags to `app` (its own subcommand).
  virtual void setup(CLI::App& app) = 0;
  /// Does the work. Throws throng errors; main maps them to exit codes.
  virtual void run(Context& context) = 0;

  /// Runs as a step of `throng run` (see drivers/pipeline.h for the pipeline keys). `step` holds the step's own
  /// keys (the keys of the command's job file; the pipeline keys are already removed, and `output` too when
  /// makes_crowd()); the step must read them all and call step.finish(). `inputs` are the crowds it reads: the
  /// previous crowd-making step's result (when reads_crowds()) unless the step names its inputs. Returns the crowd
  /// it makes (nullopt for steps that only write pictures or tables). Default: this command cannot be a step (ConfigError).
  virtual std::optional<StepResult> run_step(const ConfigNode& step, const std::vector<const CrowdFile*>& inputs, Context& context);
  /// True when the step makes a crowd (then the pipeline writes it where the step's `output` key says).
  [[nodiscard]] virtual bool makes_crowd() const { return true; }
  /// False when the step never reads a crowd (sketch, tile): it is not given the previous step's crowd, and one it
  /// names is an error.
  [[nodiscard]] virtual bool reads_crowds() const { return true; }
};

/// Every subcommand, in the order `throng --help` lists them.
[[nodiscard]] std::vector<std::unique_ptr<Command>> all_commands();

}  // namespace throng::cli
