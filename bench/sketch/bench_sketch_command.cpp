// `throng sketch` end to end, the crowd file included: agent-steps per second of the whole command (without its
// argument parsing: the job is built here), and the share of the time spent writing the file (counter
// `write_share`). Target (issue 19): ≥ 10 M agent-steps/s at 10,000 agents on 2 cores, the file written; the
// writing at most 20 % of the time.
//
//   mode 0  before issue 19: every frame held in memory, then write_crowd_file (sketch::run + write_crowd_file)
//   mode 1  written as it goes, each full block compressed and written on the simulating thread (the command
//           before 6 December 2026)
//   mode 2  written as it goes, blocks compressed and written by a writer thread beside the simulation (the command)
//   mode 3  the frames made and dropped (the simulation and its sampling alone): the writing's cost in modes 1-2
//           is their time less this one's
// storage 0: shuffle + deflate (the default); 1: plain, the chunks unfiltered (`throng --compression none`).
//
// Counters: `write_share`, the time spent in the writing code (compressing, writing, the file's header and its
// flush to disk; in mode 2 the writer thread's busy time, which overlaps the simulation) over the command's time;
// and, in modes 1-2, `cost_share`, what the file costs the command: 1 − (the same run with its frames dropped, as
// mode 3, timed in the same iteration just before, with the benchmark's timer paused) / (the command's time), both
// summed over the repetition's iterations. (With one iteration, at 1,000,000 agents, the first repetition's dropped
// run pays the process's first touch of its memory, so its cost_share comes out low.)
//
// The crowd: N agents at 1 per m² in a square of side √N metres walking east between auxiliary lines (as
// bench_sketch's BM_Step), `seconds` of crowd time at 10 frames per second: 4 s (100 steps, 41 frames), where the
// file's fixed costs (its header, the flush to disk at the end) weigh most, and 60 s (1,500 steps, 601 frames), a
// shot's length, where the blocks written as the frames come are what remains.
//
// Run: build/<dir>/bench/sketch/bench_sketch_command --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <throng/core/communicator.h>
#include <throng/core/parallel.h>
#include <throng/core/random.h>
#include <throng/io/crowd_file.h>
#include <throng/io/crowd_stream.h>
#include <throng/io/sketch_job.h>
#include <throng/io/sketch_stream.h>
#include <throng/sketch/runner.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <numeric>
#include <unistd.h>

#include "scenes.h"

using namespace throng;
using namespace throng::sketch;

namespace {

Job square_job(std::size_t n, double seconds) {
  const double side = std::sqrt(static_cast<double>(n));
  const auto per_row = static_cast<std::size_t>(std::ceil(side));
  Job job;
  job.options.wide_distance_m = 1.0;
  job.options.narrow_distance_m = 1.0;
  job.options.resample_spacing_m = 1.0;
  job.options.duration_s = seconds;
  job.options.output_rate_hz = 10.0;
  const double length = 3 * side;  // nobody arrives during the run
  job.drawing.strokes = {scenes::straight_stroke({0, 0.5 * side}, {length, 0.5 * side}, 2, 1.3),
                         scenes::straight_stroke({0, 0}, {length, 0}, 2, 1.3),
                         scenes::straight_stroke({0, side}, {length, side}, 2, 1.3)};
  Rng rng(5);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = static_cast<double>(i % per_row) + 0.5, y = static_cast<double>(i / per_row) + 0.5;
    job.drawing.initial_positions.emplace_back(x + rng.uniform(-0.2, 0.2), y + rng.uniform(-0.2, 0.2));
  }
  return job;
}


CrowdFile file_of(Run& run) {
  CrowdFile out;
  static_cast<Crowd&>(out) = std::move(run.crowd);
  out.provenance.program_version = "bench";
  return out;
}

// Frames made and dropped (mode 3): one frame's arrays, filled again and again.
class DroppedFrames final : public FrameSink {
 public:
  void start(std::size_t agents, std::size_t, bool) override {
    positions_.assign(3 * agents, 0.0);
    orientations_.assign(4 * agents, 0.0);
    actions_.assign(agents, 0);
  }
  Frame next_frame() override { return {positions_, orientations_, actions_}; }
  void commit() override { benchmark::DoNotOptimize(positions_.data()); }

 private:
  std::vector<double> positions_, orientations_;
  std::vector<std::int32_t> actions_;
};

ExtraWriter record(const Run& run) {
  return [&run](const h5::Group& parameters) { write_data(parameters.create_group("sketch"), run); };
}

void BM_SketchCommand(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const auto mode = state.range(1);
  const CrowdStorage storage = state.range(2) == 0 ? CrowdStorage::compressed : CrowdStorage::plain;
  const Job job = square_job(n, static_cast<double>(state.range(3)));
  const ThreadLimit limit(2);
  const std::filesystem::path out =
      std::filesystem::temp_directory_path() / ("bench_sketch_command_" + std::to_string(getpid()) + ".h5");
  NoProgress quiet;
  std::size_t agent_steps = 0;
  double writing = 0, total = 0, dropped = 0;
  for (auto _ : state) {
    if (mode == 1 || mode == 2) {  // the same run without the file, outside the timed region: cost_share's baseline
      state.PauseTiming();
      DroppedFrames sink;
      const auto begin = std::chrono::steady_clock::now();
      (void)sketch::run({}, job, quiet, Communicator::single(), sink, 0.0);
      dropped += std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
      state.ResumeTiming();
    }
    const auto start = std::chrono::steady_clock::now();
    if (mode == 0) {
      Run run = sketch::run({}, job, quiet, Communicator::single());
      const auto written = std::chrono::steady_clock::now();
      agent_steps += run.result.step_count * n;
      const CrowdFile file = file_of(run);
      write_crowd_file(out, file, record(run), storage);
      writing += std::chrono::duration<double>(std::chrono::steady_clock::now() - written).count();
    } else if (mode == 3) {
      DroppedFrames sink;
      Run run = sketch::run({}, job, quiet, Communicator::single(), sink, 0.0);
      agent_steps += run.result.step_count * n;
    } else {
      SketchFileSink sink(out, mode == 2, storage);
      Run run = sketch::run({}, job, quiet, Communicator::single(), sink, 0.0);
      agent_steps += run.result.step_count * n;
      const CrowdFile file = file_of(run);
      const std::unique_ptr<CrowdStreamWriter> writer = sink.take();
      writer->finish(file, record(run));
      writing += writer->seconds_writing();
    }
    total += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  std::filesystem::remove(out);
  state.SetItemsProcessed(static_cast<std::int64_t>(agent_steps));
  state.counters["write_share"] = total > 0 ? writing / total : 0.0;
  if (mode == 1 || mode == 2) state.counters["cost_share"] = total > 0 ? 1.0 - dropped / total : 0.0;
}
BENCHMARK(BM_SketchCommand)
    ->ArgNames({"agents", "mode", "storage", "seconds"})
    ->ArgsProduct({{10000, 100000}, {0, 1, 2}, {0, 1}, {4}})
    ->Args({10000, 3, 0, 4})
    ->Args({100000, 3, 0, 4})
    ->ArgsProduct({{10000}, {1, 2, 3}, {0, 1}, {60}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_SketchCommand)
    ->ArgNames({"agents", "mode", "storage", "seconds"})
    ->ArgsProduct({{1000000}, {0, 1, 2}, {0, 1}, {4}})
    ->Args({1000000, 3, 0, 4})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
