// Catch2 check shared by the detection tests: two contact sets are the same contacts, in the same order, with
// the same bits (pair moments, distances and offsets; obstacle depths).
#pragma once

#include <throng/collide/broad_phase.h>

#include <catch2/catch.hpp>

namespace throng::collide::check {

inline void require_same_contacts(const Contacts& x, const Contacts& y) {
  REQUIRE(x.pairs.size() == y.pairs.size());
  for (std::size_t k = 0; k < x.pairs.size(); ++k) {
    const PairContact &p = x.pairs[k], &q = y.pairs[k];
    INFO("pair contact " << k << ": agents " << p.a << ", " << p.b << " interval " << p.interval);
    REQUIRE(p.a == q.a);
    REQUIRE(p.b == q.b);
    REQUIRE(p.interval == q.interval);
    REQUIRE(p.s == q.s);
    REQUIRE(p.distance == q.distance);
    REQUIRE(p.clearance == q.clearance);
    REQUIRE(p.offset == q.offset);
  }
  REQUIRE(x.obstacles.size() == y.obstacles.size());
  for (std::size_t k = 0; k < x.obstacles.size(); ++k) {
    const ObstacleContact &p = x.obstacles[k], &q = y.obstacles[k];
    INFO("obstacle contact " << k << ": agent " << p.agent << " obstacle " << p.obstacle << " interval " << p.interval);
    REQUIRE(p.agent == q.agent);
    REQUIRE(p.obstacle == q.obstacle);
    REQUIRE(p.interval == q.interval);
    REQUIRE(p.s == q.s);
    REQUIRE(p.signed_distance == q.signed_distance);
    REQUIRE(p.clearance == q.clearance);
  }
}

}  // namespace throng::collide::check
