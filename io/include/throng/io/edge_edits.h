// The `formation.edits` list of a job (edit and stitch jobs, their `throng run` steps):
//   formation:
//     edits:
//       - {add: [a, b], frames: [first, last]}    # agent ids; frames inclusive, last may be `end`
//       - {remove: [a, b]}                        # without frames: the whole clip
// What the frame indices index (the input crowd for an edit, the stitched output for a stitch) is the caller's;
// it only appears in messages.
#pragma once

#include <throng/graph/motion_graph.h>
#include <throng/io/config.h>

#include <yaml-cpp/yaml.h>

#include <string>

namespace throng {

/// Appends the job's edits to `o.edits`. Errors (ConfigError at the entry): neither or both of add/remove, not
/// two distinct agent ids, frames not [first, last|end], a negative frame (the message says frames index
/// `frames_of`), first after last.
void read_edge_edits(const ConfigNode& job, FormationOptions& o, const std::string& frames_of);

/// Writes `o.edits` as `formation.edits` into an effective job (nothing when there are none), in the form
/// read_edge_edits reads.
void write_edge_edits(YAML::Node& job, const FormationOptions& o);

}  // namespace throng
