// The built-in patch library: hand-designed root-path episodes, the kind the paper made "manually using our
// motion editing system" (§6), sampled at a fixed rate and put in their canonical frames (normalise_frames).
//
// Pose classes: "standing", "walking" (and "carrying", "sitting" for the box patches). Walking ends face along
// the path. Patches (name: characters, entry → exit, what happens):
//   walk            1  walking → walking     straight, walk_duration_s
//   walk_slow       1  walking → walking     straight at 0.7 × speed (label "slow")
//   walk_fast       1  walking → walking     straight at 1.4 × speed (label "fast")
//   turn_left, turn_right            1  walking → walking   45° arcs
//   turn_left_90, turn_right_90      1  walking → walking   90° arcs
//   stop            1  walking → standing    decelerate to a stand
//   start           1  standing → walking    accelerate from a stand
//   wait            1  standing → standing   stand still
//   turn_in_place   1  standing → standing   turn 90° on the spot
//   meet            2  walking → walking     approach, stop face to face 1 m apart, talk, walk off to the sides
//   pass            2  walking → walking     walk past each other 0.6 m apart, each sidestepping 0.3 m
//   handshake       2  walking → walking     approach, stand 0.9 m apart shaking hands, walk on past each other
//   bump            2  walking → walking     shoulders brush (capsules 2 cm apart), both are deflected
//   bow_rows        10 walking → walking     two rows of five walk in side by side, bow to each other, turn round and walk back out (label "group")
//   box_pickup      1  standing → carrying   take a box from a stack (prop: the stack)
//   box_carry       1  carrying → carrying   walk with the box
//   box_pass        2  carrying, walking → walking, carrying   hand the box over
//   box_sit         1  carrying → sitting    put the box down and sit on it
//   sit             1  sitting → sitting     sit on the box
//   box_stand       1  sitting → walking     stand up and walk away (prop: the box, left behind)
// A character carrying a box (or sitting on one) is a capsule 0.1 m wider and has the prop "box" (Fragment::prop);
// boxes on the ground are props.
// Interpersonal constraints tie the characters of two-character and group patches at the frames where they
// interact. No two capsules of a built-in patch (characters and props) ever overlap: the patches declare no
// contact (patch.h, contact_pairs), so the tiler and the checker keep every pair of an instance clear.
#pragma once

#include <throng/tiling/patch.h>

#include <string>
#include <vector>

namespace throng::tiling {

struct BuiltinOptions {
  double sample_rate_hz = 10.0;   ///< samples per second of every path
  double radius_m = 0.25;         ///< character radius
  double walk_speed_mps = 1.3;
  double walk_duration_s = 2.0;   ///< length of the single-character walking patches
  double wait_duration_s = 2.0;
  double preference_per_character = 1.0;  ///< a type's preference = this × its characters (§6: larger patches favoured)
};

/// Every built-in patch name, in library order.
[[nodiscard]] std::vector<std::string> builtin_patch_names();

/// Named groups for job files: "locomotion" (walks, turns, stop, start, wait, turn_in_place), "interaction"
/// (meet, pass, handshake, bump), "group" (bow_rows), "boxes" (the box patches), "all".
[[nodiscard]] std::vector<std::string> builtin_patch_group(const std::string& group);

/// The library of the named patches (in the order given; names may repeat groups' members only once).
/// Throws ConfigError naming an unknown patch and listing the known ones.
[[nodiscard]] PatchLibrary builtin_library(const std::vector<std::string>& names, const BuiltinOptions& options = {});

}  // namespace throng::tiling
