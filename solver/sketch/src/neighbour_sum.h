// The inner loop of the agents' repulsion (agent_repulsion.h): Σ (p − p_l)(r/d − 1) over the candidates l of up to
// three slot ranges of the neighbour grid, two implementations that give the same bits.
#pragma once

#include <cstddef>
#include <cstdint>

namespace throng::sketch::detail {

/// The candidates: slot ranges [from[i], to[i]) of the grid's sorted positions x, y (read up to 3 slots past a
/// range: NeighbourGrid::padding), and the agent's place (px, py) and reach r.
struct NeighbourQuery {
  const double* x;
  const double* y;
  std::uint32_t from[3], to[3];
  std::size_t ranges;
  double px, py, r;
};

/// The sum of the terms of the candidates closer than r and not at p, and how many candidates are exactly at p.
struct NeighbourSum {
  double x, y;
  int at_p;
};

/// The order of the sum, the same in both: candidates in groups of four from each range's first slot (the group's
/// lanes past the range masked out), lane m of every group into sum m (m = 0..3, ranges in turn), then
/// (sum 0 + sum 1) + (sum 2 + sum 3). Each term is r/√d² − 1 times the offset, IEEE operations without fused
/// multiply-adds (the file is compiled with -ffp-contract=off), so both give the same bits.
[[nodiscard]] NeighbourSum neighbour_sum_sse2(const NeighbourQuery& query) noexcept;
/// The same with AVX2 (four lanes at once); call only where the processor has AVX2 (has_avx2()).
[[nodiscard]] NeighbourSum neighbour_sum_avx2(const NeighbourQuery& query) noexcept;
/// Whether this processor runs AVX2 code.
[[nodiscard]] bool has_avx2() noexcept;

}  // namespace throng::sketch::detail
