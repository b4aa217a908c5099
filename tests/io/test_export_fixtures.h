// The crowd every export test writes, and what the tests share: 6 agents over 25 frames at 25 fps starting at
// t = 2 s, walking in different directions at 1.3 m/s; agent 40 enters at frame 5, agent 50 leaves after
// frame 19, agent 30 stands still from frame 10 on (the standing rule keeps its facing); three species, radii
// 0.2–0.45 m, a circle, a polygon and a wall as static obstacles.
#pragma once

#include <throng/io/crowd_file.h>

#include <filesystem>
#include <string>

namespace throng::test {

/// Without stored facing or actions (the exporters derive them from the paths).
CrowdFile export_crowd();
/// With stored facing (each agent faces 30° left of its path, so a derived facing would differ) and actions
/// from a table with a tiled patch's label and a prop, one name holding a comma and a quote.
CrowdFile posed_export_crowd();

/// Runs `command`, returns its output; the test fails (showing the output) unless it exits 0.
std::string run_tool(const std::string& command);

/// Files in `dir` (names), to check that a failed export left nothing behind.
std::vector<std::string> files_in(const std::filesystem::path& dir);

}  // namespace throng::test
