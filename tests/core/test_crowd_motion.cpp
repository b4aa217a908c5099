#include <throng/core/crowd_motion.h>
#include <throng/core/errors.h>

#include <catch2/catch.hpp>

using throng::CrowdMotion;

TEST_CASE("with_shape gives absent agents, ids 0..N-1 and the requested radius") {
  const auto m = CrowdMotion::with_shape(4, 3, 0.3);
  CHECK(m.frame_count() == 4);
  CHECK(m.agent_count() == 3);
  CHECK(m.positions.size() == 4 * 3 * 3);
  for (std::size_t t = 0; t < 4; ++t) {
    for (std::size_t n = 0; n < 3; ++n) CHECK_FALSE(m.present(t, n));
  }
  CHECK(m.ids == std::vector<std::int64_t>{0, 1, 2});
  CHECK(m.radii == std::vector<double>{0.3, 0.3, 0.3});
  CHECK_NOTHROW(m.validate());
}

TEST_CASE("position and frame views address the T by N by 3 layout") {
  auto m = CrowdMotion::with_shape(2, 3);
  m.position(1, 2) = Eigen::Vector3d(7, 8, 9);
  CHECK(m.positions[(1 * 3 + 2) * 3 + 0] == 7);
  CHECK(m.positions[(1 * 3 + 2) * 3 + 2] == 9);
  CHECK(m.frame(1)(2, 1) == 8);
  CHECK(m.present(1, 2));
  CHECK_FALSE(m.present(0, 2));
}

TEST_CASE("presence_span encloses the frames where an agent is present") {
  auto m = CrowdMotion::with_shape(6, 2);
  m.position(2, 0).setZero();
  m.position(4, 0).setZero();
  CHECK(m.presence_span(0) == std::pair<std::size_t, std::size_t>{2, 5});
  CHECK(m.presence_span(1) == std::pair<std::size_t, std::size_t>{0, 0});
}

TEST_CASE("validate rejects each broken invariant with a message naming it") {
  auto good = CrowdMotion::with_shape(3, 2);
  good.position(0, 0).setZero();

  SECTION("times not increasing") {
    auto m = good;
    m.times[2] = m.times[1];
    CHECK_THROWS_WITH(m.validate("x"), Catch::Contains("not strictly increasing at frame 2"));
  }
  SECTION("partly NaN position") {
    auto m = good;
    m.position(1, 1) = Eigen::Vector3d(1, std::nan(""), 0);
    CHECK_THROWS_AS(m.validate(), throng::InputError);
  }
  SECTION("wrong position count") {
    auto m = good;
    m.positions.pop_back();
    CHECK_THROWS_WITH(m.validate(), Catch::Contains("expected frames × agents × 3"));
  }
  SECTION("duplicate id") {
    auto m = good;
    m.ids[1] = m.ids[0];
    CHECK_THROWS_WITH(m.validate(), Catch::Contains("is used by agents 0 and 1"));
  }
  SECTION("negative radius") {
    auto m = good;
    m.radii[0] = -1;
    CHECK_THROWS_WITH(m.validate(), Catch::Contains("radius"));
  }
}
