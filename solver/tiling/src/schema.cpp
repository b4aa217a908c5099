#include <throng/tiling/schema.h>

namespace throng::tiling {
namespace {

// Sample rates above this make patches of tens of thousands of samples, beyond every deformation budget.
constexpr Range sample_rates{0, 1000, true, false};
constexpr Range half_turn{0, 180, true, false};

}  // namespace

void describe(OptionBinder& b, Options& o) {
  b.field({.key = "characters", .range = Range::closed(0, 1e9), .help = "phase 1 adds no patch beyond this many characters (0: no limit)"},
          o.characters);
  b.field({.key = "chains", .range = Range::closed(1, 100000), .help = "independent chains (multi-start over threads and ranks)"},
          o.chains);
  b.section("limits", [&](OptionBinder& l) {
    l.field({.key = "stretch", .unit = "m", .range = Range::positive(), .help = "deformation per frame: stretch"}, o.limits.stretch_m);
    angle_in_degrees(l, {.key = "bend", .unit = "deg", .range = half_turn, .help = "deformation per frame: bend"}, o.limits.bend_rad);
    l.field({.key = "time_shift", .unit = "s", .range = Range::positive(), .help = "deformation per frame: time shift"},
            o.limits.time_shift_s);
    double rate = 1.0 / o.limits.frame_period_s;
    l.field({.key = "frame_rate", .unit = "Hz", .range = Range::positive(), .help = "the frames the limits are per"}, rate);
    o.limits.frame_period_s = 1.0 / rate;
    l.field({.key = "bend_min_segment", .unit = "m", .range = Range::non_negative(), .help = "shorter segments are not checked for bend"},
            o.limits.bend_min_segment_m);
    l.field({.key = "speed_ratio", .range = Range::non_negative(),
             .help = "no deformed segment faster than this times the library's fastest (0: the paper's limits only)"},
            o.limits.speed_ratio);
  });
  b.section("match", [&](OptionBinder& m) {
    m.field({.key = "distance", .unit = "m", .range = Range::positive(), .help = "an exit matches an entry this close"}, o.match.distance_m);
    angle_in_degrees(m, {.key = "angle", .unit = "deg", .range = half_turn, .help = "... turned at most this much"}, o.match.angle_rad);
    m.field({.key = "time", .unit = "s", .range = Range::positive(), .help = "... and this close in time"}, o.match.time_s);
  });
  b.section("deformation", [&](OptionBinder& d) {
    d.field({.key = "anchor_weight", .range = Range::positive(), .help = "weight keeping a patch near its shape"},
            o.deformation.anchor_weight);
    d.field({.key = "deform_neighbours", .help = "a placement may deform the patches it connects to"}, o.deformation.deform_neighbours);
    d.field({.key = "constraint_tolerance", .range = Range::positive(), .help = "a connection is met within this"},
            o.deformation.constraint_tolerance);
  });
  b.section("annealing", [&](OptionBinder& a) {
    a.field({.key = "alpha", .range = Range::non_negative(), .help = "phase 1's cost of a dangling end"}, o.annealing.alpha);
    a.field({.key = "k", .range = Range::positive(), .help = "Boltzmann constant of the acceptance"}, o.annealing.boltzmann_k);
    a.field({.key = "t_max", .range = Range::non_negative(), .help = "start temperature"}, o.annealing.t_max);
    a.field({.key = "t_step", .range = Range::non_negative(), .help = "cooling per proposal"}, o.annealing.t_step);
    a.field({.key = "max_failures", .range = Range::closed(0, 1e12), .help = "proposals in a row without a placement"},
            o.annealing.max_failures);
    a.field({.key = "max_proposals", .range = Range::closed(1, 1e12), .help = "proposals at most"}, o.annealing.max_proposals);
  });
  b.section("search", [&](OptionBinder& s) {
    s.section("jitter_start", [&](OptionBinder& j) {
      j.field({.key = "distance", .unit = "m", .range = Range::non_negative(), .help = "first jitter of a retried end"},
              o.search.jitter_distance_start_m);
      angle_in_degrees(j, {.key = "angle", .unit = "deg", .range = Range::closed(0, 180)}, o.search.jitter_angle_start_rad);
      j.field({.key = "time", .unit = "s", .range = Range::non_negative()}, o.search.jitter_time_start_s);
    });
    s.section("jitter_end", [&](OptionBinder& j) {
      j.field({.key = "distance", .unit = "m", .range = Range::non_negative(), .help = "last jitter of a retried end"},
              o.search.jitter_distance_end_m);
      angle_in_degrees(j, {.key = "angle", .unit = "deg", .range = Range::closed(0, 180)}, o.search.jitter_angle_end_rad);
      j.field({.key = "time", .unit = "s", .range = Range::non_negative()}, o.search.jitter_time_end_s);
    });
    s.field({.key = "attempts", .range = Range::closed(1, 1e6), .help = "jittered tries per end"}, o.search.jitter_attempts);
    s.field({.key = "max_steps", .range = Range::closed(0, 1e12), .help = "placements of the deterministic search at most"},
            o.search.max_steps);
  });
  b.section("density", [&](OptionBinder& d) {  // the zones, a list, are read beside the schema (io/tiling_job.h)
    DensityOptions& o2 = o.density;
    d.field({.key = "per_m2", .unit = "1/m²", .range = Range::non_negative(),
             .help = "characters per m² over the region at every time (0: none; `characters` caps the total)"},
            o2.per_m2);
    d.field({.key = "free_area", .help = "areas are what obstacles leave free (else their boxes)"}, o2.free_area);
    d.field({.key = "area_cell", .unit = "m", .range = Range::positive(), .help = "raster of the free area"}, o2.area_cell_m);
    d.field({.key = "tolerance", .range = Range{0, 1, true, true}, .help = "a reported window's mean within this relative error"},
            o2.tolerance);
    d.field({.key = "bin", .unit = "s", .range = Range::positive(), .help = "control and measurement bins"}, o2.bin_s);
    d.field({.key = "report_window", .unit = "s", .range = Range::positive(), .help = "reported windows (a windowed run's own)"},
            o2.report_window_s);
    d.field({.key = "rounds", .range = Range::closed(0, 1000), .help = "correction rounds after phase 2"}, o2.rounds);
    d.field({.key = "projection_speed", .unit = "m/s", .range = Range::positive(),
             .help = "walking speed at which a dangling end is projected to the region's side"},
            o2.projection_speed_mps);
  });
  b.section("index", [&](OptionBinder& i) {
    i.field({.key = "cell", .unit = "m", .range = Range::positive(), .help = "space cell of the validity tests' grid"}, o.index.cell_m);
    i.field({.key = "cell_time", .unit = "s", .range = Range::positive(), .help = "time cell of that grid"}, o.index.cell_s);
  });
  b.field({.key = "obstacle_step", .unit = "m", .range = Range::positive(), .help = "obstacle tests every so many metres"},
          o.obstacle_step_m);
  b.field({.key = "obstacle_step_time", .unit = "s", .range = Range::positive(), .help = "... and seconds along each path"},
          o.obstacle_step_s);
}

void describe(OptionBinder& b, LayoutOptions& o) {
  b.field({.key = "frame_rate", .unit = "Hz", .range = Range::positive(), .help = "the characters' frames"}, o.frame_rate_hz);
  angle_in_degrees(b, {.key = "max_facing_rate", .unit = "deg/s", .range = Range::non_negative(),
                       .help = "the fastest a facing turns (0: as the patches' headings, the paper's output)"},
                   o.max_facing_rate_rad_s);
  std::vector<std::int64_t> repeat(o.repeat.begin(), o.repeat.end());
  b.field({.key = "repeat", .range = Range::closed(1, 1000), .help = "copies of a repeating tile per axis (x, y, t)", .length = 3}, repeat);
  for (std::size_t a = 0; a < 3 && a < repeat.size(); ++a) o.repeat[a] = static_cast<int>(repeat[a]);
}

void describe(OptionBinder& b, BuiltinOptions& o) {
  b.field({.key = "sample_rate", .unit = "Hz", .range = sample_rates, .help = "samples per second of the built-in patches"},
          o.sample_rate_hz);
  b.field({.key = "radius", .unit = "m", .range = Range::positive()}, o.radius_m);
  b.field({.key = "walk_speed", .unit = "m/s", .range = Range::positive()}, o.walk_speed_mps);
  b.field({.key = "walk_duration", .unit = "s", .range = Range::positive()}, o.walk_duration_s);
  b.field({.key = "wait_duration", .unit = "s", .range = Range::positive()}, o.wait_duration_s);
  b.field({.key = "preference_per_character", .range = Range::positive()}, o.preference_per_character);
}

void describe(OptionBinder& b, RealPatchOptions& o) {
  b.field({.key = "sample_rate", .unit = "Hz", .range = sample_rates, .help = "samples per second of the patches"}, o.sample_rate_hz);
  b.field({.key = "max_gap", .unit = "s", .range = Range::positive()}, o.max_gap_s);
  b.field({.key = "radius", .unit = "m", .range = Range::positive()}, o.radius_m);
  b.field({.key = "standing_speed", .unit = "m/s", .range = Range::positive()}, o.standing_speed_mps);
  b.field({.key = "clean_acceleration", .unit = "m/s²", .range = Range::positive(), .help = "boundaries only where the velocity changes less"},
          o.clean_acceleration_mps2);
  b.field({.key = "reaction_window", .unit = "s", .range = Range::non_negative(), .help = "half window of the motion variation (Eq. 4)"},
          o.reaction_window_s);
  b.field({.key = "contact", .unit = "m", .range = Range::non_negative(), .help = "two people this close have a contact event"}, o.contact_m);
  b.field({.key = "near", .unit = "m", .range = Range::positive(), .help = "two people this close have a proximity event when one reacts"},
          o.near_m);
  b.field({.key = "reaction_min", .unit = "m²/s²", .range = Range::non_negative(), .help = "motion variation (Eq. 4) of a reaction"},
          o.reaction_min_m2ps2);
  b.field({.key = "sync_range", .unit = "m", .range = Range::non_negative(), .help = "synchronicity events only between people this close"},
          o.sync_range_m);
  b.field({.key = "synchronicity_min", .unit = "m⁴/s⁴", .range = Range::non_negative(), .help = "synchronicity (Eq. 5) of an event"},
          o.synchronicity_min);
  b.field({.key = "min_contact", .unit = "s", .range = Range::non_negative(), .help = "shorter events are ignored"}, o.min_contact_s);
  b.field({.key = "merge_gap", .unit = "s", .range = Range::non_negative(), .help = "events this close in time may merge into one episode"},
          o.merge_gap_s);
  b.field({.key = "merge_distance", .unit = "m", .range = Range::non_negative(),
           .help = "events of different people merge when two of them come this close"},
          o.merge_distance_m);
  b.field({.key = "max_episode_characters", .range = Range::closed(2, 1e6), .help = "larger merged episodes are dropped"},
          o.max_episode_characters);
  b.field({.key = "margin", .unit = "s", .range = Range::non_negative(), .help = "boundaries are searched this far beyond an episode"},
          o.margin_s);
  b.field({.key = "boundary_lead", .unit = "s", .range = Range::non_negative(),
           .help = "boundaries at least this far before and after an episode (0: tight, as the paper)"},
          o.boundary_lead_s);
  b.field({.key = "pose_speed_scale", .unit = "m/s", .range = Range::positive(), .help = "speed unit of the boundary pose distance"},
          o.pose_speed_scale_mps);
  b.field({.key = "pose_turn_scale", .unit = "rad/s", .range = Range::positive(), .help = "turn-rate unit of the boundary pose distance"},
          o.pose_turn_scale_radps);
  b.field({.key = "pose_threshold", .range = Range::closed(0.05, 1e6), .help = "diameter below which boundary poses form one group (≥ 0.05: its clustering grid grows as its inverse square)"},
          o.pose_threshold);
  b.field({.key = "pose_groups", .range = Range::closed(1, 16), .help = "the largest pose groups the boundaries are chosen from"},
          o.pose_groups);
  b.field({.key = "diversity_weight", .range = Range::non_negative(),
           .help = "cost of one more pose group against the patches' share of the recorded frames"},
          o.diversity_weight);
  b.field({.key = "builtin_classes", .help = "name the pose groups standing and walking like the built-in patches"}, o.builtin_classes);
  b.field({.key = "single_duration", .unit = "s", .range = Range::positive()}, o.single_duration_s);
  b.field({.key = "max_episode_patches", .range = Range::closed(0, 1e6), .help = "pair and group patches at most"}, o.max_episode_patches);
  b.field({.key = "max_single_patches", .range = Range::closed(0, 1e6)}, o.max_single_patches);
  b.field({.key = "preference_per_character", .range = Range::positive()}, o.preference_per_character);
  b.field({.key = "prefix", .help = "the patch names' prefix"}, o.prefix);
}

}  // namespace throng::tiling
