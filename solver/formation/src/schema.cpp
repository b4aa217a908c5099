#include <throng/formation/schema.h>
#include <throng/timewarp/schema.h>

namespace throng::formation {

void describe(OptionBinder& b, Options& o) {
  b.field({.key = "frame_rate", .unit = "Hz", .range = Range::positive(), .help = "output frames per second"}, o.frame_rate_hz);
  b.field({.key = "tension", .range = Range::closed(0, 1), .help = "Catmull-Rom τ of Eq. 5"}, o.tension);
  b.choice({.key = "interpolation", .help = "the paper's method, or a baseline of its figures (linear, polar)"},
           o.interpolation,
           {{"spectral", Interpolation::spectral}, {"linear", Interpolation::linear}, {"polar", Interpolation::polar}});
  b.choice({.key = "keyframe_product", .help = "Eq. 5's eigenbasis path: consecutive rotations, or as printed"},
           o.keyframe_product, {{"cumulative", KeyframeProduct::cumulative}, {"paper", KeyframeProduct::paper}});
  b.choice({.key = "reordering", .help = "none, greedy, or greedy then the max-min refinement (§4.2)"}, o.reordering,
           {{"none", Reordering::none}, {"greedy", Reordering::greedy}, {"max_min", Reordering::max_min}});
  b.choice({.key = "orientation", .help = "the PCA adjustment of §3.3"}, o.orientation,
           {{"none", OrientationAlignment::none}, {"pca", OrientationAlignment::pca},
            {"procrustes", OrientationAlignment::procrustes}});
  b.field({.key = "isotropy_tolerance", .range = {0.0, 1.0, false, true},
           .help = "below it (principal variances nearly equal) PCA uses procrustes"},
          o.isotropy_tolerance);
  b.field({.key = "match_individuals", .help = "keyframes' rows are not in correspondence: match them"}, o.match_individuals);
  b.field({.key = "auto_cluster_size", .range = Range::closed(2, 1e9),
           .help = "the largest group of a hierarchy built automatically"},
          o.auto_cluster_size);
  b.field({.key = "radius", .unit = "m", .range = Range::non_negative(), .help = "every individual's radius in the output"},
          o.radius_m);
  b.field({.key = "max_speed", .unit = "m/s", .range = Range::non_negative(),
           .help = "the stated speed the guard holds to (× guard.max_speed_ratio); 0: the keyframes' own"},
          o.max_speed_mps);
  b.section("guard", [&](OptionBinder& g) { timewarp::describe(g, o.guard); });
  b.section("facing", [&](OptionBinder& f) {
    FacingOptions& k = o.facing;
    f.field({.key = "smoothing", .unit = "s", .range = Range::non_negative(),
             .help = "the direction of travel is the path's chord over this window"},
            k.smoothing_s);
    f.field({.key = "standing_speed", .unit = "m/s", .range = Range::positive(),
             .help = "slower: standing (the facing is kept)"},
            k.rule.standing_speed);
    f.field({.key = "running_speed", .unit = "m/s", .range = Range::positive(), .help = "from this speed: running"},
            k.rule.running_speed);
    f.field({.key = "max_turn_rate", .unit = "rad/s", .range = Range::positive(),
             .help = "the travel facing turns at most this fast"},
            k.max_turn_rate_rad_s);
    f.field({.key = "bank", .help = "3-D: roll into turns as a coordinated turn"}, k.bank);
    f.field({.key = "gravity", .unit = "m/s²", .range = Range::positive(), .help = "g of the coordinated turn"},
            k.gravity_mps2);
  });
  b.section("collision", [&](OptionBinder& c) {
    CollisionOptions& k = o.collision;
    c.field({.key = "enabled", .help = "social forces then smoothing (§4.3)"}, k.enabled);
    c.field({.key = "min_distance", .unit = "m", .range = Range::positive(), .help = "centre to centre, at every frame"},
            k.min_distance_m);
    c.field({.key = "relaxation_time", .unit = "s", .range = Range::positive(), .help = "τ of the driving force"},
            k.relaxation_time_s);
    c.field({.key = "tracking_time", .unit = "s", .range = Range::positive(), .help = "how fast the path is tracked"},
            k.tracking_time_s);
    c.field({.key = "repulsion_strength", .unit = "m/s²", .range = Range::non_negative(), .help = "A of the repulsion"},
            k.repulsion_strength_m_per_s2);
    c.field({.key = "repulsion_range", .unit = "m", .range = Range::positive(), .help = "B of the repulsion"},
            k.repulsion_range_m);
    c.field({.key = "time_step", .unit = "s", .range = Range::positive(), .help = "largest simulation step"}, k.time_step_s);
    c.field({.key = "smoothing_time", .unit = "s", .range = Range::positive(), .help = "extent of the temporal smoothing"},
            k.smoothing_time_s);
    c.field({.key = "smoothing_passes", .range = Range::closed(1, 1000), .help = "smoothing/projection alternations"},
            k.smoothing_passes);
    c.field({.key = "projection_sweeps", .range = Range::closed(1, 1e6), .help = "Gauss–Seidel sweeps per frame"},
            k.projection_sweeps);
  });
}

}  // namespace throng::formation
