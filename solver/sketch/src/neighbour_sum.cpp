#include "neighbour_sum.h"

#include <cmath>
#include <cstring>
#include <limits>

namespace throng::sketch::detail {
namespace {

using Pair = double __attribute__((vector_size(16)));
using PairMask = std::int64_t __attribute__((vector_size(16)));
using Quad = double __attribute__((vector_size(32)));
using QuadMask = std::int64_t __attribute__((vector_size(32)));

constexpr double far = std::numeric_limits<double>::infinity();
// Added to a group's squared distances: [the group's lanes inside the range, 0–4] puts the others out of reach. A
// sum, not a mask: GCC turns masks it cannot see as comparisons into a branch on each lane.
alignas(32) constexpr double past_range[5][4] = {
    {far, far, far, far}, {0, far, far, far}, {0, 0, far, far}, {0, 0, 0, far}, {0, 0, 0, 0}};

std::size_t inside(std::uint32_t l, std::uint32_t to) noexcept { return to - l >= 4 ? 4 : to - l; }

// Two lanes of a group: their terms added to sum_x, sum_y and their squared distances of zero counted.
inline void add_pair(const double* x, const double* y, const double* past, Pair px, Pair py, Pair r, Pair r2,
                     Pair& sum_x, Pair& sum_y, int& at_p) noexcept {
  const Pair zero = {0, 0}, one = {1, 1};
  Pair qx, qy, extra;
  std::memcpy(&qx, x, sizeof qx);
  std::memcpy(&qy, y, sizeof qy);
  std::memcpy(&extra, past, sizeof extra);
  const Pair dx = px - qx, dy = py - qy;
  const Pair d2 = (dx * dx + dy * dy) + extra;
  const PairMask near = (d2 < r2) & (d2 > zero);
  const Pair safe = near ? d2 : r2;
  const Pair root = {std::sqrt(safe[0]), std::sqrt(safe[1])};
  const Pair c = near ? r / root - one : zero;
  sum_x += c * dx;
  sum_y += c * dy;
  const PairMask zeros = d2 == zero;  // −1 in a lane at p
  at_p -= static_cast<int>(zeros[0] + zeros[1]);
}

}  // namespace

NeighbourSum neighbour_sum_sse2(const NeighbourQuery& q) noexcept {
  const Pair px = {q.px, q.px}, py = {q.py, q.py}, r = {q.r, q.r}, r2 = {q.r * q.r, q.r * q.r};
  Pair low_x = {0, 0}, low_y = {0, 0}, high_x = {0, 0}, high_y = {0, 0};  // lanes 0–1 and 2–3
  int at_p = 0;
  for (std::size_t range = 0; range < q.ranges; ++range) {
    const std::uint32_t to = q.to[range];
    for (std::uint32_t l = q.from[range]; l < to; l += 4) {
      const double* past = past_range[inside(l, to)];
      add_pair(q.x + l, q.y + l, past, px, py, r, r2, low_x, low_y, at_p);
      add_pair(q.x + l + 2, q.y + l + 2, past + 2, px, py, r, r2, high_x, high_y, at_p);
    }
  }
  return {(low_x[0] + low_x[1]) + (high_x[0] + high_x[1]), (low_y[0] + low_y[1]) + (high_y[0] + high_y[1]), at_p};
}

#if defined(__x86_64__)
// Compiled for AVX2 whatever the build's target, and called only where the processor has it (has_avx2). Nothing
// here is a function other code could share (an inline or template instance compiled for AVX2 would be).
__attribute__((target("avx2,popcnt"))) NeighbourSum neighbour_sum_avx2(const NeighbourQuery& q) noexcept {
  const Quad px = {q.px, q.px, q.px, q.px}, py = {q.py, q.py, q.py, q.py}, r = {q.r, q.r, q.r, q.r};
  const double r_squared = q.r * q.r;
  const Quad r2 = {r_squared, r_squared, r_squared, r_squared}, zero = {0, 0, 0, 0}, one = {1, 1, 1, 1};
  Quad sum_x = zero, sum_y = zero;
  int at_p = 0;
  for (std::size_t range = 0; range < q.ranges; ++range) {
    const std::uint32_t to = q.to[range];
    for (std::uint32_t l = q.from[range]; l < to; l += 4) {
      Quad qx, qy, extra;
      std::memcpy(&qx, q.x + l, sizeof qx);
      std::memcpy(&qy, q.y + l, sizeof qy);
      std::memcpy(&extra, past_range[inside(l, to)], sizeof extra);
      const Quad dx = px - qx, dy = py - qy;
      const Quad d2 = (dx * dx + dy * dy) + extra;
      const QuadMask near = (d2 < r2) & (d2 > zero);
      const Quad safe = near ? d2 : r2;
      const Quad root = __builtin_ia32_sqrtpd256(safe);
      const Quad c = near ? r / root - one : zero;
      sum_x += c * dx;
      sum_y += c * dy;
      at_p += __builtin_popcount(static_cast<unsigned>(__builtin_ia32_movmskpd256(reinterpret_cast<Quad>(d2 == zero))));
    }
  }
  return {(sum_x[0] + sum_x[1]) + (sum_x[2] + sum_x[3]), (sum_y[0] + sum_y[1]) + (sum_y[2] + sum_y[3]), at_p};
}

bool has_avx2() noexcept {
  __builtin_cpu_init();  // a static initialiser calls this (agent_repulsion.cpp), maybe before libgcc's own has run
  static const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("popcnt");
  return avx2;
}
#else
NeighbourSum neighbour_sum_avx2(const NeighbourQuery& q) noexcept { return neighbour_sum_sse2(q); }
bool has_avx2() noexcept { return false; }
#endif

}  // namespace throng::sketch::detail
