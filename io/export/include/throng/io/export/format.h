// The export formats by name, and the entry points `throng export --format F` and the pipeline's `export` step
// call. Each format's own header says what it writes.
#pragma once

#include <throng/io/crowd_file.h>
#include <throng/io/export/pedpy.h>
#include <throng/io/export/pose_rule.h>

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace throng {

enum class ExportFormat { xdmf, gltf, usd, pedpy, csv };

/// Every format's name, in the order above: "xdmf", "gltf", "usd", "pedpy", "csv".
[[nodiscard]] const std::vector<std::string>& export_format_names();
/// "xdmf, gltf, usd, pedpy, csv" (for messages).
[[nodiscard]] std::string join_export_format_names();
/// The format called `name`; ConfigError (exit 2) naming the known formats otherwise.
[[nodiscard]] ExportFormat parse_export_format(const std::string& name);
/// The file extension a format writes: ".xmf", ".glb", ".usda", ".h5", ".csv".
[[nodiscard]] std::string export_extension(ExportFormat format);
/// The format an output's extension tells: .xmf xdmf, .glb gltf, .usda usd, .h5 pedpy (an export never writes a
/// crowd file), .csv csv; nullopt for any other.
[[nodiscard]] std::optional<ExportFormat> export_format_of(const std::filesystem::path& output);
/// Where an export goes when no output is named: beside the crowd, its name with the format's extension
/// (crowd.h5 → crowd.xmf, crowd.glb, crowd.usda, crowd.csv), and crowd.pedpy.h5 for pedpy (not the crowd itself).
[[nodiscard]] std::filesystem::path default_export_output(ExportFormat format, const std::filesystem::path& crowd);

/// What an export wrote, for the report.
struct ExportSummary {
  std::vector<std::filesystem::path> files;  ///< every file written (csv: the rows and the obstacles)
  std::size_t agents = 0, frames = 0;
  std::size_t rows = 0;                      ///< present agent-frames: csv's and pedpy's rows, gltf's and usd's samples
                                             ///< shown (xdmf: 0, it reads no positions)
};

/// Exports the crowd file `crowd` to `output` in `format`. Checks first, before reading the crowd: `output` is not
/// the crowd itself (ConfigError, exit 2) and its folder exists (IoError, exit 4). Errors: IoError when a file
/// cannot be read or written, InputError (exit 3) for a malformed crowd or one the format cannot hold, ConfigError
/// for a request the crowd cannot meet (pedpy's required walkable area without obstacles); no partial file is
/// left in any case.
ExportSummary export_crowd(ExportFormat format, const std::filesystem::path& crowd, const std::filesystem::path& output,
                           const ExportOptions& options = {}, const PedpyOptions& pedpy = {});
/// The same for a crowd held in memory (a pipeline's). xdmf points into a crowd file on disk and has no such form:
/// ConfigError.
ExportSummary export_crowd(ExportFormat format, const CrowdFile& crowd, const std::filesystem::path& output,
                           const ExportOptions& options = {}, const PedpyOptions& pedpy = {});

}  // namespace throng
