// Flags from an options schema (throng/core/schema.h): each field that names a flag becomes an option of the
// command, its help made from the schema (what it does, unit, default, range or words, job key). After parsing,
// the flags the user gave become overrides of the job (io/config.h: Override): their key paths, their values as
// YAML ("3,8" a list for a list option), and what the user typed, so the job reader checks them and a message
// about one names the flag ("--margin -1: value -1 is out of range, expected ≥ 0").
#pragma once

#include <throng/core/schema.h>
#include <throng/io/config.h>

#include <CLI/CLI.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace throng::cli {

class OptionFlags {
 public:
  /// Adds a flag for every field of `describe` that names one (run on a default Job: the defaults in the help).
  template <class Job>
  void add(CLI::App& app, void (*describe)(OptionBinder&, Job&)) {
    Job defaults{};
    add(app, [&](OptionBinder& b) { describe(b, defaults); });
  }
  void add(CLI::App& app, const std::function<void(OptionBinder&)>& describe);

  /// The flags the user gave, in the schema's order.
  [[nodiscard]] std::vector<Override> overrides() const;

  /// What the binder records per flag (entries are bound by address to CLI11: one allocation each).
  struct Entry {
    enum class Kind { value, list, on, off } kind;
    std::string path;                 ///< job key path
    std::string flag;                 ///< "--margin"
    std::optional<std::string> text;  ///< value or list as typed
    bool given = false;               ///< switches
  };

 private:
  std::vector<std::unique_ptr<Entry>> entries_;
};

}  // namespace throng::cli
