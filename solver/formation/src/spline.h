// Keyframe timing and the Catmull-Rom weights of Eq. 5.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace throng::formation {

/// Weights of the four control keyframes n−1, n, n+1, n+2 at parameter t ∈ [0, 1] of the interval n → n+1, with
/// tension τ (Eq. 5): c−1 = τ(−t + 2t² − t³), c0 = 1 − 3t² + 2t³ + τ(t² − t³), c1 = 3t² − 2t³ + τ(t − 2t² + t³),
/// c2 = τ(−t² + t³). They sum to 1; t = 0 gives (0, 1, 0, 0) and t = 1 gives (0, 0, 1, 0).
struct SplineWeights {
  std::array<double, 4> c{0, 1, 0, 0};
};
[[nodiscard]] SplineWeights catmull_rom_weights(double t, double tension) noexcept;

/// The keyframes n−1, n, n+1, n+2 controlling interval `segment` (= n), with the endpoints duplicated:
/// keys[0] = max(n−1, 0), keys[3] = min(n+2, K−1). A sharp keyframe (`sharp[k]`, empty: none) is duplicated too,
/// the paper's "when p_n (or p_{n+1}) is ... a point at which the curve is set to be nonsmooth, p_n (or p_{n+1})
/// is duplicated" (§4.1): keys[0] = n when keyframe n is sharp, keys[3] = n+1 when keyframe n+1 is. The spline
/// then leaves and reaches the keyframe along the chord of its own interval only (tangent τ(p_{n+1} − p_n)), so
/// the path turns there with the angle between the two chords, and the intervals beyond its neighbours do not
/// change.
struct ControlKeys {
  std::array<int, 4> keys{0, 0, 0, 0};
};
[[nodiscard]] ControlKeys control_keys(int segment, int keyframe_count, const std::vector<bool>& sharp = {}) noexcept;

/// Output frames: every keyframe time is a frame; interval k → k+1 gets max(1, round((t_{k+1} − t_k)·rate))
/// equal steps.
///   times           #frames (seconds)
///   segment         #frames: the interval a frame belongs to (the last frame belongs to the last interval)
///   local           #frames: its parameter t ∈ [0, 1] within that interval
///   keyframe_frame  #keyframes: the frame of each keyframe
struct Timeline {
  std::vector<double> times;
  std::vector<int> segment;
  std::vector<double> local;
  std::vector<std::size_t> keyframe_frame;

  [[nodiscard]] std::size_t frame_count() const noexcept { return times.size(); }
};
[[nodiscard]] Timeline make_timeline(const std::vector<double>& keyframe_times, double frame_rate_hz);

}  // namespace throng::formation
