// The merge job (`throng merge A.h5 B.h5 [C.h5 ...] -o OUT.h5`, or a `merge` step of `throng run` with
// `inputs: [a, b, ...]`) and the data it stores under /parameters/throng/merge. Crowds are merged in the order
// given: ((A + B) + C) + ... (solver/stitch/merge.h for the decisions: timeline, frame times, ids, scene).
//
// Job keys (all optional; defaults shown):
//
//   span: overlap                 # overlap: the frames every crowd shares (no overlap is an error) | union
//   on_id_clash: shift            # shift: a later crowd's ids move above the earlier ones' | error
//   time_tolerance: 1e-6          # seconds: frame times closer than this are one frame
//   max_edge_length: 0            # metres: stored formation edges longer than this are dropped (0: keep all)
//   obstacles: [...]              # added to the union of the crowds' scenes (the shared environment, e.g. a
//   region: {...}                 #   town's buildings); format in throng/io/scene_config.h
#pragma once

#include <throng/io/config.h>
#include <throng/io/crowd_file.h>
#include <throng/io/hdf5.h>
#include <throng/stitch/merge.h>

#include <yaml-cpp/yaml.h>

#include <vector>

namespace throng {

struct MergeJob {
  stitch::MergeOptions options;
  Scene scene;  ///< obstacles and region added to the union
};

/// Reads and checks a whole job, then calls job.finish(). ConfigError naming the line.
[[nodiscard]] MergeJob read_merge_job(const ConfigNode& job);
[[nodiscard]] YAML::Node effective_merge_job(const MergeJob& job);

/// The merged crowd file and what each merge did.
///   group      #agents: the index of the input each agent comes from
///   id_shifts  #inputs: what was added to each input's ids (0 for the first)
struct MergedCrowds {
  CrowdFile crowd;
  std::vector<std::int32_t> group;
  std::vector<std::int64_t> id_shifts;
  std::vector<stitch::MergeReport> reports;  ///< one per merge (#inputs − 1)
};

/// Merges two or more crowds in order; provenance credits of every input are kept. InputError from the merges
/// names the input ("input 3: ..."); fewer than two inputs is a ConfigError.
[[nodiscard]] MergedCrowds merge_crowds(const std::vector<const CrowdFile*>& inputs, const MergeJob& job);

/// Writes /parameters/throng/merge: group int32[N], id_shift int64[#inputs], cross_edges int64[#inputs − 1]
/// (formation edges joining the groups at the frame the edges were taken), interpolated_frames int64[#inputs − 1][2].
void write_merge_data(const h5::Group& throng_parameters, const MergedCrowds& merged);

}  // namespace throng
