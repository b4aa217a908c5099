// throng sketch JOB.yaml -o OUT.h5: a crowd from a few drawn strokes (stroke-driven crowds, solver/sketch/runner.h).
// The job format is in io/sketch/include/throng/io/sketch_job.h; docs/commands/sketch.md is the README section.
// Agents that do not arrive within max_duration (or steps that end inside an obstacle): the crowd and the report
// (with a `shortfall` field) are written, then exit 5; as a step of `throng run`, a warning.
//
// The command writes the crowd file as the simulation goes (io/crowd_stream.h): the frames go to the file's
// temporary block by block, and write() below adds the rest (provenance, scene, record) and moves it into place,
// so memory does not grow with the frame count. As a step of `throng run` the crowd stays in memory (the next
// step reads it).
#include "../method_command.h"
#include "factories.h"

#include <throng/io/crowd_stream.h>
#include <throng/io/sketch_stream.h>
#include <throng/io/sketch_job.h>

#include <memory>
#include <numeric>

namespace throng::cli {
namespace {

// Full blocks compressed and written on a writer thread beside the simulation (true) or on the simulating thread
// (false). Measured on 2 cores (docs/commands/sketch.md, "A writer thread again"): with zlib the compression kept
// both cores busy and a writer thread gained nothing; with today's compression it fills the moments the
// simulation's steps leave a core idle: 5-11 % faster with deflate at 10,000 and 100,000 agents, 8-31 % without
// compression, the same at 1,000,000 (and its first repetition 12-19 % faster), for a second block per dataset
// (16 MB more at 10,000 agents, 136 MB at 1,000,000).
constexpr bool write_in_background = true;


// The writer of a command's run, from its runner hook to write(); none in a step.
struct Streamed {
  std::unique_ptr<CrowdStreamWriter> writer;
};

using Method = MethodCommand<sketch::Job>;

class SketchCommand final : public Method {
 public:
  SketchCommand(MethodSpec spec, Hooks hooks, std::shared_ptr<Streamed> streamed)
      : Method(spec, std::move(hooks)), streamed_(std::move(streamed)) {}

  void run(Context& context) override {
    try {
      Method::run(context);
    } catch (...) {
      streamed_->writer.reset();  // a failure before the file was finished: its temporary goes
      throw;
    }
    streamed_->writer.reset();
  }

 protected:
  void write(const CrowdFile& out, const ExtraWriter& record, const sketch::Run& run, Context& context) override {
    if (!streamed_->writer) return Method::write(out, record, run, context);
    const std::unique_ptr<CrowdStreamWriter> writer = std::move(streamed_->writer);
    writer->finish(out, record);
  }

 private:
  std::shared_ptr<Streamed> streamed_;
};

}  // namespace

std::unique_ptr<Command> make_sketch_command() {
  auto streamed = std::make_shared<Streamed>();
  return std::make_unique<SketchCommand>(
      MethodSpec{
          .name = "sketch",
          .summary = "Make a crowd from drawn strokes: a timed main line (path, speed) and auxiliary lines (spread, irregularity)",
          .job = JobArgument::positional, .job_help = "Sketch job (.yaml): strokes, agents, options, obstacles",
          .inputs = {.count_text = "sketch reads no crowd"}, .output_help = "Crowd file to write (.h5)"},
      Method::Hooks{.run = [streamed](const Crowds& in, sketch::Job& job, MethodRun& r) {
        try {
          // A step of `throng run` (no output of its own) and ranks other than the writer keep the crowd in memory.
          if (r.output.empty() || !r.context.writer()) return sketch::run(in, job, r.progress(), r.communicator());
          SketchFileSink sink(r.output, write_in_background, r.context.global.storage);
          const std::size_t agents =
              job.drawing.initial_positions.empty() ? job.options.agent_count : job.drawing.initial_positions.size();
          sketch::Run out = sketch::run(in, job, r.progress(), r.communicator(), sink,
                                        static_cast<double>(CrowdStreamWriter::held_bytes(agents, write_in_background)));
          streamed->writer = sink.take();
          return out;
        } catch (const ConfigError& e) {
          throw ConfigError(r.where + ": " + e.what());  // the memory check before the simulation names the job
        }
      }},
      streamed);
}

}  // namespace throng::cli
