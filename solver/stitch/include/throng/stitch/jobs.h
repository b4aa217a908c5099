// The clip operations as jobs: what `throng split`, `merge`, `transform` and `stitch`, their steps of `throng run`
// and library users run. Each has a job (its options schema is in schema.h, its job file in throng/io/<op>_job.h),
// a runner, and a report written with the same fields to stdout and to the output's record.
#pragma once

#include <throng/core/communicator.h>
#include <throng/core/crowd.h>
#include <throng/core/progress.h>
#include <throng/core/report.h>
#include <throng/core/schema.h>
#include <throng/stitch/merge.h>
#include <throng/stitch/split.h>
#include <throng/stitch/stitch.h>
#include <throng/stitch/transform.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace throng::stitch {

// ---------------------------------------------------------------------------------------------------- split

enum class Part { first, second };
enum class AgentPart { selected, rest };

/// Splitting by time (at a frame or time, or a range of frames or times), by agents (ids, species), or both.
struct SplitJob {
  std::optional<std::size_t> at_frame;
  std::optional<double> at_time;
  std::optional<std::vector<std::int64_t>> frames;  ///< [first, last]
  std::optional<std::vector<double>> times;         ///< [first, last], seconds
  std::optional<Part> keep;                         ///< of a split at a frame or time (default first)
  std::optional<std::vector<std::int64_t>> agents;  ///< ids
  std::optional<std::vector<std::int64_t>> species;
  std::optional<AgentPart> keep_agents;             ///< of a split by agents (default selected)
  bool present_throughout = false;

  [[nodiscard]] bool by_time() const noexcept { return at_frame || at_time; }
  [[nodiscard]] bool by_range() const noexcept { return frames || times; }
  [[nodiscard]] bool by_agents() const noexcept { return agents || species; }
};

void describe(OptionBinder& b, SplitJob& job);

/// One part of the input.
struct SplitRun {
  Crowd crowd;                                  ///< the part (the input's scene)
  std::size_t first_frame = 0, last_frame = 0;  ///< the input frames it covers
  std::string part;                             ///< "first", "second", "range", "selected", "rest", or combinations
  std::vector<std::string> warnings;
  std::string shortfall;                        ///< always empty
};

/// The part the job keeps, or with `other` the other half of a split by time or the rest of a split by agents
/// (ConfigError for a job that has no single other part: a range, or time and agents together). ConfigError for a
/// frame or an agent that does not fit the crowd; InputError for a part without agents.
[[nodiscard]] SplitRun split(const Crowd& input, const SplitJob& job, bool other = false);
/// The runner: the part the job keeps of the one crowd of `inputs` (one process).
[[nodiscard]] SplitRun run(const Crowds& inputs, const SplitJob& job, Progress& progress, const Communicator& communicator);

void describe(ReportWriter& w, const SplitRun& run);

// ---------------------------------------------------------------------------------------------------- merge

struct MergeJob {
  MergeOptions options;
  Scene scene;  ///< obstacles and region added to the union of the crowds' scenes
};

void describe(OptionBinder& b, MergeJob& job);

struct MergeRun {
  Crowd crowd;
  std::vector<std::int32_t> group;      ///< per agent, the index of the input it comes from
  std::vector<std::int64_t> id_shifts;  ///< per input, what was added to its ids (0 for the first)
  std::vector<MergeReport> reports;     ///< one per merge (#inputs − 1)
  std::size_t inputs = 0;
  std::vector<std::string> warnings, notes;
  std::string shortfall;                ///< always empty
};

/// Merges two or more crowds in order: ((A + B) + C) + ... InputError from a merge names the input; fewer than
/// two inputs is a ConfigError. One process.
[[nodiscard]] MergeRun run(const Crowds& inputs, const MergeJob& job, Progress& progress, const Communicator& communicator);

void describe(ReportWriter& w, const MergeRun& run);

// ---------------------------------------------------------------------------------------------------- transform

/// A clip placed in space and time. Degrees as given (printed back unrounded); place_at and start_time are
/// resolved against the crowd (its first frame's centroid, its first time).
struct TransformJob {
  double rotate = 0.0;                              ///< degrees, counter-clockwise about the pivot
  std::optional<std::vector<double>> pivot;         ///< [x, y]; default: the first frame's centroid
  std::optional<std::vector<double>> translate;     ///< [x, y]; default [0, 0]
  std::optional<std::vector<double>> place_at;      ///< [x, y]: the first frame's centroid goes here
  double time_scale = 1.0;
  std::optional<double> time_shift;                 ///< seconds; default 0
  std::optional<double> start_time;                 ///< the first frame's new time
  double frame_rate = 0.0;                          ///< Hz; 0 keeps the frames
  std::int64_t id_offset = 0;
  std::optional<std::int64_t> species;
};

void describe(OptionBinder& b, TransformJob& job);

/// The transform options for this crowd (place_at and start_time turned into a translation and a time shift).
[[nodiscard]] TransformOptions resolve(const TransformJob& job, const CrowdMotion& crowd);

struct TransformRun {
  Crowd crowd;
  TransformOptions applied;
  std::vector<std::string> warnings;
  std::string shortfall;  ///< always empty
};

/// Transforms the one crowd of `inputs` (one process).
[[nodiscard]] TransformRun run(const Crowds& inputs, const TransformJob& job, Progress& progress, const Communicator& communicator);

void describe(ReportWriter& w, const TransformRun& run);

// ---------------------------------------------------------------------------------------------------- stitch

struct StitchJob {
  Options options;
};

void describe(OptionBinder& b, StitchJob& job);

/// The stitched clip and one result per joint (#inputs − 1), each without its crowd (kept in `crowd`).
struct StitchRun {
  Crowd crowd;                                      ///< the first input's scene
  std::vector<Result> joints;
  std::vector<std::size_t> joint_frames;            ///< the output frame of each joint
  /// Per joint, the ids of the clip so far that took part (agents absent somewhere in their clip are left out,
  /// so a later joint may hold fewer agents than an earlier one); row k matches joints[k].second_ids.
  std::vector<std::vector<std::int64_t>> joint_ids;
  std::size_t inputs = 0;
  std::size_t max_blend_vertices = 0;
  std::vector<std::string> warnings;
  std::string shortfall;                            ///< always empty
};

/// Stitches two or more clips in order. Errors from a joint name it ("joint 2 (inputs 1..2 then input 3): ...");
/// fewer than two inputs is a ConfigError. `progress` receives each joint's progress in turn. The ranks: the petsc
/// backend shares its solves over them; with another backend every rank solves the whole problem (a warning).
[[nodiscard]] StitchRun run(const Crowds& inputs, const StitchJob& job, Progress& progress, const Communicator& communicator);

void describe(ReportWriter& w, const StitchRun& run);

}  // namespace throng::stitch
