// The merge job (`throng merge A.h5 B.h5 [C.h5 ...] -o OUT.h5`, or a `merge` step of `throng run` with
// `inputs: [a, b, ...]`) and the data it stores under /parameters/throng/merge. Crowds are merged in the order
// given: ((A + B) + C) + ... (solver/stitch/merge.h for the decisions: timeline, frame times, ids, scene; the
// options' schema in solver/stitch/schema.h, the runner in jobs.h).
//
// Job keys (all optional; defaults shown):
//
//   span: overlap                 # overlap: the frames every crowd shares (no overlap is an error) | union
//   on_id_clash: shift            # shift: a later crowd's ids move above the earlier ones' | error
//   join_by: none                 # none: every agent of a later crowd is another agent | id: the same id is the
//                                 #   same agent (clips of one recording joined back; merge.h)
//   join_tolerance: 1e-6          # metres: joined by id, one agent's two samples at one frame must be this close
//   time_tolerance: 1e-6          # seconds: frame times closer than this are one frame
//   max_edge_length: 0            # metres: stored formation edges longer than this are dropped (0: keep all)
//   obstacles: [...]              # added to the union of the crowds' scenes (the shared environment, e.g. a
//   region: {...}                 #   town's buildings); format in throng/io/scene_config.h
#pragma once

#include <throng/io/job_file.h>
#include <throng/stitch/jobs.h>

namespace throng::stitch {

/// The job (options and scene) is read and written by job_file.h. Writes beside the report (stitch/jobs.h) in /parameters/throng/merge: group int32[N] (the input each agent
/// comes from), interpolated_frames_by_merge int64[#inputs − 1][2] (frames interpolated in the first and the
/// second crowd of each merge).
void write_data(const h5::Group& record, const MergeRun& run);

}  // namespace throng::stitch
