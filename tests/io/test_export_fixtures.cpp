#include "test_export_fixtures.h"

#include <catch2/catch.hpp>
#include "test_paths.h"

#include <algorithm>
#include <cmath>

namespace throng::test {

CrowdFile export_crowd() {
  CrowdFile f;
  CrowdMotion& m = f.motion;
  m = CrowdMotion::with_shape(25, 6);
  m.ids = {10, 20, 30, 40, 50, 60};
  m.radii = {0.25, 0.2, 0.3, 0.45, 0.25, 0.35};
  m.species = {0, 0, 1, 1, 2, 0};
  for (std::size_t t = 0; t < 25; ++t) {
    m.times[t] = 2.0 + static_cast<double>(t) / 25.0;
    for (std::size_t n = 0; n < 6; ++n) {
      if ((n == 3 && t < 5) || (n == 4 && t >= 20)) continue;
      const double heading = 1.1 * static_cast<double>(n) - 2.0;
      const double walked = 1.3 * (n == 2 ? std::min(m.times[t] - 2.0, 0.4) : m.times[t] - 2.0);
      m.position(t, n) = Eigen::Vector3d(2.0 * n + walked * std::cos(heading), 1.0 - 0.5 * n + walked * std::sin(heading), 0.0);
    }
  }
  f.scene.obstacles.push_back({Circle{{4, 6}, 0.5}, {}, "pillar"});
  f.scene.obstacles.push_back({ConvexPolygon{{{8, 3}, {10, 3}, {10, 4}}}, {}, "kiosk, \"north\""});
  f.scene.obstacles.push_back({Wall{{-3, -5}, {13, -5}, 0.2}, {}, "fence"});
  f.provenance.program_version = "test";
  f.provenance.credits = {"test crowd"};
  return f;
}

CrowdFile posed_export_crowd() {
  CrowdFile f = export_crowd();
  CrowdMotion& m = f.motion;
  const std::size_t T = m.frame_count(), N = m.agent_count();
  m.orientations.assign(T * N * 4, absent);
  m.actions.assign(T * N, -1);
  m.action_table = standard_actions();
  m.action_table.push_back({"bow", ""});
  m.action_table.push_back({"wave, \"hello\"", "flag"});
  for (std::size_t t = 0; t < T; ++t) {
    for (std::size_t n = 0; n < N; ++n) {
      if (!m.present(t, n)) continue;
      const double heading = 1.1 * static_cast<double>(n) - 2.0 + 0.5236;
      m.orientation(t, n) = facing_along(Eigen::Vector3d(std::cos(heading), std::sin(heading), 0));
      m.action(t, n) = static_cast<std::int32_t>((t / 5 + n) % m.action_table.size());
    }
  }
  return f;
}

std::string run_tool(const std::string& command) {
  std::string output;
  const int status = run_command(command, &output);
  INFO(command << "\n" << output);
  REQUIRE(status == 0);
  return output;
}

std::vector<std::string> files_in(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace throng::test
