#include "synthetic_crowd.h"

#include <throng/core/errors.h>
#include <throng/graph/clip.h>

#include <catch2/catch.hpp>

using namespace throng;
using Catch::Matchers::Contains;

TEST_CASE("a clip samples every step, always keeps its last frame and the required frames") {
  const CrowdMotion crowd = test::marching_grid(2, 3, 30);
  ClipOptions options;
  options.first_frame = 3;
  options.last_frame = 20;
  options.sample_step = 5;
  const std::size_t required[] = {9, 4};
  const Clip clip = make_clip(crowd, options, required);
  CHECK(clip.frames == std::vector<std::size_t>{3, 4, 8, 9, 13, 18, 20});
  CHECK(clip.agent_count() == 6);
  CHECK(clip.ids.front() == 100);
  for (std::size_t i = 0; i < clip.sample_count(); ++i) {
    CHECK(clip.times[i] == crowd.times[clip.frames[i]]);
    for (std::size_t j = 0; j < clip.agent_count(); ++j) {
      CHECK(clip.positions(clip.vertex(i, j), 0) == crowd.position(clip.frames[i], j).x());
      CHECK(clip.positions(clip.vertex(i, j), 1) == crowd.position(clip.frames[i], j).y());
    }
  }
  CHECK(clip.sample_of_frame(13) == 4);
  CHECK(clip.sample_of_frame(14) == -1);
  CHECK(clip.agent_of_id(103) == 3);
}

TEST_CASE("agents absent somewhere in the clip are left out, or an error when asked for") {
  CrowdMotion crowd = test::marching_grid(2, 2, 20);
  crowd.position(7, 1).setConstant(absent);   // agent id 101 leaves at frame 7
  crowd.position(12, 2).setConstant(absent);  // agent id 102 leaves at frame 12
  ClipOptions options;
  options.last_frame = 10;
  const Clip clip = make_clip(crowd, options);
  CHECK(clip.ids == std::vector<std::int64_t>{100, 102, 103});
  CHECK(clip.left_out == std::vector<std::int64_t>{101});

  options.agents = {100, 101};
  CHECK_THROWS_WITH(make_clip(crowd, options), Contains("agent 101 is absent at frames 7"));
  options.agents = {100, 999};
  CHECK_THROWS_WITH(make_clip(crowd, options), Contains("no agent with id 999"));
}

TEST_CASE("bad clip options are configuration errors naming the value") {
  const CrowdMotion crowd = test::marching_grid(2, 2, 10);
  ClipOptions o;
  o.first_frame = 10;
  CHECK_THROWS_AS(make_clip(crowd, o), ConfigError);
  CHECK_THROWS_WITH(make_clip(crowd, o), Contains("first_frame 10") && Contains("last frame 9"));
  o = {};
  o.last_frame = 12;
  CHECK_THROWS_WITH(make_clip(crowd, o), Contains("last_frame 12"));
  o = {};
  o.first_frame = 5;
  o.last_frame = 5;
  CHECK_THROWS_WITH(make_clip(crowd, o), Contains("at least two frames"));
  o = {};
  o.sample_step = 0;
  CHECK_THROWS_WITH(make_clip(crowd, o), Contains("sample_step"));
  o = {};
  o.last_frame = 6;
  const std::size_t outside[] = {8};
  CHECK_THROWS_WITH(make_clip(crowd, o, outside), Contains("frame 8 is outside the clip [0, 6]"));
}
