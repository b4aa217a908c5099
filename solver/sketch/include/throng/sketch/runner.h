// The stroke-driven crowd as a job: what `throng sketch`, the `sketch` step of `throng run` and library users run.
// The job file's format is in throng/io/sketch_job.h.
#pragma once

#include <throng/core/communicator.h>
#include <throng/core/crowd.h>
#include <throng/core/report.h>
#include <throng/core/schema.h>
#include <throng/sketch/sketch.h>

#include <string>
#include <vector>

namespace throng::sketch {

/// What was drawn, the surroundings, and the options (the seed: the caller's, --seed for the program).
struct Job {
  Drawing drawing;
  Scene scene;
  Options options;
};

void describe(OptionBinder& b, Job& job);

/// A finished simulation.
struct Run {
  Crowd crowd;                        ///< the agents, among the job's obstacles
  Drawing drawing;                    ///< as given (stored with the output)
  SimulationResult result;            ///< course, per-agent parameters, arrival times (its motion moved to crowd)
  std::size_t arrived = 0;
  std::vector<std::string> warnings;
  std::string shortfall;              ///< agents that did not arrive, or steps that ended inside an obstacle
};

/// Refuses (ConfigError naming the keys to change) a run whose frames cannot fit in `memory_bytes`: all frames
/// are held until the file is written (per agent and frame: position 24 B, facing 32 B, action 4 B, then the
/// file's per-frame ids 8 B more: 72 B), so a run that does not fit would otherwise end in an allocation failure
/// after the whole simulation.
/// With duration 0 the bound is max_duration's frame count. memory_bytes 0: unknown, no check.
void check_memory(const Options& options, double memory_bytes);

/// The same for a run whose frames are written as they go (`throng sketch`): only their times stay in memory (8 B
/// per frame, and 8 more for the step numbers written at the end), with `held_bytes` of frame blocks the writer
/// holds whatever the frame count. With duration 0 the bound is max_duration's frame count.
void check_streamed_memory(const Options& options, double held_bytes, double memory_bytes);

/// Simulates the job (check_memory against this machine's memory first). A sketch reads no crowd (`inputs` are
/// not used) and runs on one process.
[[nodiscard]] Run run(const Crowds& inputs, const Job& job, Progress& progress, const Communicator& communicator);
/// The same with the frames handed to `sink` as they are made (check_streamed_memory with the `held_bytes` the
/// sink holds, first): the Run's crowd has no per-frame arrays (positions, orientations, actions); its times,
/// ids, radii, species and action table, and everything else, are run()'s.
[[nodiscard]] Run run(const Crowds& inputs, const Job& job, Progress& progress, const Communicator& communicator,
                      FrameSink& sink, double held_bytes);

/// The report: the same fields on stdout and in /parameters/throng/sketch.
void describe(ReportWriter& w, const Run& run);

}  // namespace throng::sketch
