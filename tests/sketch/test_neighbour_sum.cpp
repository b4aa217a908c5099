// The agents' repulsion (solver/sketch/src/agent_repulsion.h) and its inner loop (neighbour_sum.h): the grid search
// gives the sum over every agent within reach, and the SSE2 and AVX2 loops give the same bits, including where a
// range's last group of four reaches past it (into another range's slots or the grid's padding).
#include "agent_repulsion.h"
#include "neighbour_grid.h"
#include "neighbour_sum.h"

#include <throng/core/random.h>

#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

using throng::Rng;
using namespace throng::sketch::detail;

namespace {

bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

// Σ over l ≠ self with 0 < d < r of (p − p_l)(r/d − 1), straight from the definition.
Eigen::Vector2d reference(const std::vector<double>& x, const std::vector<double>& y, std::size_t self, double r) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  const Eigen::Vector2d p(x[self], y[self]);
  for (std::size_t l = 0; l < x.size(); ++l) {
    const Eigen::Vector2d offset = p - Eigen::Vector2d(x[l], y[l]);
    const double d = offset.norm();
    if (l != self && d > 0 && d < r) sum += offset * (r / d - 1.0);
  }
  return sum;
}

// The neighbour sum of the candidates in the ranges, straight from the definition.
NeighbourSum reference(const NeighbourQuery& q) {
  NeighbourSum sum{0, 0, 0};
  for (std::size_t range = 0; range < q.ranges; ++range) {
    for (std::uint32_t l = q.from[range]; l < q.to[range]; ++l) {
      const double dx = q.px - q.x[l], dy = q.py - q.y[l];
      const double d = std::sqrt(dx * dx + dy * dy);
      if (d == 0) ++sum.at_p;
      if (d > 0 && d < q.r) {
        sum.x += dx * (q.r / d - 1.0);
        sum.y += dy * (q.r / d - 1.0);
      }
    }
  }
  return sum;
}

}  // namespace

TEST_CASE("the grid search's repulsion is the sum over every agent within reach") {
  Rng rng(31);
  for (const std::size_t n : {1, 2, 7, 60, 700}) {
    // A crowd at about 1 per m², a few agents sharing a place; reach 0.6–1.4 m.
    const double side = std::sqrt(static_cast<double>(n)) + 1.0;
    std::vector<double> x(n), y(n);
    for (std::size_t i = 0; i < n; ++i) {
      x[i] = rng.uniform(0, side);
      y[i] = rng.uniform(0, side);
      if (i > 0 && rng.uniform() < 0.05) {
        x[i] = x[i - 1];
        y[i] = y[i - 1];
      }
    }
    const double r = rng.uniform(0.6, 1.4);
    Eigen::AlignedBox2d bounds;
    for (std::size_t i = 0; i < n; ++i) bounds.extend(Eigen::Vector2d(x[i], y[i]));
    NeighbourGrid grid;
    grid.build(x, y, std::vector<std::uint8_t>(n, 1), n, bounds, r);
    for (std::size_t slot = 0; slot < n; ++slot) {
      const std::uint32_t j = grid.order()[slot];
      const Eigen::Vector2d got = agent_repulsion(grid, slot, Eigen::Vector2d(x[j], y[j]), r);
      const Eigen::Vector2d expected = reference(x, y, j, r);
      std::size_t shared = 0;
      for (std::size_t l = 0; l < n; ++l) shared += l != j && x[l] == x[j] && y[l] == y[j];
      INFO("n " << n << " agent " << j << " sharing its place with " << shared);
      REQUIRE(std::isfinite(got.x()));
      REQUIRE(std::isfinite(got.y()));
      if (shared == 0) {
        CHECK((got - expected).norm() <= 1e-12 * (1.0 + expected.norm()));
      } else {
        // Agents at the same place push each other r apart, in a direction of the pair's own: the terms of the
        // others match, and the same-place terms add up to at most r each.
        CHECK((got - expected).norm() <= static_cast<double>(shared) * r + 1e-12 * (1.0 + expected.norm()));
        CHECK((got - expected).norm() > 0);
      }
    }
  }
}

TEST_CASE("the SSE2 and AVX2 neighbour loops give the same bits, past every range's end included") {
  Rng rng(7);
  // Sorted positions with the grid's padding (zeros) after the last; candidates near the query point, some exactly
  // at it, and slots just past a range within reach (another range's agents, which must not count twice).
  constexpr std::size_t slots = 40;
  std::vector<double> x(slots + NeighbourGrid::padding, 0.0), y(slots + NeighbourGrid::padding, 0.0);
  std::size_t avx2_compared = 0;
  for (int trial = 0; trial < 5000; ++trial) {
    const double px = rng.uniform(-3, 3), py = rng.uniform(-3, 3), r = rng.uniform(0.3, 2.0);
    for (std::size_t l = 0; l < slots; ++l) {
      x[l] = px + rng.uniform(-1.5 * r, 1.5 * r);
      y[l] = py + rng.uniform(-1.5 * r, 1.5 * r);
      if (rng.uniform() < 0.05) {
        x[l] = px;
        y[l] = py;
      }
    }
    NeighbourQuery q{x.data(), y.data(), {}, {}, 0, px, py, r};
    q.ranges = rng.below(4);
    std::uint32_t next = static_cast<std::uint32_t>(rng.below(3));
    for (std::size_t range = 0; range < q.ranges; ++range) {
      // Lengths 0–13 (0 to 4 groups of four), the last range possibly ending at the last slot (padding after it).
      const auto length = static_cast<std::uint32_t>(rng.below(14));
      q.from[range] = std::min<std::uint32_t>(next, slots);
      q.to[range] = std::min<std::uint32_t>(q.from[range] + length, slots);
      next = q.to[range] + 1 + static_cast<std::uint32_t>(rng.below(3));
    }
    if (rng.uniform() < 0.2 && q.ranges > 0) {
      q.to[q.ranges - 1] = slots;
      q.from[q.ranges - 1] = std::min(q.from[q.ranges - 1], q.to[q.ranges - 1]);
    }
    const NeighbourSum sse2 = neighbour_sum_sse2(q);
    const NeighbourSum expected = reference(q);
    INFO("trial " << trial);
    REQUIRE(std::isfinite(sse2.x));
    REQUIRE(std::isfinite(sse2.y));
    CHECK(sse2.at_p == expected.at_p);
    CHECK(std::abs(sse2.x - expected.x) <= 1e-12 * (1.0 + std::abs(expected.x)));
    CHECK(std::abs(sse2.y - expected.y) <= 1e-12 * (1.0 + std::abs(expected.y)));
    if (has_avx2()) {
      const NeighbourSum avx2 = neighbour_sum_avx2(q);
      CHECK(same_bits(avx2.x, sse2.x));
      CHECK(same_bits(avx2.y, sse2.y));
      CHECK(avx2.at_p == sse2.at_p);
      ++avx2_compared;
    }
  }
  // This processor's AVX2 loop ran (where it has none, only the SSE2 loop can be checked here).
  if (!has_avx2()) WARN("no AVX2 on this processor: the AVX2 loop was not compared");
  CHECK((avx2_compared == 5000 || !has_avx2()));
}
