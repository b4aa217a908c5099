// What `throng export` and the pipeline's `export` step are asked: the format (or none: told by the output's
// extension), the facing and action rule for crowds that store none, and pedpy's walkable area. Its schema
// (describe) gives the keys, the flags and their help; docs/commands/export.md shows them.
//
//   format: gltf                 # xdmf, gltf, usd, pedpy, csv; absent or "": from the output's extension
//   standing_speed: 0.3          # m/s, > 0: slower is standing (keeps its last facing)   [--standing-speed]
//   running_speed: 2.0           # m/s, > standing_speed: from here on running            [--running-speed]
//   walkable_area: if_obstacles  # pedpy only: if_obstacles, required, none              [--walkable-area]
#pragma once

#include <throng/core/schema.h>
#include <throng/io/export/format.h>

#include <filesystem>
#include <string>

namespace throng {

struct ExportRequest {
  std::string format;  ///< a name of export_format_names(), or "" : told by the output's extension (export_format_of)
  ExportOptions options;
  /// pedpy's walkable area; another value than the default with another format is a ConfigError (it would do
  /// nothing).
  PedpyOptions::WalkableArea walkable_area = PedpyOptions{}.walkable_area;
};

void describe(OptionBinder& b, ExportRequest& request);

/// The format the request names, or the one `output`'s extension tells (export_format_of); ConfigError (exit 2)
/// when neither says, or for options that tie together wrongly: running_speed not above standing_speed, a
/// walkable_area other than if_obstacles asked of a format other than pedpy.
[[nodiscard]] ExportFormat resolve_format(const ExportRequest& request, const std::filesystem::path& output);

/// pedpy's options as the request gives them.
[[nodiscard]] PedpyOptions pedpy_options(const ExportRequest& request);

}  // namespace throng
