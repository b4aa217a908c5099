// Flags that stand for keys of a command's job file (`throng split --at-frame 120` is the job key `at_frame: 120`):
// the clip commands (split, merge, transform, stitch, timewarp) take an optional --job file and these flags over
// it, and read both through the same job reader as their `throng run` step (io/command_job.h).
#pragma once

#include <CLI/CLI.hpp>
#include <yaml-cpp/yaml.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace throng::cli {

class JobFlags {
 public:
  /// A flag holding one value (a number or a word), stored as the job key `key`.
  CLI::Option* value(CLI::App& app, const std::string& flag, const std::string& key, const std::string& help);
  /// A flag holding a comma-separated list (`--frames 10,40`), stored as a sequence.
  CLI::Option* list(CLI::App& app, const std::string& flag, const std::string& key, const std::string& help);
  /// A switch, stored as `key: true` when given.
  CLI::Option* flag(CLI::App& app, const std::string& flag, const std::string& key, const std::string& help);

  /// The keys of the flags the user gave (a mapping; empty when none). Values are parsed as YAML scalars, so the
  /// job reader checks them and names the key in its messages.
  [[nodiscard]] YAML::Node yaml() const;

 private:
  enum class Kind { value, list, flag };
  struct Entry {
    std::string key;
    Kind kind;
    std::optional<std::string> text;
    bool given = false;
  };
  // Entries are bound by address to CLI11, so they must not move: one allocation each.
  std::vector<std::unique_ptr<Entry>> entries_;
};

}  // namespace throng::cli
