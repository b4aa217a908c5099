#include <throng/core/parallel.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <vector>

TEST_CASE("parallel_for covers every index exactly once") {
  throng::ThreadLimit limit(2);
  std::vector<int> hits(10007, 0);
  throng::parallel_for(hits.size(), 16, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) ++hits[i];
  });
  for (int h : hits) REQUIRE(h == 1);
}

TEST_CASE("deterministic_sum gives the same bits for 1 and 2 threads") {
  auto term = [](std::size_t i) { return std::sin(static_cast<double>(i)) * 1e-3 + 1.0 / (1.0 + i); };
  double one, two;
  {
    throng::ThreadLimit limit(1);
    one = throng::deterministic_sum(100000, 97, term);
  }
  {
    throng::ThreadLimit limit(2);
    two = throng::deterministic_sum(100000, 97, term);
  }
  CHECK(std::memcmp(&one, &two, sizeof(double)) == 0);
}
