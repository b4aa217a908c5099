// The characters a tiling makes: chains of connected character fragments become continuous agents.
//
// lay_out() places copies of the tile (repeat[a] copies along each periodic axis a, shifted by the period;
// 1 on non-periodic axes) and follows every connection from fragment to fragment — into the neighbouring copy
// when the connection crosses a seam — so a character walks on across the seams of a repeating tile. A chain
// is cut where it would enter a copy that is not laid (the outer boundary of the laid tiles), and its samples
// are kept only inside the laid box on periodic axes (every point of the laid box then belongs to exactly one
// image of each path) and inside the laid time span. Each maximal piece of a chain present without a gap is one
// agent. Agents are sampled at `frame_rate_hz` by linear interpolation of the deformed paths (the paths are
// piecewise linear between samples: interpolation is exact).
//
// Frames: from t0 to t0 + repeat[t] · (t1 − t0), every 1 / frame_rate_hz; the last frame is t1 itself on a
// non-periodic time axis and is left out on a periodic one (it is the first frame of the next copy).
// Agent order: by first present frame, then by (copy, instance, fragment) of the chain's first fragment;
// ids 0..N−1; radius: the largest radius of the chain's fragments; species 0.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/tiling/patch.h>
#include <throng/tiling/tiling.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace throng::tiling {

struct LayoutOptions {
  double frame_rate_hz = 10.0;
  std::array<int, 3> repeat{1, 1, 1};  ///< copies per axis (x, y, t); > 1 only on periodic axes
};

/// Which fragment copies make up an agent, in order.
struct AgentPiece {
  FragmentRef fragment;
  std::array<int, 3> copy{0, 0, 0};
};

struct Characters {
  CrowdMotion motion;
  std::vector<std::vector<AgentPiece>> pieces;  ///< per agent, the fragment copies it walks through
};

/// Lays out the characters of `tiling` (see the file comment). Throws ConfigError for a repeat count < 1 or
/// > 1 on a non-periodic axis, or a frame rate ≤ 0.
[[nodiscard]] Characters lay_out(const PatchLibrary& library, const Tiling& tiling, const Region& region,
                                 const LayoutOptions& options);

/// Number of chains of connected character fragments (what the paper counts as characters): fragments minus
/// connections, plus one per closed loop (possible only on a periodic time axis).
[[nodiscard]] std::size_t count_characters(const PatchLibrary& library, const Tiling& tiling);

}  // namespace throng::tiling
