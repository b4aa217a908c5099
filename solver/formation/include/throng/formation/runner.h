// Spectral formation control as a job: what `throng formation`, the `formation` step of `throng run` and library
// users run. The job file's format is in throng/io/formation_job.h.
#pragma once

#include <throng/core/communicator.h>
#include <throng/core/crowd.h>
#include <throng/core/report.h>
#include <throng/core/schema.h>
#include <throng/formation/formation.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace throng::formation {

struct Job {
  Problem problem;
  Options options;
};

void describe(OptionBinder& b, Job& job);

/// A finished animation.
struct Run {
  Crowd crowd;            ///< the group; its formation edges: the pairs neighbours in every keyframe's graph
  Problem problem;        ///< the keyframes as animated (stored with the output)
  Result result;          ///< correspondence, hierarchy, keyframe frames and graphs (its motion moved to crowd)
  std::vector<std::string> warnings;
  std::string shortfall;  ///< individuals closer than collision.min_distance, when the collision pass could not part them
};

/// Animates the job's keyframes. The crowd made moves in the scene of the first input, when there is one (the crowd
/// the keyframes were taken from); one process.
[[nodiscard]] Run run(const Crowds& inputs, const Job& job, Progress& progress, const Communicator& communicator);

/// The neighbour relations a formation keeps: the pairs that are edges of every keyframe's graph (sorted).
[[nodiscard]] std::vector<std::array<std::int32_t, 2>> kept_edges(const Result& result);

/// The report: the same fields on stdout and in /parameters/throng/formation.
void describe(ReportWriter& w, const Run& run);

}  // namespace throng::formation
