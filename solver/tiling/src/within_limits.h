// The tiler's test of the per-frame deformation limits (options.h: DeformationLimits). The checker measures
// the same quantities with its own code (check.cpp).
#pragma once

#include <throng/tiling/options.h>
#include <throng/tiling/patch.h>
#include <throng/tiling/tiling.h>

namespace throng::tiling {

/// True when `path` (a deformation of `fragment`) keeps times strictly increasing, every stretch, bend and
/// time shift within `limits` and every segment's speed at most `max_speed_m_s` (speed_limit(), patch.h).
[[nodiscard]] bool within_limits(const Fragment& fragment, const Path& path, const DeformationLimits& limits,
                                 double max_speed_m_s) noexcept;

}  // namespace throng::tiling
