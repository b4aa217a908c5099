// The split job (`throng split CROWD.h5 -o PART.h5 [--other REST.h5]`, or a `split` step of `throng run`) and the
// data it stores under /parameters/throng/split. Splitting by time, by agents, or both (solver/stitch/split.h).
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

#include <throng/core/crowd_motion.h>
#include <throng/io/config.h>
#include <throng/io/hdf5.h>
#include <throng/stitch/split.h>

#include <yaml-cpp/yaml.h>

#include <optional>
#include <string>

namespace throng {

struct SplitJob {
  std::optional<std::size_t> at_frame;
  std::optional<double> at_time;
  std::optional<std::array<std::size_t, 2>> frames;
  std::optional<std::array<double, 2>> times;
  bool keep_second = false;           ///< keep: second
  std::optional<stitch::AgentSelection> agents;
  bool keep_rest = false;             ///< keep_agents: rest
  bool present_throughout = false;

  [[nodiscard]] bool by_time() const noexcept { return at_frame || at_time; }
  [[nodiscard]] bool by_range() const noexcept { return frames || times; }
};

/// Reads and checks a whole job, then calls job.finish(). ConfigError naming the line.
[[nodiscard]] SplitJob read_split_job(const ConfigNode& job);

/// The job with its effective values.
[[nodiscard]] YAML::Node effective_split_job(const SplitJob& job);

/// One part of the input, as the job says; `other` takes the other half of a split by time, or the rest of a
/// split by agents (ConfigError for a job that has no single other part: a range, or time and agents together).
struct SplitPart {
  CrowdMotion crowd;
  std::size_t first_frame = 0, last_frame = 0;  ///< the input frames the part covers
  std::string part;                             ///< "first", "second", "range", "selected", "rest", or combinations
};
[[nodiscard]] SplitPart split_crowd(const CrowdMotion& input, const SplitJob& job, bool other = false);

/// Writes /parameters/throng/split: attributes first_frame, last_frame (input frames), part; dataset ids int64[N].
void write_split_data(const h5::Group& throng_parameters, const SplitPart& part);

}  // namespace throng
