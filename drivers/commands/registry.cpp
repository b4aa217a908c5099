// The list of subcommands. Adding one: a file in commands/, one line here, one line in drivers/CMakeLists.txt.
#include "../command.h"
#include "factories.h"

namespace throng::cli {

std::vector<std::unique_ptr<Command>> all_commands() {
  std::vector<std::unique_ptr<Command>> c;
  c.push_back(make_import_command());
  c.push_back(make_sketch_command());
  c.push_back(make_edit_command());
  c.push_back(make_formation_command());
  c.push_back(make_collide_command());
  c.push_back(make_split_command());
  c.push_back(make_merge_command());
  c.push_back(make_transform_command());
  c.push_back(make_stitch_command());
  c.push_back(make_timewarp_command());
  c.push_back(make_tile_command());
  c.push_back(make_check_tiling_command());
  c.push_back(make_check_motion_command());
  c.push_back(make_export_command());
  c.push_back(make_info_command());
  c.push_back(make_plot_command());

  std::vector<Command*> steps;
  for (const auto& command : c) steps.push_back(command.get());
  c.push_back(make_run_command(std::move(steps)));
  return c;
}

}  // namespace throng::cli
