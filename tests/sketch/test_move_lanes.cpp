// The move and facing lanes of the simulation step (solver/sketch/src/move_lanes.h): four agents per vector
// operation give, lane by lane, the bits of the scalar rules of sketch.h (written out here one agent at a time, in
// the order of operations the simulation used before the lanes; this file is compiled without fused
// multiply-adds), the SSE2 and AVX2 builds give the same bits, and the rules' bounds hold (acceleration, largest
// turn, unit facing). The obstacle rules run between the steps in simulation.cpp (brake on the wanted velocity,
// keep_clear on the new place, both skipping `stay`); the shipped scenes with obstacles check them end to end.
#include "move_lanes.h"
#include "neighbour_sum.h"

#include <throng/core/random.h>
#include <throng/sketch/sketch.h>

#include <Eigen/Core>
#include <catch2/catch.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>

using throng::Rng;
using namespace throng::sketch;
using namespace throng::sketch::detail;

namespace {

bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

MoveConstants constants(double dt, double filter_s, double max_acceleration) {
  return {dt,
          filter_s > 0,
          filter_s > 0 ? -std::expm1(-dt / filter_s) : 1.0,
          max_acceleration * dt,
          -std::expm1(-dt / facing_filter_s),
          std::cos(facing_turn_rate_rad_s * dt),
          std::sin(facing_turn_rate_rad_s * dt),
          facing_standing_speed_m_s};
}

// One agent's move, the rules of sketch.h one agent at a time (Eigen): the new place and the step's velocity.
struct Moved {
  Eigen::Vector2d q, v;
};
Moved move_one(const MoveConstants& c, MoveKind kind, Eigen::Vector2d force, double speed, Eigen::Vector2d p,
               Eigen::Vector2d u) {
  if (kind == MoveKind::stay) return {p, Eigen::Vector2d::Zero()};
  const double f = force.norm();
  Eigen::Vector2d q = p;
  const Eigen::Vector2d room =
      0.5 * f > 0 ? Eigen::Vector2d((std::min(0.5 * f, speed * c.dt) / f) * force) : Eigen::Vector2d::Zero();
  if (!c.filtered) {
    if (kind == MoveKind::along_force) {
      if (f > 0) q = p + (speed * c.dt / f) * force;
    } else {
      q = p + room;
    }
  } else {
    const Eigen::Vector2d wanted =
        kind == MoveKind::along_force ? (f > 0 ? Eigen::Vector2d((speed / f) * force) : Eigen::Vector2d::Zero())
                                      : Eigen::Vector2d(room / c.dt);
    Eigen::Vector2d change = c.relax * (wanted - u);
    if (c.largest_change > 0) change = change * std::min(1.0, c.largest_change / change.norm());
    q = p + c.dt * (u + change);
  }
  return {q, (q - p) / c.dt};
}

// One agent's facing after a step with velocity v (sketch.h "Facing and actions").
Eigen::Vector2d face_one(const MoveConstants& c, const Eigen::Vector2d& h, const Eigen::Vector2d& v) {
  const double speed2 = v.squaredNorm();
  if (speed2 < facing_standing_speed_m_s * facing_standing_speed_m_s) return h;
  const double along = h.dot(v), across = h.x() * v.y() - h.y() * v.x();
  if (along > 0 && across * across <= 1e-6 * speed2) return h;
  const Eigen::Vector2d g = (h + c.follow * (v / std::sqrt(speed2) - h)).normalized();
  if (h.dot(g) >= c.cos_turn) return g;
  const double side = h.x() * g.y() - h.y() * g.x() >= 0 ? 1.0 : -1.0;
  return Eigen::Vector2d(h.x() * c.cos_turn - side * h.y() * c.sin_turn, side * h.x() * c.sin_turn + h.y() * c.cos_turn)
      .normalized();
}

// A block of agents of every kind: forces from zero to large, walking velocities from rest to a sprint in any
// direction, facings along, across and against the velocity.
void fill(Rng& rng, MoveBlock& b, std::size_t count) {
  for (std::size_t i = 0; i < count; ++i) {
    b.kind[i] = static_cast<std::int64_t>(rng.below(3));
    const double angle = rng.uniform(0, 2 * std::numbers::pi);
    // Zero, too small to square (|F|² underflows to 0: no direction), and from 1e-6 to 10.
    const double draw = rng.uniform();
    const double magnitude = draw < 0.1 ? 0.0 : draw < 0.15 ? 1e-170 : std::pow(10.0, rng.uniform(-6, 1));
    b.fx[i] = magnitude * std::cos(angle);
    b.fy[i] = magnitude * std::sin(angle);
    b.speed[i] = rng.uniform(0.5, 2.0);
    b.px[i] = rng.uniform(-50, 50);
    b.py[i] = rng.uniform(-50, 50);
    const double u_angle = rng.uniform() < 0.5 ? angle : rng.uniform(0, 2 * std::numbers::pi);
    const double u_speed = rng.uniform() < 0.1 ? 0.0 : rng.uniform(0, 3);
    b.ux[i] = u_speed * std::cos(u_angle);
    b.uy[i] = u_speed * std::sin(u_angle);
    const double h_angle = rng.uniform() < 0.3 ? u_angle : rng.uniform(0, 2 * std::numbers::pi);
    b.hx[i] = std::cos(h_angle);
    b.hy[i] = std::sin(h_angle);
    b.fastest[i] = rng.uniform(0, 4);
  }
}

void run(const MoveLanes& lanes, const MoveConstants& c, MoveBlock& b, std::size_t count) {
  lanes.wanted_velocities(c, b, count);
  lanes.moved_places(c, b, count);
  lanes.velocities_and_facings(c, b, count);
}

}  // namespace

