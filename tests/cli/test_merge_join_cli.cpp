// `throng merge --join-by id` as the inverse of `throng split` on a recorded crowd (issue 17): the two halves of
// zara01 cut at a time give back the same crowd (agents, ids, positions at every frame, obstacles); one id at two
// places is exit 3 naming it; without joining the people who cross the cut are renumbered and the walls kept once.
#include "positions_by_id.h"
#include "cli.h"
#include "test_paths.h"

#include <throng/io/crowd_file.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <map>

using namespace throng;
using Catch::Matchers::Contains;

namespace {

using test::run;

std::string s(const std::filesystem::path& p) { return p.string(); }


}  // namespace

TEST_CASE("zara01 split at a time and merged back joined by id is the same crowd") {
  const auto dir = test::scratch_dir("cli_merge_join");
  std::string out;
  REQUIRE(run("--quiet import " + s(test::real_data_dir() / "zara01") + " -o " + s(dir / "zara.h5")) == 0);
  const CrowdFile zara = read_crowd_file(dir / "zara.h5");
  REQUIRE(zara.scene.obstacles.size() > 0);
  REQUIRE(run("--quiet split " + s(dir / "zara.h5") + " --at-time 150 -o " + s(dir / "head.h5") + " --other " + s(dir / "tail.h5")) == 0);
  const CrowdFile head = read_crowd_file(dir / "head.h5"), tail = read_crowd_file(dir / "tail.h5");

  REQUIRE(run("--quiet --json merge " + s(dir / "head.h5") + " " + s(dir / "tail.h5") + " --join-by id --span union -o " +
                  s(dir / "back.h5"), &out) == 0);
  const auto report = nlohmann::json::parse(out);
  const CrowdFile back = read_crowd_file(dir / "back.h5");
  // The people seen on both sides of the cut are joined, none renumbered.
  const std::size_t crossing = head.motion.agent_count() + tail.motion.agent_count() - zara.motion.agent_count();
  CHECK(crossing > 0);
  CHECK(report["joined"] == nlohmann::json::array({crossing}));
  CHECK(report["id_shifts"] == nlohmann::json::array({0, 0}));
  CHECK(report["obstacles"] == zara.scene.obstacles.size());
  CHECK(report["shared_obstacles"] == zara.scene.obstacles.size());
  // The same crowd: frame times, agents and ids, positions at every frame, obstacles.
  CHECK(back.motion.times == zara.motion.times);
  REQUIRE(back.motion.agent_count() == zara.motion.agent_count());
  const auto original = test::positions_by_id(zara.motion), merged = test::positions_by_id(back.motion);
  REQUIRE(merged.size() == original.size());
  std::size_t differing = 0;
  for (const auto& [id, values] : original) differing += merged.count(id) && test::same_values(merged.at(id), values) ? 0 : 1;
  CHECK(differing == 0);
  CHECK(back.scene.obstacles.size() == zara.scene.obstacles.size());

  SECTION("the job key does the same as the flag") {
    test::write_file(dir / "merge.yaml", "join_by: id\nspan: union\n");
    REQUIRE(run("--quiet merge " + s(dir / "head.h5") + " " + s(dir / "tail.h5") + " --job " + s(dir / "merge.yaml") + " -o " +
                s(dir / "again.h5")) == 0);
    CHECK(test::positions_by_id(read_crowd_file(dir / "again.h5").motion).size() == original.size());
  }
  SECTION("without joining (the default) the crossing people are renumbered, the walls still kept once") {
    REQUIRE(run("--quiet --json merge " + s(dir / "head.h5") + " " + s(dir / "tail.h5") + " --span union -o " + s(dir / "two.h5"),
                &out) == 0);
    const auto two = nlohmann::json::parse(out);
    CHECK(two["agents"] == zara.motion.agent_count() + crossing);
    CHECK(two["id_shifts"][1] > 0);
    CHECK(two["obstacles"] == zara.scene.obstacles.size());
  }
  SECTION("one id at two places at one frame: exit 3 naming the id and the frame, nothing written") {
    REQUIRE(run("--quiet transform " + s(dir / "tail.h5") + " --translate=0.5,0 -o " + s(dir / "moved.h5")) == 0);
    CHECK(run("merge " + s(dir / "head.h5") + " " + s(dir / "moved.h5") + " --join-by id --span union -o " + s(dir / "bad.h5"),
              &out) == 3);
    CHECK_THAT(out, Contains("joined by id: agent ") && Contains(" of the first, 0 of the second") && Contains("join_tolerance"));
    CHECK_FALSE(std::filesystem::exists(dir / "bad.h5"));
  }
}
