#include <throng/core/errors.h>
#include <throng/io/scene_config.h>

#include <catch2/catch.hpp>

#include <numbers>

using namespace throng;

TEST_CASE("obstacles and region read from YAML, and write back to the same scene") {
  const std::string text = R"(
obstacles:
  - circle: {center: [1, 2], radius: 0.5}
    name: pillar
  - polygon: [[0, 0], [0, 1], [1, 1], [1, 0]]   # clockwise: reversed
    motion:
      - {time: 0, translation: [0, 0], angle: 0}
      - {time: 4, translation: [2, 0], angle: 90}
  - wall: {from: [0, 0], to: [5, 0]}
region: {min: [0, 0], max: [10, 8], time: [0, 20], periodic: [true, true, false]}
)";
  const ConfigNode job = ConfigNode::parse(text, "scene.yaml");
  const Scene s = read_scene(job);
  job.finish();
  REQUIRE(s.obstacles.size() == 3);
  CHECK(std::get<Circle>(s.obstacles[0].shape).radius == 0.5);
  CHECK(s.obstacles[0].name == "pillar");
  CHECK_NOTHROW(validate(s.obstacles[1], "polygon"));  // now counter-clockwise
  CHECK(s.obstacles[1].motion[1].angle == Catch::Detail::Approx(std::numbers::pi / 2));
  CHECK(std::get<Wall>(s.obstacles[2].shape).thickness == 0.2);
  REQUIRE(s.region);
  CHECK(s.region->periodic == std::array<bool, 3>{true, true, false});

  YAML::Node out(YAML::NodeType::Map);
  write_scene(out, s);
  const Scene again = read_scene(ConfigNode(out, "written"));
  REQUIRE(again.obstacles.size() == 3);
  CHECK(std::get<ConvexPolygon>(again.obstacles[1].shape).vertices == std::get<ConvexPolygon>(s.obstacles[1].shape).vertices);
  CHECK(again.obstacles[1].motion[1].angle == Catch::Detail::Approx(s.obstacles[1].motion[1].angle));
  CHECK(again.region->max == s.region->max);
}

TEST_CASE("bad obstacles are config errors naming the line") {
  auto read = [](const std::string& text) { return read_scene(ConfigNode::parse(text, "s.yaml")); };
  CHECK_THROWS_WITH(read("obstacles:\n  - circle: {center: [0, 0], radius: 0}\n"), Catch::Contains("s.yaml:2") && Catch::Contains("radius"));
  CHECK_THROWS_AS(read("obstacles:\n  - {circle: {center: [0, 0], radius: 1}, wall: {from: [0, 0], to: [1, 1]}}\n"), ConfigError);
  CHECK_THROWS_WITH(read("obstacles:\n  - polygon: [[0, 0], [2, 0], [1, 0.2], [2, 2], [0, 2]]\n"), Catch::Contains("not convex"));
  CHECK_THROWS_WITH(read("region: {min: [0, 0], max: [0, 5]}\n"), Catch::Contains("region is empty"));
}
