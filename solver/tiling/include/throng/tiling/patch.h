// Motion patches: the building blocks a tiling lays out in space and time.
//
// Paper: Hyun, Kim, Hwang, Lee, "Tiling Motion Patches" (seed 004) §3, read with METHODS.md §4. There is no
// full-body motion here: a patch holds its characters' ROOT paths (ground position, heading, time per sample),
// and per entry/exit a discrete pose class (standing, walking, clusters of boundary states ...). A patch may also
// carry props (a box, a stack of boxes): occupants that move with the patch and must not be penetrated, but that
// have no entries or exits.
//
// Shapes (per fragment, #samples ≥ 2):
//   positions  #samples ground points (metres) in the patch's own frame
//   headings   #samples facing directions (radians, CCW from +x) in the patch's own frame
//   times      #samples (seconds), strictly increasing, in the patch's own clock
//
// Entry = first sample of a character fragment, exit = last sample. Stitching an exit of one instance to an
// entry of another (Eq. 1–3) needs the same pose class and position, direction and time within thresholds.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace throng::tiling {

/// What a fragment is: a character's root path (with an entry and an exit), or a prop carried or placed by the
/// patch (an occupant only: never stitched, never dangling, not a character of the output).
enum class FragmentKind { character, prop };

/// One path through a patch.
struct Fragment {
  FragmentKind kind = FragmentKind::character;
  double radius_m = 0.25;                 ///< body (or prop) radius: the capsule of the interpenetration test
  std::vector<Eigen::Vector2d> positions;  ///< see the file comment for shapes and frames
  std::vector<double> headings;
  std::vector<double> times;
  std::size_t entry_class = 0;  ///< pose class of the first sample (index into PatchLibrary::pose_classes)
  std::size_t exit_class = 0;   ///< pose class of the last sample
  std::string prop;             ///< what the character carries or uses in this patch ("box"); empty for nothing.
                                ///< Names the laid character's action with the type's name (characters.h)

  [[nodiscard]] std::size_t sample_count() const noexcept { return times.size(); }
  [[nodiscard]] bool is_character() const noexcept { return kind == FragmentKind::character; }
};

/// An interpersonal (or person–object) constraint: the relative position of sample `sample_b` of fragment
/// `fragment_b` with respect to sample `sample_a` of fragment `fragment_a`, and their time difference, stay as in
/// the patch while the patch deforms (see deformation.h for how this is kept linear).
struct InterpersonalConstraint {
  std::size_t fragment_a = 0;
  std::size_t sample_a = 0;
  std::size_t fragment_b = 0;
  std::size_t sample_b = 0;
};

/// One patch type of the library: an episode of one or more characters.
struct PatchType {
  std::string name;              ///< unique within the library
  std::string label;             ///< user label for preferences (Eq. 7 f4: "slow", "fast", "friendly" ...); may be empty
  double preference = 1.0;       ///< relative sampling weight in phase 1 (larger patches favoured, paper §6), > 0
  std::vector<Fragment> fragments;
  std::vector<InterpersonalConstraint> constraints;

  [[nodiscard]] std::size_t character_count() const noexcept;
  [[nodiscard]] std::size_t sample_count() const noexcept;  ///< over all fragments
  [[nodiscard]] double start_time() const noexcept;         ///< earliest sample time
  [[nodiscard]] double end_time() const noexcept;           ///< latest sample time
};

/// A collection of patch types and the names of their pose classes.
struct PatchLibrary {
  std::vector<std::string> pose_classes;
  std::vector<PatchType> types;

  /// Index of the type called `name`; throws ConfigError naming the known types when there is none.
  [[nodiscard]] std::size_t find(const std::string& name) const;
  /// Index of pose class `name`, added when new.
  std::size_t pose_class(const std::string& name);

  /// Checks every invariant: at least one type; unique non-empty names; preference > 0; every fragment with ≥ 2
  /// samples, matching array lengths, finite values, strictly increasing times, radius > 0; pose classes in
  /// range; at least one character per type; constraint indices in range. Throws InputError naming `what`, the
  /// type, the fragment, the sample and the value.
  void validate(const std::string& what = "patch library") const;
};

/// The pairs of fragments (a < b) that the patch itself brings closer than the sum of their radii at some
/// time: contact the patch declares by its own data (a recorded couple walking arm in arm, a hand-over). Every
/// other pair of an instance must keep clear however the instance deforms; the tiler and the checker test it.
/// Exact on the linearly interpolated paths.
[[nodiscard]] std::vector<std::pair<std::size_t, std::size_t>> contact_pairs(const PatchType& type);

/// The fastest segment of any fragment of `library` (m/s): distance over time between consecutive samples.
[[nodiscard]] double fastest_speed(const PatchLibrary& library);

/// The speed no deformed segment may exceed under `speed_ratio` (DeformationLimits): that times the library's
/// fastest segment, or infinity when speed_ratio is 0 or no patch moves (a library of standing patches has no
/// speed to keep to).
[[nodiscard]] double speed_limit(const PatchLibrary& library, double speed_ratio);

/// Re-expresses every type in its canonical frame, which the preference function (Eq. 7) and the instance
/// transforms refer to: origin at the centroid of all samples, +x along the mean travel direction (sum over
/// character fragments of exit − entry; the mean entry heading when nobody travels), time origin at the middle of
/// the type's time span. The shape of every path is unchanged (a rigid motion in space, a shift in time).
void normalise_frames(PatchLibrary& library);

}  // namespace throng::tiling
