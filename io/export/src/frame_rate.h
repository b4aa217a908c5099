// Frame rates for formats that count frames (USD time codes, PedPy's fps).
#pragma once

#include <optional>
#include <vector>

namespace throng::detail {

/// Frames per second when the frames are evenly spaced: every time within 1e-6 steps of t0 + k·Δ, Δ the mean
/// step (recorded crowds are frame / fps up to rounding; a time-warped crowd is not). nullopt for fewer than two
/// frames or uneven spacing.
[[nodiscard]] std::optional<double> uniform_frame_rate(const std::vector<double>& times);

}  // namespace throng::detail
