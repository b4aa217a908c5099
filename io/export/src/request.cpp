#include <throng/core/errors.h>
#include <throng/core/format.h>
#include <throng/io/export/request.h>

namespace throng {

void describe(OptionBinder& b, ExportRequest& r) {
  std::vector<std::string> formats{""};  // "": told by the output's extension
  formats.insert(formats.end(), export_format_names().begin(), export_format_names().end());
  b.choice({.key = "format", .flag = "--format",
            .help = "the format: xdmf (.xmf for ParaView), gltf (.glb), usd (.usda), pedpy (.h5 for PedPy), csv "
                    "(.csv + _obstacles.csv); none: told by the output's extension"},
           r.format, formats);
  b.field({.key = "standing_speed", .unit = "m/s", .range = Range::positive(), .flag = "--standing-speed",
           .help = "for crowds without stored facing: slower is standing (keeps its last facing), else it faces its velocity"},
          r.options.pose.standing_speed);
  b.field({.key = "running_speed", .unit = "m/s", .range = Range::positive(), .flag = "--running-speed",
           .help = "for crowds without stored actions: from this speed on the action is run (walk below, stand below standing_speed)"},
          r.options.pose.running_speed);
  b.choice({.key = "walkable_area", .flag = "--walkable-area",
            .help = "for pedpy: write the walkable area if the crowd has static obstacles (if_obstacles), always (required: "
                    "an error without them) or never (none)"},
           r.walkable_area,
           {{"if_obstacles", PedpyOptions::WalkableArea::if_obstacles},
            {"required", PedpyOptions::WalkableArea::required},
            {"none", PedpyOptions::WalkableArea::none}});
}

ExportFormat resolve_format(const ExportRequest& request, const std::filesystem::path& output) {
  const std::optional<ExportFormat> told =
      request.format.empty() ? export_format_of(output) : std::optional(parse_export_format(request.format));
  if (!told) {
    throw ConfigError("no export format: give --format (" + join_export_format_names() + "), or an output ending in " +
                      ".xmf, .glb, .usda, .h5 or .csv");
  }
  const PathPoseRule& pose = request.options.pose;
  if (!(pose.running_speed > pose.standing_speed)) {
    throw ConfigError("running_speed " + shortest(pose.running_speed) + " m/s must be above standing_speed " +
                      shortest(pose.standing_speed) + " m/s");
  }
  if (request.walkable_area != PedpyOptions{}.walkable_area && *told != ExportFormat::pedpy) {
    throw ConfigError("walkable_area applies to the pedpy format only, not to " +
                      export_format_names()[static_cast<std::size_t>(*told)]);
  }
  return *told;
}

PedpyOptions pedpy_options(const ExportRequest& request) {
  PedpyOptions o;
  o.walkable_area = request.walkable_area;
  return o;
}

}  // namespace throng
