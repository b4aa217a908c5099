#include <throng/collide/schema.h>

namespace throng::collide {

void describe(OptionBinder& b, Options& o) {
  b.field({.key = "margin", .unit = "m", .range = Range::non_negative(), .flag = "--margin",
           .help = "clearance beyond the radii: r_a + r_b + margin between agents, r + margin to an obstacle"},
          o.margin);
  b.field({.key = "push_fraction", .range = {0.0, 1.0, true, false}, .flag = "--push-fraction",
           .help = "a push separates a pair by this fraction of its clearance (paper: 10 %)"},
          o.push_fraction);
  b.choice({.key = "push_size", .flag = "--push-size",
            .help = "full: a push clears the deficit plus push_fraction; fraction: push_fraction alone (paper: 10 %)"},
           o.push_size, {{"full", PushSize::full}, {"fraction", PushSize::fraction}});
  b.field({.key = "max_iterations", .range = Range::closed(1, 1e9), .flag = "--max-iterations", .help = "solves at most"},
          o.max_iterations);
  b.field({.key = "smoothing_time", .unit = "s", .range = Range::non_negative(), .flag = "--smoothing-time",
           .help = "a push fades as (1 + |t|/T) e^(-|t|/T) over this time each side (0: spread and velocity_weight instead)"},
          o.smoothing_time);
  b.field({.key = "smoothing_weight", .range = Range::positive(),
           .help = "λ: the smoothing in time against the temporal shape features"},
          o.smoothing_weight);
  b.field({.key = "catch_up_time", .unit = "s", .range = Range::non_negative(),
           .help = "the same along the agent's own path: a push that holds it back is caught up over this time"},
          o.catch_up_time);
  b.field({.key = "spread", .unit = "frames", .range = Range::closed(1, 1e6), .flag = "--spread",
           .help = "smoothing_time 0: frames over which a push fades along a trajectory, each side"},
          o.spread);
  b.field({.key = "velocity_weight", .range = Range::non_negative(),
           .help = "smoothing_time 0: weight of velocity changes against the shape features (0: the paper's energy)"},
          o.velocity_weight);
  b.choice({.key = "obstacle_pull", .flag = "--obstacle-pull",
            .help = "back: to the side the agent came from; sideways: across its motion, the way round; nearest: to the "
                    "nearest boundary (paper)"},
           o.obstacle_pull,
           {{"back", ObstaclePull::back}, {"sideways", ObstaclePull::sideways}, {"nearest", ObstaclePull::nearest}});
  b.choice({.key = "pair_push", .help = "sideways: across the pair's relative motion; apart: along their offset (paper)"},
           o.pair_push, {{"sideways", PairPush::sideways}, {"apart", PairPush::apart}});
  b.field({.key = "pin_ends", .flag = "!--no-pin-ends",
           .help = "every trajectory's first and last present frame stays where it is"},
          o.pin_ends);
  b.field({.key = "fixed_agents", .flag = "--fixed-agents", .help = "ids of agents that must not move at all"},
          o.fixed_agents);
  b.field({.key = "min_feature_length", .unit = "m", .range = Range::positive(),
           .help = "ℓ of the temporal feature weights (throng/graph/features.h)"},
          o.min_feature_length);
  b.field({.key = "max_displacement", .unit = "m", .range = Range::non_negative(), .flag = "--max-displacement",
           .help = "how far a vertex may move from its input (0: 8 agent radii); a deformation is shortened to keep within it"},
          o.max_displacement);
  b.field({.key = "max_speed_ratio", .range = Range::non_negative(), .flag = "--max-speed-ratio",
           .help = "no deformation makes an agent faster than this × the input crowd's fastest (0: no limit)"},
          o.max_speed_ratio);
  b.field({.key = "max_acceleration", .unit = "m/s²", .range = Range::non_negative(), .flag = "--max-acceleration",
           .help = "nor raises a frame's acceleration above this or the input's own there (0: no limit)"},
          o.max_acceleration);
  b.field({.key = "contact_patience", .range = Range::closed(1, 1e9),
           .help = "pushes of one contact without getting shallower before it is abandoned"},
          o.contact_patience);
  b.field({.key = "stall_iterations", .range = Range::closed(1, 1e9),
           .help = "stop (\"no progress\") after this many iterations without fewer pushable contacts"},
          o.stall_iterations);
}

}  // namespace throng::collide
