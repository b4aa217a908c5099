// One subcommand of the `throng` program: its flags (bound to its own members in setup) and its run.
// Each subcommand lives in its own file under commands/ and is listed once in commands/registry.cpp.
#pragma once

#include "context.h"

#include <CLI/CLI.hpp>

#include <memory>
#include <string>
#include <vector>

namespace throng::cli {

class Command {
 public:
  virtual ~Command() = default;
  [[nodiscard]] virtual std::string name() const = 0;
  [[nodiscard]] virtual std::string summary() const = 0;
  /// Adds this command's positional arguments and flags to `app` (its own subcommand).
  virtual void setup(CLI::App& app) = 0;
  /// Does the work. Throws throng errors; main maps them to exit codes.
  virtual void run(Context& context) = 0;
};

/// Every subcommand, in the order `throng --help` lists them.
[[nodiscard]] std::vector<std::unique_ptr<Command>> all_commands();

}  // namespace throng::cli
