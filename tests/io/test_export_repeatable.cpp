// Exports are formatted in parallel over agent ranges: the same crowd gives the same bytes whatever the number
// of threads.
#include "test_export_fixtures.h"
#include "test_paths.h"

#include <throng/core/parallel.h>
#include <throng/io/export/csv_table.h>
#include <throng/io/export/gltf.h>
#include <throng/io/export/pedpy.h>
#include <throng/io/export/usd.h>

#include <catch2/catch.hpp>

#include <fstream>
#include <limits>
#include <map>
#include <sstream>

using namespace throng;

namespace {

std::string bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// `crowd`'s agents repeated side by side (3 m apart per copy) to `agents` agents, with their presence (and stored
// facing and actions, when it has them).
CrowdFile widened(CrowdFile crowd, std::size_t agents) {
  const CrowdMotion& small = crowd.motion;
  const std::size_t N = small.agent_count(), T = small.frame_count();
  CrowdMotion big = CrowdMotion::with_shape(T, agents);
  big.times = small.times;
  if (!small.orientations.empty()) big.orientations.assign(T * agents * 4, std::numeric_limits<double>::quiet_NaN());
  if (!small.actions.empty()) big.actions.assign(T * agents, -1), big.action_table = small.action_table;
  for (std::size_t t = 0; t < T; ++t) {
    for (std::size_t n = 0; n < agents; ++n) {
      if (!small.present(t, n % N)) continue;
      big.position(t, n) = small.position(t, n % N) + Eigen::Vector3d(0.0, 3.0 * static_cast<double>(n / N), 0.0);
      if (!small.orientations.empty()) big.orientation(t, n) = small.orientation(t, n % N);
      if (!small.actions.empty()) big.action(t, n) = small.action(t, n % N);
    }
  }
  crowd.motion = big;
  return crowd;
}

void check_same_bytes_on_any_thread_count(const CrowdFile& crowd, const std::filesystem::path& dir) {
  std::map<std::string, std::string> first;
  for (const std::size_t threads : {std::size_t{1}, std::size_t{4}}) {
    const ThreadLimit limit(threads);
    export_gltf(crowd, dir / "crowd.glb");
    export_usd(crowd, dir / "crowd.usda");
    export_csv(crowd, dir / "crowd.csv");
    export_pedpy(crowd, dir / "crowd.h5");
    for (const char* name : {"crowd.glb", "crowd.usda", "crowd.csv", "crowd.h5"}) {
      INFO(name << " on " << threads << " threads");
      if (threads == 1) first[name] = bytes(dir / name);
      else CHECK(bytes(dir / name) == first[name]);
    }
  }
}

}  // namespace

TEST_CASE("every export writes the same bytes on one thread and on several") {
  const auto dir = test::scratch_dir("export_repeatable");
  // Enough agents for every one of the 16 agent ranges to hold several.
  check_same_bytes_on_any_thread_count(widened(test::export_crowd(), 100), dir);
}

TEST_CASE("exports streamed in many blocks write the same bytes on one thread and on several") {
  const auto dir = test::scratch_dir("export_repeatable_blocks");
  // 4,000 agents × 25 frames: the text formats stream it in several blocks of frames (csv about 2 frames a block),
  // pedpy in blocks across a whole HDF5 chunk (100,000 rows); stored facing and actions held where absent.
  const CrowdFile crowd = widened(test::posed_export_crowd(), 4000);
  check_same_bytes_on_any_thread_count(crowd, dir);
  // The rows are all there, in frame order: every present agent-frame once.
  std::size_t present = 0;
  for (std::size_t t = 0; t < crowd.motion.frame_count(); ++t) {
    for (std::size_t n = 0; n < crowd.motion.agent_count(); ++n) present += crowd.motion.present(t, n) ? 1 : 0;
  }
  std::ifstream csv(dir / "crowd.csv");
  std::string line;
  std::getline(csv, line);
  std::size_t rows = 0;
  long last_frame = -1;
  bool ordered = true;
  while (std::getline(csv, line)) {
    const long frame = std::stol(line.substr(0, line.find(',')));
    ordered = ordered && frame >= last_frame;
    last_frame = frame;
    ++rows;
  }
  CHECK(rows == present);
  CHECK(ordered);
  CHECK(last_frame == static_cast<long>(crowd.motion.frame_count()) - 1);
}
