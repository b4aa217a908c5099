// One factory per subcommand, each defined in its own file in this folder.
#pragma once

#include "../command.h"

namespace throng::cli {

std::unique_ptr<Command> make_import_command();
std::unique_ptr<Command> make_export_command();
std::unique_ptr<Command> make_edit_command();
std::unique_ptr<Command> make_formation_command();
std::unique_ptr<Command> make_info_command();
std::unique_ptr<Command> make_plot_command();
std::unique_ptr<Command> make_sketch_command();
std::unique_ptr<Command> make_collide_command();
std::unique_ptr<Command> make_split_command();
std::unique_ptr<Command> make_merge_command();
std::unique_ptr<Command> make_transform_command();
std::unique_ptr<Command> make_stitch_command();
std::unique_ptr<Command> make_timewarp_command();
std::unique_ptr<Command> make_tile_command();
std::unique_ptr<Command> make_check_tiling_command();
std::unique_ptr<Command> make_check_motion_command();
/// `throng run`: runs the other commands as steps (they must outlive it).
std::unique_ptr<Command> make_run_command(std::vector<Command*> commands);

}  // namespace throng::cli