TEST_CASE("the move lanes give each agent's scalar rule, the same bits in SSE2 and AVX2, within the rules' bounds") {
  const MoveLanes sse2_lanes{sse2::wanted_velocities, sse2::moved_places, sse2::velocities_and_facings};
  const MoveLanes avx2_lanes{avx2::wanted_velocities, avx2::moved_places, avx2::velocities_and_facings};
  Rng rng(11);
  std::size_t turns_limited = 0, kept = 0, bounded = 0, avx2_compared = 0;
  for (int trial = 0; trial < 600; ++trial) {
    const double dt = rng.uniform() < 0.5 ? 0.04 : rng.uniform(0.01, 0.2);
    const double filter_s = rng.uniform() < 0.25 ? 0.0 : rng.uniform(0.1, 1.0);
    const double max_acceleration = rng.uniform() < 0.25 ? 0.0 : rng.uniform(0.5, 5.0);
    const MoveConstants c = constants(dt, filter_s, max_acceleration);
    const std::size_t count = 1 + rng.below(MoveBlock::size);
    MoveBlock sse2_block;
    fill(rng, sse2_block, MoveBlock::size);  // lanes past count hold other agents, as in a reused block
    const MoveBlock input = sse2_block;
    run(sse2_lanes, c, sse2_block, count);
    if (has_avx2()) {
      MoveBlock avx2_block = input;
      run(avx2_lanes, c, avx2_block, count);
      for (std::size_t i = 0; i < count; ++i) {
        INFO("trial " << trial << " lane " << i);
        CHECK(same_bits(avx2_block.qx[i], sse2_block.qx[i]));
        CHECK(same_bits(avx2_block.qy[i], sse2_block.qy[i]));
        CHECK(same_bits(avx2_block.vx[i], sse2_block.vx[i]));
        CHECK(same_bits(avx2_block.vy[i], sse2_block.vy[i]));
        CHECK(same_bits(avx2_block.nx[i], sse2_block.nx[i]));
        CHECK(same_bits(avx2_block.ny[i], sse2_block.ny[i]));
        CHECK(same_bits(avx2_block.fastest[i], sse2_block.fastest[i]));
      }
      ++avx2_compared;
    }
    for (std::size_t i = 0; i < count; ++i) {
      INFO("trial " << trial << " lane " << i << " kind " << input.kind[i] << " filtered " << c.filtered);
      const auto kind = static_cast<MoveKind>(input.kind[i]);
      const Eigen::Vector2d p(input.px[i], input.py[i]), u(input.ux[i], input.uy[i]), h(input.hx[i], input.hy[i]);
      const Moved expected =
          move_one(c, kind, Eigen::Vector2d(input.fx[i], input.fy[i]), input.speed[i], p, u);
      const Eigen::Vector2d q(sse2_block.qx[i], sse2_block.qy[i]), v(sse2_block.vx[i], sse2_block.vy[i]);
      CHECK(same_bits(q.x(), expected.q.x()));
      CHECK(same_bits(q.y(), expected.q.y()));
      CHECK(same_bits(v.x(), expected.v.x()));
      CHECK(same_bits(v.y(), expected.v.y()));
      CHECK(sse2_block.fastest[i] == std::max(input.fastest[i], v.squaredNorm()));
      if (kind == MoveKind::stay) {
        CHECK(q == p);
        CHECK(v == Eigen::Vector2d::Zero());
      }
      // The acceleration bound: the walking velocity changes by at most max_acceleration Δt.
      if (c.filtered && c.largest_change > 0 && kind != MoveKind::stay) {
        CHECK((v - u).norm() <= c.largest_change * (1 + 1e-9) + 1e-9);
        bounded += (v - u).norm() >= 0.999 * c.largest_change;
      }
      const Eigen::Vector2d n(sse2_block.nx[i], sse2_block.ny[i]);
      const Eigen::Vector2d expected_n = face_one(c, h, v);
      CHECK(same_bits(n.x(), expected_n.x()));
      CHECK(same_bits(n.y(), expected_n.y()));
      if (n == h) {
        ++kept;
        CHECK(expected_n == h);  // a facing kept is kept exactly
      } else {
        CHECK(std::abs(n.norm() - 1) <= 1e-12);
        // At most the largest turn per step.
        CHECK(h.dot(n) >= c.cos_turn - 1e-12);
        turns_limited += h.dot(n) <= c.cos_turn + 1e-9;
      }
    }
  }
  // Every branch of the rules was taken.
  CHECK(turns_limited > 100);
  CHECK(kept > 100);
  CHECK(bounded > 100);
  if (has_avx2()) CHECK(avx2_compared == 600);
}
