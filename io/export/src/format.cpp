#include <throng/core/errors.h>
#include <throng/io/export/csv_table.h>
#include <throng/io/export/format.h>
#include <throng/io/export/gltf.h>
#include <throng/io/export/usd.h>
#include <throng/io/export/xdmf.h>

namespace throng {

const std::vector<std::string>& export_format_names() {
  static const std::vector<std::string> names{"xdmf", "gltf", "usd", "pedpy", "csv"};
  return names;
}

ExportFormat parse_export_format(const std::string& name) {
  const auto& names = export_format_names();
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return static_cast<ExportFormat>(i);
  }
  std::string known;
  for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
  throw ConfigError("unknown export format '" + name + "', expected one of: " + known);
}

std::string export_extension(ExportFormat format) {
  switch (format) {
    case ExportFormat::xdmf: return ".xmf";
    case ExportFormat::gltf: return ".glb";
    case ExportFormat::usd: return ".usda";
    case ExportFormat::pedpy: return ".h5";
    case ExportFormat::csv: return ".csv";
  }
  return {};
}

void export_crowd(ExportFormat format, const std::filesystem::path& crowd, const std::filesystem::path& output,
                  const ExportOptions& options, const PedpyOptions& pedpy) {
  switch (format) {
    case ExportFormat::xdmf: export_xdmf(crowd, output); return;
    case ExportFormat::gltf: export_gltf(crowd, output, options); return;
    case ExportFormat::usd: export_usd(crowd, output, options); return;
    case ExportFormat::pedpy: export_pedpy(crowd, output, pedpy, options); return;
    case ExportFormat::csv: export_csv(crowd, output, options); return;
  }
}

}  // namespace throng
