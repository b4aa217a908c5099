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
//
// Facing and action (CrowdMotion::orientations, actions, action_table): the patch's own root headings, carried
// through the instance's placement and deformation (Path::headings), interpolated between samples as the
// positions are (turning the shorter way), as a yaw about +z: a turn in place turns the character by the patch's
// angle, a standing character keeps its facing, a bowing row faces its partners. The action at a frame is the
// patch (type name, fragment prop) of the path segment the frame lies on (the earlier patch at a frame exactly on
// a join), an index into patch_actions(library).table. Absent frames: orientation NaN, action −1.
// Beyond the paper, the facing turns at most LayoutOptions::max_facing_rate_rad_s: from frame to frame of an
// agent's present run it follows the patches' heading, but turns at most that rate × the frame period toward it
// (laid_pose.h, facing_toward), so patches joined with different headings turn the character on the spot.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/tiling/patch.h>
#include <throng/tiling/tiling.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <vector>

namespace throng::tiling {

struct LayoutOptions {
  double frame_rate_hz = 10.0;
  std::array<int, 3> repeat{1, 1, 1};  ///< copies per axis (x, y, t); > 1 only on periodic axes
  /// The fastest a character's facing turns (rad/s; 0: as fast as the patches' headings, the paper's output).
  /// 270°/s: a person turns about on the spot in under a second.
  double max_facing_rate_rad_s = 1.5 * std::numbers::pi;
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

/// The action table of a library's laid characters: standard_actions() (walk, stand, run), then for every
/// character fragment of every type, in library order, its (type name, prop) when not yet in the table (a "walk"
/// patch without a prop is the standard walk). The same for every tiling of the library, so the windows of a long
/// run share it.
struct PatchActions {
  std::vector<ActionKind> table;
  std::vector<std::vector<std::int32_t>> of_fragment;  ///< per type, per fragment: index into table; −1 for props
};
[[nodiscard]] PatchActions patch_actions(const PatchLibrary& library);

/// The largest turn of a character's facing from one frame to the next under `options` (radians; infinity when
/// max_facing_rate_rad_s is 0). Throws ConfigError for a negative or non-finite facing rate, or a frame rate ≤ 0.
[[nodiscard]] double max_turn_per_frame(const LayoutOptions& options);

/// Lays out the characters of `tiling` (see the file comment). Throws ConfigError for a repeat count < 1 or
/// > 1 on a non-periodic axis, a frame rate ≤ 0, or a negative or non-finite facing rate.
[[nodiscard]] Characters lay_out(const PatchLibrary& library, const Tiling& tiling, const Region& region,
                                 const LayoutOptions& options);

/// Number of chains of connected character fragments (what the paper counts as characters): fragments minus
/// connections, plus one per closed loop (possible only on a periodic time axis).
[[nodiscard]] std::size_t count_characters(const PatchLibrary& library, const Tiling& tiling);

}  // namespace throng::tiling
