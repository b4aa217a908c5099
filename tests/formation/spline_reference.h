// The paper's Catmull-Rom weights (Eq. 5) and control keyframes, written out again for the tests, so that a
// test's expected positions do not come from the code under test.
#pragma once

#include <algorithm>
#include <array>
#include <vector>

namespace throng::test {

/// c−1, c0, c1, c2 at t with tension τ (Eq. 5).
inline std::array<double, 4> eq5_weights(double t, double tau) {
  return {tau * (-t + 2 * t * t - t * t * t), (1 - 3 * t * t + 2 * t * t * t) + tau * (t * t - t * t * t),
          (3 * t * t - 2 * t * t * t) + tau * (t - 2 * t * t + t * t * t), tau * (-t * t + t * t * t)};
}

/// Keyframes n−1, n, n+1, n+2 of interval n among `count`: endpoints and sharp keyframes duplicated (§4.1).
inline std::array<int, 4> eq5_keys(int n, int count, const std::vector<bool>& sharp = {}) {
  auto is_sharp = [&](int k) { return !sharp.empty() && sharp[static_cast<std::size_t>(k)]; };
  return {n == 0 || is_sharp(n) ? n : n - 1, n, n + 1, n + 2 >= count || is_sharp(n + 1) ? n + 1 : n + 2};
}

}  // namespace throng::test
