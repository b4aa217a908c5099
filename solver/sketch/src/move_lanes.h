// The per-agent arithmetic of a simulation step after the forces (simulation.cpp passes 2 and 3): the move of
// Eq. 21–22 with the direction filter and acceleration bound, and the facing step of sketch.h "Facing and
// actions", four agents per vector operation over a block of agents stored as structure of arrays.
//
// Why lanes: per agent these are chains of square roots and divisions (a move has two of each, a facing two
// more); one agent at a time, each waits for the last, and the two passes took a quarter of the step
// (bench/sketch BM_Step, 10,000 agents). Every branch of the scalar rules is a select here, computed for all lanes.
//
// Bits: each lane does the IEEE operations of the scalar rule (sketch.h) in its order, without fused
// multiply-adds (the files are compiled with -ffp-contract=off); square roots and divisions are correctly rounded
// in SSE2 and AVX alike. So the SSE2 build (two halves per operation) and the AVX2 one give the same bits.
#pragma once

#include <cstddef>
#include <cstdint>

namespace throng::sketch::detail {

/// What pass 1 decided for an agent.
enum class MoveKind : std::int64_t {
  along_force = 0,  // walking: v_k Δt along the force
  make_room = 1,    // standing: half its overlap, at most v_k Δt
  stay = 2,         // removed, or about to be: does not move, velocity zero
};

/// One block of agents, lane i = the block's i-th agent. Entries past the block's count are computed on and
/// never read: zeros, or an earlier block's values (the block is reused), never uninitialised.
struct MoveBlock {
  static constexpr std::size_t size = 64;  // a multiple of 4
  // In (pass 1): the kind, the force F (walking) or overlap (standing), v_k, the place p, the walking velocity u
  // and the facing h at the step's start.
  alignas(32) std::int64_t kind[size] = {};
  alignas(32) double fx[size] = {}, fy[size] = {};
  alignas(32) double speed[size] = {};
  alignas(32) double px[size] = {}, py[size] = {};
  alignas(32) double ux[size] = {}, uy[size] = {};
  alignas(32) double hx[size] = {}, hy[size] = {};
  // Out: the walking velocity wanted (filtered; wanted_velocities), the new place (moved_places), the step's
  // velocity (q − p)/Δt and the new facing (velocities_and_facings); `fastest` is max-ed with |velocity|².
  alignas(32) double wx[size] = {}, wy[size] = {};
  alignas(32) double qx[size] = {}, qy[size] = {};
  alignas(32) double vx[size] = {}, vy[size] = {};
  alignas(32) double nx[size] = {}, ny[size] = {};
  alignas(32) double fastest[size] = {};
};

/// The step's constants.
struct MoveConstants {
  double dt;              // Δt (s)
  bool filtered;          // the direction filter is on
  double relax;           // 1 − exp(−Δt/τ) (filtered)
  double largest_change;  // max_acceleration Δt, 0 for no bound (filtered)
  double follow;          // 1 − exp(−Δt/τ_facing)
  double cos_turn, sin_turn;  // of the largest turn per step, facing_turn_rate_rad_s Δt
  double standing_speed;  // facing_standing_speed_m_s: slower, the facing is kept
};

/// The three steps, in this order, with the obstacle rules between them (simulation.cpp): each reads the block's
/// inputs and the outputs of the steps before, for lanes [0, count) rounded up to 4.
struct MoveLanes {
  /// Filtered: w = u + bounded(relax (target − u)), the target v_k F/|F| (walking, 0 for F = 0) or the room
  /// min(|F|/2, v_k Δt) F/|F| over Δt (standing); bounded scales a change longer than largest_change down to it.
  /// Unfiltered (the paper's rule): nothing.
  void (*wanted_velocities)(const MoveConstants&, MoveBlock&, std::size_t count) noexcept;
  /// q: filtered p + Δt w; unfiltered p + (v_k Δt/|F|) F (walking, p for F = 0) or p plus the room (standing);
  /// p for `stay`.
  void (*moved_places)(const MoveConstants&, MoveBlock&, std::size_t count) noexcept;
  /// v = (q − p)/Δt (0 for `stay`), fastest = max(fastest, |v|²), and the facing n after h with velocity v:
  /// h itself below standing_speed or within 1e-3 rad of v's direction; else h moved toward v̂ by
  /// `follow` of the difference and renormalised (|g| ≥ 1 − 2 follow > 0), turned by at most the largest turn (then
  /// exactly that far, toward the side it was going). Kept within 1e-3 rad (0.06°, invisible): agents walking
  /// straight on skip the square roots (a third of the step without it, bench/sketch BM_Step).
  void (*velocities_and_facings)(const MoveConstants&, MoveBlock&, std::size_t count) noexcept;
};

/// The lanes for this processor, chosen on the first call: AVX2 where it has it, SSE2 elsewhere (the same bits).
[[nodiscard]] const MoveLanes& move_lanes() noexcept;

namespace sse2 {
void wanted_velocities(const MoveConstants&, MoveBlock&, std::size_t count) noexcept;
void moved_places(const MoveConstants&, MoveBlock&, std::size_t count) noexcept;
void velocities_and_facings(const MoveConstants&, MoveBlock&, std::size_t count) noexcept;
}  // namespace sse2
namespace avx2 {
void wanted_velocities(const MoveConstants&, MoveBlock&, std::size_t count) noexcept;
void moved_places(const MoveConstants&, MoveBlock&, std::size_t count) noexcept;
void velocities_and_facings(const MoveConstants&, MoveBlock&, std::size_t count) noexcept;
}  // namespace avx2

}  // namespace throng::sketch::detail
