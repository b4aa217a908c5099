#include <throng/core/errors.h>
#include <throng/core/format.h>
#include <throng/io/export/request.h>

namespace throng {

void describe(OptionBinder& b, ExportRequest& r) {
  b.choice({.key = "format", .flag = "--format",
            .help = "xdmf (.xmf for ParaView), gltf (.glb), usd (.usda), pedpy (.h5 for PedPy), csv (.csv + _obstacles.csv); "
                    "default: told by the output's extension"},
           r.format,
           {{"xdmf", ExportFormat::xdmf}, {"gltf", ExportFormat::gltf}, {"usd", ExportFormat::usd},
            {"pedpy", ExportFormat::pedpy}, {"csv", ExportFormat::csv}});
  b.field({.key = "standing_speed", .unit = "m/s", .range = Range::positive(), .flag = "--standing-speed",
           .help = "crowds without stored facing: slower is standing (keeps its last facing), else it faces its velocity"},
          r.options.pose.standing_speed);
  b.field({.key = "running_speed", .unit = "m/s", .range = Range::positive(), .flag = "--running-speed",
           .help = "crowds without stored actions: from this speed on the action is run (walk below, stand below standing_speed)"},
          r.options.pose.running_speed);
  b.choice({.key = "walkable_area", .flag = "--walkable-area",
            .help = "pedpy: write the walkable area if the crowd has static obstacles (if_obstacles), always (required: "
                    "an error without them) or never (none)"},
           r.walkable_area,
           {{"if_obstacles", PedpyOptions::WalkableArea::if_obstacles},
            {"required", PedpyOptions::WalkableArea::required},
            {"none", PedpyOptions::WalkableArea::none}});
}

ExportFormat resolve_format(const ExportRequest& request, const std::filesystem::path& output) {
  const std::optional<ExportFormat> told = request.format ? request.format : export_format_of(output);
  if (!told) {
    throw ConfigError("no export format: give --format (" + join_export_format_names() + "), or an output ending in " +
                      ".xmf, .glb, .usda, .h5 or .csv");
  }
  const PathPoseRule& pose = request.options.pose;
  if (!(pose.running_speed > pose.standing_speed)) {
    throw ConfigError("running_speed " + shortest(pose.running_speed) + " m/s must be above standing_speed " +
                      shortest(pose.standing_speed) + " m/s");
  }
  if (request.walkable_area && *told != ExportFormat::pedpy) {
    throw ConfigError("walkable_area applies to the pedpy format only, not to " +
                      export_format_names()[static_cast<std::size_t>(*told)]);
  }
  return *told;
}

PedpyOptions pedpy_options(const ExportRequest& request) {
  PedpyOptions o;
  if (request.walkable_area) o.walkable_area = *request.walkable_area;
  return o;
}

}  // namespace throng
