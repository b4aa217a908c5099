// The export formats by name, and one entry point for a crowd file on disk (what `throng export --format F`
// will call). Each format's own header says what it writes.
#pragma once

#include <throng/io/export/pedpy.h>
#include <throng/io/export/pose_rule.h>

#include <filesystem>
#include <string>
#include <vector>

namespace throng {

enum class ExportFormat { xdmf, gltf, usd, pedpy, csv };

/// Every format's name, in the order above: "xdmf", "gltf", "usd", "pedpy", "csv".
[[nodiscard]] const std::vector<std::string>& export_format_names();
/// The format called `name`; ConfigError (exit 2) naming the known formats otherwise.
[[nodiscard]] ExportFormat parse_export_format(const std::string& name);
/// The file extension a format writes: ".xmf", ".glb", ".usda", ".h5", ".csv".
[[nodiscard]] std::string export_extension(ExportFormat format);

/// Exports the crowd file `crowd` to `output` in `format`. Errors: IoError (exit 4) when the output folder does
/// not exist or a file cannot be read or written, InputError (exit 3) for a malformed crowd or one the format
/// cannot hold, ConfigError (exit 2) for a request the crowd cannot meet (pedpy's required walkable area without
/// obstacles), and `output` naming the crowd itself; no partial file is left in any case.
void export_crowd(ExportFormat format, const std::filesystem::path& crowd, const std::filesystem::path& output,
                  const ExportOptions& options = {}, const PedpyOptions& pedpy = {});

}  // namespace throng
