// A tiling: patch instances placed in space and time, their deformed paths, and the connections between them;
// and the environment it is made for (region, obstacles, sources and sinks).
//
// An instance places a patch type by a rigid motion in space and a shift in time (`Transform`), then deforms
// its paths slightly (stitching, deformation.h): `paths` are the deformed paths in world coordinates, what the
// characters do. A connection stitches the exit of one character fragment to the entry of another (Eq. 1–3):
// same position, same tangent, same time — up to a whole number of periods on the periodic axes of a repeating
// tile (`image`: entry + image ⊙ period = exit).
//
// Ends that need no partner ("the region rule"): an entry or exit outside the region's open box on a
// non-periodic axis (the character enters or leaves the box in space or time), an entry inside a source, an exit
// inside a sink. Every other unconnected character end is dangling; a tiling is perfect when none is.
#pragma once

#include <throng/core/scene.h>

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace throng::tiling {

/// Where an instance is: p_world = R(angle) p_patch + translation, t_world = t_patch + time_shift.
struct Transform {
  Eigen::Vector2d translation{0, 0};  ///< metres: where the patch's centroid goes
  double angle = 0.0;                 ///< radians, CCW: where the patch's +x (mean travel direction) points
  double time_shift = 0.0;            ///< seconds: when the middle of the patch's time span happens

  [[nodiscard]] Eigen::Vector2d apply(const Eigen::Vector2d& p) const;
};

/// One deformed path in world coordinates (same shapes as the fragment it deforms, see patch.h).
struct Path {
  std::vector<Eigen::Vector2d> positions;
  std::vector<double> headings;
  std::vector<double> times;
};

/// A placed patch.
struct Instance {
  std::size_t type = 0;
  Transform transform;
  bool keyframed = false;   ///< placed by the user: never deformed, never removed
  std::vector<Path> paths;  ///< one per fragment of the type
};

/// A fragment of an instance.
struct FragmentRef {
  std::uint32_t instance = 0;
  std::uint32_t fragment = 0;
  friend bool operator==(const FragmentRef&, const FragmentRef&) = default;
  friend auto operator<=>(const FragmentRef&, const FragmentRef&) = default;
};

/// Exit of `from` stitched to the entry of `to`; `image` counts periods per axis (x, y, t): entry + image ⊙ period
/// = exit. Always 0 on non-periodic axes.
struct Connection {
  FragmentRef from;
  FragmentRef to;
  std::array<int, 3> image{0, 0, 0};
};

struct Tiling {
  std::vector<Instance> instances;
  std::vector<Connection> connections;
};

/// A disc in space over a time interval: where characters may appear (source: entries need no partner) or
/// leave (sink: exits need no partner).
struct Zone {
  Eigen::Vector2d center{0, 0};
  double radius_m = 1.0;
  double t0 = -1e300;
  double t1 = 1e300;

  [[nodiscard]] bool contains(const Eigen::Vector2d& p, double t) const noexcept {
    return (p - center).squaredNorm() <= radius_m * radius_m && t >= t0 && t <= t1;
  }
};

/// What a tiling is made for. `scene.region` is required by the tiler: the space-time box to fill (periodic
/// axes make a repeating tile); `scene.obstacles`, static or moving, may not be penetrated by any character.
struct Environment {
  Scene scene;
  std::vector<Zone> sources;
  std::vector<Zone> sinks;
};

/// The region's periods per axis (x, y, t): the box's extent on periodic axes, 0 elsewhere.
[[nodiscard]] Eigen::Vector3d periods(const Region& region);

/// The region rule for a character end: true when an end at (`position`, `time`) needs no partner because it
/// lies outside the region's open box on a non-periodic axis, or (entries) in a source, or (exits) in a sink.
[[nodiscard]] bool end_needs_no_partner(const Environment& environment, const Eigen::Vector2d& position, double time,
                                        bool is_exit);

}  // namespace throng::tiling
