// The split job (`throng split CROWD.h5 -o PART.h5 [--other REST.h5]`, or a `split` step of `throng run`) and the
// data it stores under /parameters/throng/split. Splitting by time, by agents, or both (solver/stitch/split.h;
// the job's schema in solver/stitch/schema.h, the runner in jobs.h).
//
// Job keys (all optional, but at least one way to split; frames are indices into the input, times in seconds):
//
//   at_frame: 120                 # split by time at this frame: the two parts share it (first: 0..120,
//   at_time: 4.8                  #   second: 120..end); or at the frame nearest this time
//   frames: [100, 400]            # or cut out frames 100..400 (a split at both ends keeping the middle);
//   times: [4, 16]                #   or the frames nearest these times
//   keep: first                   # first | second: the part of a split at at_frame / at_time
//   agents: [3, 5, 8]             # split by agents: these ids ...
//   species: [1]                  # ... and every agent of these species (the union of both)
//   keep_agents: selected         # selected | rest
//   present_throughout: false     # keep only agents present at every frame of the part (a clip for editing
//                                 # and stitching); by default a part keeps every agent present somewhere in it
//
// Errors: no split key, both at_frame and at_time (or frames and times, or a split with a range), a frame out of
// range, an empty agent list, an unknown id or species: ConfigError (exit 2) naming the key; a part without
// agents: InputError (exit 3).
#pragma once

#include <throng/io/job_file.h>
#include <throng/stitch/jobs.h>

namespace throng::stitch {

/// Reads and checks a whole job (the schema's keys, then how they go together), then calls node.finish().
/// ConfigError naming the line. The effective job is job_file.h's.
void read_job(const ConfigNode& node, SplitJob& job);
/// Writes beside the report (stitch/jobs.h) in /parameters/throng/split: ids int64[N], the part's agents.
void write_data(const h5::Group& record, const SplitRun& part);

}  // namespace throng::stitch
