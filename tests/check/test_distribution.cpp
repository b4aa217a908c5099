// The checker's distributions (solver/check/src/samples.h, private): the nearest-rank percentiles are the values a
// full sort puts at ranks ⌈p·n⌉ − 1, ties and repeated values included, and the maximum names the first sample
// that holds it, across merged collections too.
#include "samples.h"

#include <throng/core/random.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

using throng::Rng;
using throng::check::detail::distribution;
using throng::check::detail::Samples;

TEST_CASE("distribution's percentiles are the sorted samples at the nearest ranks") {
  Rng rng(17);
  std::vector<std::int64_t> ids(50);
  for (std::size_t a = 0; a < ids.size(); ++a) ids[a] = 1000 + static_cast<std::int64_t>(a);
  for (const std::size_t n : {1, 2, 3, 19, 20, 21, 99, 100, 101, 1000, 4567}) {
    for (const bool coarse : {false, true}) {  // coarse: few distinct values, many ties
      // Two halves merged as measure() merges agents, the samples' agents and times kept here to find the first
      // largest by a scan.
      Samples s, second;
      std::vector<std::size_t> agents;
      std::vector<double> values, times;
      for (std::size_t i = 0; i < n; ++i) {
        const double v = coarse ? std::floor(rng.uniform(0, 5)) : rng.uniform(-3, 7);
        agents.push_back(rng.below(ids.size()));
        times.push_back(0.1 * static_cast<double>(i));
        values.push_back(v);
        (i < n / 2 ? s : second).add(v, agents.back(), times.back());
      }
      s.append(second);
      REQUIRE(s.values == values);
      std::vector<double> sorted = values;
      std::sort(sorted.begin(), sorted.end());
      const auto rank = [&](double p) { return std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(p * static_cast<double>(n) - 1e-9))) - 1; };
      const std::size_t first_max = static_cast<std::size_t>(std::max_element(values.begin(), values.end()) - values.begin());
      const auto d = distribution(s, ids);
      INFO("n " << n << (coarse ? ", coarse" : ""));
      CHECK(d.samples == n);
      CHECK(d.p50 == sorted[rank(0.50)]);
      CHECK(d.p95 == sorted[rank(0.95)]);
      CHECK(d.p99 == sorted[rank(0.99)]);
      CHECK(d.max == sorted.back());
      CHECK(d.max_agent == ids[agents[first_max]]);
      CHECK(d.max_time == times[first_max]);
    }
  }
}
