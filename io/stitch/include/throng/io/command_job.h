// The job of a command that takes an optional job file and flags for some of its keys (`throng split`, `merge`,
// `stitch`, `transform`, `timewarp`): one ConfigNode that the same reader parses whether the keys came from a
// file, from flags or from a step of `throng run`.
#pragma once

#include <throng/io/config.h>

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <string>
#include <vector>

namespace throng {

/// The job file's keys (none when `job_file` is empty), then every key of `flags` over them (the flags the user
/// gave, by their job key names), then the --set overrides. `command` names the source in messages when there is
/// no file.
[[nodiscard]] ConfigNode command_job(const std::filesystem::path& job_file, const YAML::Node& flags,
                                     const std::vector<std::string>& set_overrides, const std::string& command);

/// A YAML flow sequence of numbers (for flags holding lists, and effective configs).
[[nodiscard]] YAML::Node flow_numbers(const std::vector<double>& values);

/// A YAML flow sequence of integers.
[[nodiscard]] YAML::Node flow_integers(const std::vector<std::int64_t>& values);

}  // namespace throng
