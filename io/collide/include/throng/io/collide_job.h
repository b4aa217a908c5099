// The collision repair job (`throng collide CROWD.h5 [--job COLLIDE.yaml] -o OUT.h5`, or a `collide` step of
// `throng run`), and the method data it stores in the output under /parameters/throng/collide.
//
// Job file (every key optional; defaults shown; lengths in metres; the options' schema is
// throng/collide/schema.h, the method throng/collide/collide.h):
//
//   margin: 0                  # clearance = r_a + r_b + margin between agents, r + margin to an obstacle
//   push_fraction: 0.1         # a push separates a pair by its depth plus this fraction of its clearance
//   push_size: full            # full | fraction (push_fraction per push: the paper's 10 %)
//   max_iterations: 10000      # solves at most
//   smoothing_time: 1          # seconds a push fades over (0: spread and velocity_weight instead)
//   smoothing_weight: 10       # the smoothing in time against the shape features, > 0
//   catch_up_time: 8           # seconds: the same along the agent's own path
//   spread: 15                 # smoothing_time 0: frames over which a push fades along a trajectory, ≥ 1
//   velocity_weight: 1         # smoothing_time 0: velocity changes against the shape features (0: the paper's)
//   pair_push: sideways        # sideways (across the pair's relative motion) | apart (along their offset: paper)
//   obstacle_pull: back        # back (the side it came from) | sideways (the way round) | nearest (paper)
//   pin_ends: true             # every trajectory's first and last present frame stays where it is
//   fixed_agents: [3, 8]       # ids of agents that must not move at all
//   min_feature_length: 0.05   # ℓ of the temporal feature weights (throng/graph/features.h)
//   max_displacement: 0        # metres a vertex may move from its input (0: 8 agent radii)
//   max_speed_ratio: 1.25      # no agent faster than this × the input's fastest (0: no limit)
//   max_acceleration: 8        # m/s², or the input's own where higher (0: no limit)
//   contact_patience: 1000     # pushes of one contact without getting shallower before it is abandoned
//   stall_iterations: 5000     # stop ("no progress") after this many iterations without fewer pushable contacts
//   allow_remaining: false     # true: collisions left at the end are a warning, not exit 5
//   obstacles: [...]           # more obstacles, added to the crowd file's own (io/scene_config.h format)
//   region: {...}              # carried into the output's scene; a periodic region is a ConfigError (distances
//                              # are not wrapped)
//
// Malformed keys and values are ConfigErrors (exit 2) naming the line; an unknown fixed agent is a ConfigError
// from the solver naming the id.
#pragma once

#include <throng/collide/runner.h>
#include <throng/io/job_file.h>

namespace throng::collide {

/// Reads and checks a whole job (a periodic region is refused), then calls node.finish() (unknown keys are
/// errors). ConfigError naming the line. The effective job is job_file.h's.
void read_job(const ConfigNode& node, Job& job);
/// Writes beside the report (collide/runner.h) in /parameters/throng/collide:
///   history   int64[I]    contacts (colliding frame intervals) after each iteration
void write_data(const h5::Group& record, const Run& run);

}  // namespace throng::collide
