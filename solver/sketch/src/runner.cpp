#include <throng/core/errors.h>
#include <throng/core/format.h>
#include <throng/sketch/runner.h>
#include <throng/sketch/schema.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace throng::sketch {
namespace {

double physical_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? static_cast<double>(pages) * static_cast<double>(page) : 0.0;
}

std::string frames_text(const Options& o, double frames) {
  const bool fixed = o.duration_s > 0;
  return "up to " + std::to_string(std::llround(std::min(frames, 1e18))) + " frames (" + (fixed ? "duration " : "max_duration ") +
         with_digits(fixed ? o.duration_s : o.max_duration_s, 6) + " s × output_rate " + with_digits(o.output_rate_hz, 6) +
         " Hz) of " + std::to_string(o.agent_count) + " agents";
}

std::string lower_text(const Options& o) {
  return std::string("lower output_rate, ") + (o.duration_s > 0 ? "duration" : "max_duration (or set a duration)") + " or agents.count";
}

double most_frames(const Options& o) {
  return std::floor((o.duration_s > 0 ? o.duration_s : o.max_duration_s) * o.output_rate_hz) + 1;
}

// The sketch's Run from its simulation.
Run finish_run(const Job& job, SimulationResult result) {
  Run out;
  out.result = std::move(result);
  out.crowd.motion = std::move(out.result.motion);
  out.result.motion = CrowdMotion{};
  out.crowd.scene = job.scene;
  out.drawing = job.drawing;
  for (double t : out.result.arrival_time_s) out.arrived += std::isfinite(t) ? 1 : 0;
  const std::size_t n = out.result.arrival_time_s.size();
  if (job.options.duration_s == 0 && !out.result.finished) {
    out.shortfall = std::to_string(n - out.arrived) + " of " + std::to_string(n) +
                    " agents had not reached the end of their path after max_duration = " +
                    with_digits(job.options.max_duration_s, 6) + " s (blocked by obstacles or each other?)";
  }
  if (out.result.unresolved_obstacle_contacts > 0) {
    if (!out.shortfall.empty()) out.shortfall += "; ";
    out.shortfall += std::to_string(out.result.unresolved_obstacle_contacts) +
                     " agent-steps ended overlapping an obstacle (obstacles closer together than an agent's width)";
  }
  return out;
}

}  // namespace

void describe(OptionBinder& b, Job& job) { describe(b, job.options); }

void check_memory(const Options& o, double memory) {
  const double frames = most_frames(o);
  const double bytes = frames * static_cast<double>(o.agent_count) * 72.0;  // runner.h
  if (memory <= 0 || bytes <= memory) return;
  throw ConfigError(frames_text(o, frames) + " need about " + with_digits(bytes / 1e9, 3) +
                    " GB of memory (72 bytes per agent and frame), more than this machine's " +
                    with_digits(memory / 1e9, 3) + " GB; " + lower_text(o));
}

void check_streamed_memory(const Options& o, double held_bytes, double memory) {
  const double frames = most_frames(o);
  const double bytes = frames * 16.0 + held_bytes;  // runner.h
  if (memory <= 0 || bytes <= memory) return;
  throw ConfigError(frames_text(o, frames) + " need about " + with_digits(bytes / 1e9, 3) +
                    " GB of memory while written as they go (16 bytes per frame for its time and step, and " +
                    with_digits(held_bytes / 1e9, 3) + " GB of frame blocks), more than this machine's " +
                    with_digits(memory / 1e9, 3) + " GB; " + lower_text(o));
}

Run run(const Crowds&, const Job& job, Progress& progress, const Communicator&) {
  check_memory(job.options, physical_memory_bytes());
  return finish_run(job, simulate(job.drawing, job.scene, job.options, progress));
}

Run run(const Crowds&, const Job& job, Progress& progress, const Communicator&, FrameSink& sink, double held_bytes) {
  check_streamed_memory(job.options, held_bytes, physical_memory_bytes());
  return finish_run(job, simulate(job.drawing, job.scene, job.options, sink, progress));
}

void describe(ReportWriter& w, const Run& run) {
  const CrowdMotion& m = run.crowd.motion;
  w.count("agents", m.agent_count());
  w.count("frames", m.frame_count());
  w.number("duration_s", m.frame_count() ? m.times.back() : 0.0);
  w.count("arrived", run.arrived);
  w.count("obstacles", run.crowd.scene.obstacles.size());
  if (!run.shortfall.empty()) w.text("shortfall", run.shortfall);  // what the run missed (exit 5); absent on success
}

}  // namespace throng::sketch
