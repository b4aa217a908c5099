// The independent checker: proves a tiling perfect or lists what is wrong with it.
//
// It shares nothing with the tiler's bookkeeping (no index, no dangling counts, no stored statuses): it
// recomputes everything from the library, the instances (type, transform, deformed paths), the connections
// and the environment, by brute force over fragment pairs and images, with its own geometry:
//   dangling        every character end is connected exactly once or needs no partner (tiling.h, the region rule)
//   connection      a connection joins an exit to an entry of character fragments with the same pose class;
//                   Eq. 1 (same position), Eq. 2 (same tangent), Eq. 3 (same time), headings within the match
//                   angle; images only on periodic axes
//   seam            the same, for connections across a periodic boundary (image ≠ 0)
//   overlap         no two capsules (characters and props) closer than the sum of their radii at any time —
//                   exact on the linearly interpolated paths, over every periodic image — except the two
//                   fragments a connection joins and, within one instance, the pairs its patch itself brings
//                   into contact (patch.h contact_pairs, recomputed here)
//   obstacle        no capsule closer to an obstacle than its radius at the sampled points
//   deformation     per-frame stretch, bend and time-shift limits against the undeformed patch, and the speed
//                   limit (speed_ratio × the library's fastest segment) (options.h);
//                   times strictly increasing
//   interpersonal   the patch's interpersonal constraints still hold (relative position in the instance frame,
//                   time difference)
//   keyframe        keyframed instances are undeformed (their paths are the transformed patch)
// Malformed data (a type index out of range, a path whose length differs from its fragment's, a connection
// naming a missing fragment) is an InputError: there is nothing meaningful to check.
#pragma once

#include <throng/tiling/options.h>
#include <throng/tiling/patch.h>
#include <throng/tiling/tiling.h>

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace throng::tiling {

enum class FailureKind { dangling, connection, seam, overlap, obstacle, deformation, interpersonal, keyframe };

/// "dangling", "connection", ...
[[nodiscard]] const char* to_string(FailureKind kind) noexcept;

struct Failure {
  FailureKind kind = FailureKind::dangling;
  std::string message;  ///< names the instance(s), fragment, sample, the value and the limit
};

/// What the checker tolerates beyond the tiler's own tests (rounding only) and what it checks against.
struct CheckOptions {
  DeformationLimits limits;
  MatchThresholds match;           ///< the angle bounds the heading difference at a connection
  double obstacle_step_m = 0.1;
  double obstacle_step_s = 0.05;
  double distance_tolerance_m = 1e-6;  ///< overlaps, obstacles, Eq. 1–2 and interpersonal positions
  double time_tolerance_s = 1e-6;      ///< Eq. 3 and interpersonal times (the tiler accepts 1e-7 residuals)
  double limit_tolerance = 1e-9;       ///< relative slack on the deformation limits
};

inline constexpr std::size_t failure_kind_count = 8;

struct CheckReport {
  std::vector<Failure> failures;  ///< in the order found, at most the `max_failures` given to check_tiling
  std::array<std::size_t, failure_kind_count> totals{};  ///< every failure by kind, listed or not
  std::size_t instances = 0;
  std::size_t connections = 0;
  std::size_t character_ends = 0;
  std::size_t pairs_tested = 0;  ///< fragment pairs (per image) whose closest approach was computed
  [[nodiscard]] std::size_t total() const noexcept;
  [[nodiscard]] bool perfect() const noexcept { return total() == 0; }
  [[nodiscard]] std::size_t count(FailureKind kind) const noexcept { return totals[static_cast<std::size_t>(kind)]; }
};

/// Checks `tiling` (see the file comment). Throws InputError for malformed data; never stops at the first
/// failure: every failure is counted in `totals`, the first `max_failures` are listed.
[[nodiscard]] CheckReport check_tiling(const PatchLibrary& library, const Tiling& tiling, const Environment& environment,
                                       const CheckOptions& options, std::size_t max_failures = 1000);

}  // namespace throng::tiling
