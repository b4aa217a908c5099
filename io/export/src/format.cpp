#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>
#include <throng/io/export/csv_table.h>
#include <throng/io/export/format.h>
#include <throng/io/export/gltf.h>
#include <throng/io/export/usd.h>
#include <throng/io/export/xdmf.h>

namespace throng {
namespace {

// The rows a table export writes: one per present agent and frame.
std::size_t present_count(const CrowdMotion& m) {
  std::size_t rows = 0;
  for (std::size_t t = 0; t < m.frame_count(); ++t) {
    for (std::size_t n = 0; n < m.agent_count(); ++n) rows += m.present(t, n) ? 1 : 0;
  }
  return rows;
}

}  // namespace

const std::vector<std::string>& export_format_names() {
  static const std::vector<std::string> names{"xdmf", "gltf", "usd", "pedpy", "csv"};
  return names;
}

std::string join_export_format_names() {
  std::string known;
  for (const auto& n : export_format_names()) known += (known.empty() ? "" : ", ") + n;
  return known;
}

ExportFormat parse_export_format(const std::string& name) {
  const auto& names = export_format_names();
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return static_cast<ExportFormat>(i);
  }
  throw ConfigError("unknown export format '" + name + "', expected one of: " + join_export_format_names());
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

std::optional<ExportFormat> export_format_of(const std::filesystem::path& output) {
  const std::string extension = output.extension().string();
  for (const auto& name : export_format_names()) {
    const ExportFormat format = parse_export_format(name);
    if (export_extension(format) == extension) return format;
  }
  return std::nullopt;
}

std::filesystem::path default_export_output(ExportFormat format, const std::filesystem::path& crowd) {
  std::filesystem::path output = crowd;
  return output.replace_extension(format == ExportFormat::pedpy ? ".pedpy.h5" : export_extension(format));
}

ExportSummary export_crowd(ExportFormat format, const std::filesystem::path& crowd, const std::filesystem::path& output,
                           const ExportOptions& options, const PedpyOptions& pedpy) {
  if (format == ExportFormat::xdmf) {
    const CrowdShape shape = export_xdmf(crowd, output);
    return {.files = {output}, .agents = shape.agents, .frames = shape.frames};
  }
  check_distinct(crowd, output);
  if (format == ExportFormat::csv) check_distinct(crowd, csv_obstacles_path(output));
  check_output_target(output);  // before reading the crowd
  return export_crowd(format, read_crowd_file(crowd), output, options, pedpy);
}

ExportSummary export_crowd(ExportFormat format, const CrowdFile& crowd, const std::filesystem::path& output,
                           const ExportOptions& options, const PedpyOptions& pedpy) {
  ExportSummary summary{.files = {output}, .agents = crowd.motion.agent_count(), .frames = crowd.motion.frame_count()};
  switch (format) {
    case ExportFormat::xdmf:
      throw ConfigError("xdmf points into a crowd file on disk and this crowd is held in memory: write the crowd "
                        "(a step's output) and export that file");
    case ExportFormat::gltf: export_gltf(crowd, output, options); break;
    case ExportFormat::usd: export_usd(crowd, output, options); break;
    case ExportFormat::pedpy: export_pedpy(crowd, output, pedpy, options); break;
    case ExportFormat::csv:
      export_csv(crowd, output, options);
      summary.files.push_back(csv_obstacles_path(output));
      break;
  }
  summary.rows = present_count(crowd.motion);
  return summary;
}

}  // namespace throng
