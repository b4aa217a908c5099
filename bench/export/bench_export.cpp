// Export at scale (issue 13): a 10,000-agent × 1,000-frame crowd (25 fps, 40 s) written in every format, each
// against writing the same bytes with `cat` (the target: within 2×), with the memory the export holds.
//
// Cases: export_<format>/<agents>/<frames> writes the crowd held in memory (read once beforehand, the way a
// pipeline step hands its crowd on) to a file; xdmf_from_file reads only the .h5's layout; read_crowd is the read
// the path entry points add (peak_heap_MB there is the reader's: it holds the file's arrays and the crowd's at
// once); derive_facing the default facing alone (PathFacing::at, value by value), derive_facing_by_frame the same
// a frame at a time (PathFacing::at_frame, as the exporters ask it); cat_<format> copies that format's output with
// `cat` over its last copy, cat_durable_<format> the way the export writes (into a new file, flushed to disk,
// renamed onto the last copy), write_durable_<format> writes the same bytes from memory that way (see cat() and
// write_durable() for why all three). Every timed region starts after a sync (settle()). Counters: MB (output size),
// MB_per_s, peak_heap_MB (heap held at most during the export above what was held before: bench/common/heap.h),
// crowd_MB (the crowd's own arrays, for scale), cpu_s (CPU seconds of every thread, or of cat: on a shared
// machine the wall time measures the scheduler).
//
// The crowd: agents walking at 1.3 m/s in random directions with a slow turn, 10% entering late and 10% leaving
// early; without stored facing or actions, so every export derives them from the paths (PathFacing), as it
// does for the crowds every method writes today. Files go to $TMPDIR (default /tmp).
//
// Run:   bench_export --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
//        bench_export --benchmark_filter='/1000/100'    (a small crowd, seconds)
#include <throng/io/crowd_file.h>
#include <throng/io/export/csv_table.h>
#include <throng/io/export/gltf.h>
#include <throng/io/export/pedpy.h>
#include <throng/io/export/usd.h>
#include <throng/io/export/xdmf.h>

#include "../common/heap.h"

#include <benchmark/benchmark.h>

#include <fcntl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace throng;

std::filesystem::path folder() {
  static const std::filesystem::path dir = [] {
    const auto d = std::filesystem::temp_directory_path() / "throng_bench_export";
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

const CrowdFile& crowd(std::size_t agents, std::size_t frames) {
  static std::map<std::pair<std::size_t, std::size_t>, CrowdFile> made;
  auto [it, fresh] = made.try_emplace({agents, frames});
  if (!fresh) return it->second;
  CrowdFile& f = it->second;
  CrowdMotion& m = f.motion;
  m = CrowdMotion::with_shape(frames, agents);
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double side = std::sqrt(static_cast<double>(agents)) * 2.0;
  for (std::size_t t = 0; t < frames; ++t) m.times[t] = static_cast<double>(t) / 25.0;
  for (std::size_t n = 0; n < agents; ++n) {
    const double x0 = side * u(rng), y0 = side * u(rng), heading = 2 * M_PI * u(rng), turn = 0.2 * (u(rng) - 0.5);
    const std::size_t enter = n % 10 == 0 ? frames / 4 : 0, leave = n % 10 == 1 ? 3 * frames / 4 : frames;
    double x = x0, y = y0;
    for (std::size_t t = 0; t < frames; ++t) {
      const double h = heading + turn * m.times[t];
      x += 1.3 / 25.0 * std::cos(h);
      y += 1.3 / 25.0 * std::sin(h);
      if (t >= enter && t < leave) m.position(t, n) = Eigen::Vector3d(x, y, 0.0);
    }
  }
  Obstacle& pillar = f.scene.obstacles.emplace_back();
  pillar.shape = Circle{{side / 2, side / 2}, 1.0};
  pillar.name = "pillar";
  f.provenance.program_version = "bench";
  return f;
}

// CPU seconds (user + system) of this process's threads, or of its finished children (cat): on a shared machine
// the wall time is the share the scheduler gave, the CPU time what the work cost.
double cpu_seconds(int who) {
  struct rusage u {};
  getrusage(who, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// Writes every dirty page out before a timed region (untimed), so each case starts from the same state: without
// it a case pays for the writeback of the gigabytes the cases before it wrote (the kernel throttles writers once
// dirty pages pass its threshold), and a case's time depended on its place in the run.
void settle() { ::sync(); }

// A file for this case's size: out_<agents>_<frames><extension>.
std::filesystem::path sized(const benchmark::State& state, const std::string& stem, const std::string& extension) {
  return folder() / (stem + "_" + std::to_string(state.range(0)) + "_" + std::to_string(state.range(1)) + extension);
}

double crowd_mb(const CrowdFile& f) {
  return static_cast<double>(f.motion.positions.size() * 8 + f.motion.ids.size() * 24) / (1 << 20);
}

void report(benchmark::State& state, const std::filesystem::path& output, double seconds, double peak, double cpu) {
  const double mb = static_cast<double>(std::filesystem::file_size(output)) / (1 << 20);
  state.counters["MB"] = mb;
  state.counters["MB_per_s"] = mb / seconds;
  state.counters["peak_heap_MB"] = peak;
  state.counters["cpu_s"] = cpu;
}

template <class Export>
void run(benchmark::State& state, const char* extension, Export export_to) {
  const CrowdFile& f = crowd(static_cast<std::size_t>(state.range(0)), static_cast<std::size_t>(state.range(1)));
  const auto output = sized(state, "out", extension);
  double seconds = 0, peak = 0, cpu = 0;
  for (auto _ : state) {
    state.PauseTiming();
    settle();
    state.ResumeTiming();
    bench::HeapPeak heap;
    const double cpu0 = cpu_seconds(RUSAGE_SELF);
    const auto start = std::chrono::steady_clock::now();
    export_to(f, output);
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    cpu = cpu_seconds(RUSAGE_SELF) - cpu0;
    peak = heap.stop();
    state.SetIterationTime(seconds);
  }
  report(state, output, seconds, peak, cpu);
  state.counters["crowd_MB"] = crowd_mb(f);
}

// A baseline's timing: body() once per iteration, each after a settle(), with the CPU of `who` (RUSAGE_SELF, or
// RUSAGE_CHILDREN for the programs body runs); body returns false on failure. Reports `output`'s size.
template <class Body>
void time_baseline(benchmark::State& state, const std::filesystem::path& output, int who, const char* failure, Body body) {
  double seconds = 0, cpu = 0;
  for (auto _ : state) {
    state.PauseTiming();
    settle();
    state.ResumeTiming();
    const double cpu0 = cpu_seconds(who);
    const auto start = std::chrono::steady_clock::now();
    const bool ok = body();
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    cpu = cpu_seconds(who) - cpu0;
    if (!ok) state.SkipWithError(failure);
    state.SetIterationTime(seconds);
  }
  report(state, output, seconds, 0, cpu);
}

// `cat` copies a format's output (made by its export case first). Plain (cat_<format>): over its last copy in
// place (`>` truncates it first, and the kernel hands the freed page-cache pages straight back), the issue's
// baseline. durable (cat_durable_<format>): the way every export writes, into a new file beside the target,
// flushed to disk, renamed onto it (`cat F > T.tmp && sync T.tmp && mv T.tmp T`): the flush is what lets a
// machine that loses power keep the previous output or the new one, never half a file (AtomicOutput::commit).
void cat(benchmark::State& state, const char* extension, bool durable) {
  const auto input = sized(state, "out", extension);
  const auto output = sized(state, durable ? "cat_durable" : "cat", extension);
  if (!std::filesystem::exists(input)) {
    state.SkipWithError("run the export case first: its output is what cat copies");
    return;
  }
  const std::string temporary = output.string() + ".tmp";
  const std::string command = durable ? "cat '" + input.string() + "' > '" + temporary + "' && sync '" + temporary + "' && mv '" +
                                            temporary + "' '" + output.string() + "'"
                                      : "cat '" + input.string() + "' > '" + output.string() + "'";
  time_baseline(state, output, RUSAGE_CHILDREN, "cat failed", [&] { return std::system(command.c_str()) == 0; });
}

// The floor for a program that makes its bytes (write_durable_<format>): a format's output, held in memory (read
// untimed), written with write(2) in 8 MiB pieces into a new file, flushed and renamed onto its last copy, as
// the exports write. `cat` does not pass its bytes through a process: coreutils 9 copies a regular file with
// copy_file_range, in the kernel, which costs a half to a third of writing the same bytes from memory here (274 MB
// after a sync: cat 0.05 s, dd with 8 MiB blocks 0.12 s, with 128 KiB blocks 0.25 s).
void write_durable(benchmark::State& state, const char* extension) {
  const auto input = sized(state, "out", extension);
  const auto output = sized(state, "write_durable", extension);
  if (!std::filesystem::exists(input)) {
    state.SkipWithError("run the export case first: its output is what is written");
    return;
  }
  std::vector<char> bytes(std::filesystem::file_size(input));
  {
    std::FILE* in = std::fopen(input.c_str(), "rb");
    const bool read = in && std::fread(bytes.data(), 1, bytes.size(), in) == bytes.size();
    if (in) std::fclose(in);
    if (!read) {
      state.SkipWithError("cannot read the export's output");
      return;
    }
  }
  const std::string temporary = output.string() + ".tmp";
  time_baseline(state, output, RUSAGE_SELF, "write failed", [&] {
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    bool ok = fd >= 0;
    for (std::size_t at = 0; ok && at < bytes.size();) {
      const ssize_t n = ::write(fd, bytes.data() + at, std::min<std::size_t>(8 << 20, bytes.size() - at));
      ok = n > 0;
      at += ok ? static_cast<std::size_t>(n) : 0;
    }
    ok = ok && ::fsync(fd) == 0;
    return fd >= 0 && ::close(fd) == 0 && ok && std::rename(temporary.c_str(), output.c_str()) == 0;
  });
}

void export_csv_case(benchmark::State& s) { run(s, ".csv", [](const CrowdFile& f, const auto& o) { export_csv(f, o); }); }
void export_gltf_case(benchmark::State& s) { run(s, ".glb", [](const CrowdFile& f, const auto& o) { export_gltf(f, o); }); }
void export_usd_case(benchmark::State& s) { run(s, ".usda", [](const CrowdFile& f, const auto& o) { export_usd(f, o); }); }
void export_pedpy_case(benchmark::State& s) { run(s, ".pedpy.h5", [](const CrowdFile& f, const auto& o) { export_pedpy(f, o); }); }
void xdmf_from_file(benchmark::State& s) {
  const auto crowd_file = sized(s, "crowd", ".h5");
  const CrowdFile& f = crowd(static_cast<std::size_t>(s.range(0)), static_cast<std::size_t>(s.range(1)));
  if (!std::filesystem::exists(crowd_file)) write_crowd_file(crowd_file, f);  // not timed: the input
  run(s, ".xmf", [&](const CrowdFile&, const auto& o) { export_xdmf(crowd_file, o); });
}
void read_crowd(benchmark::State& s) {
  const auto crowd_file = sized(s, "crowd", ".h5");
  write_crowd_file(crowd_file, crowd(static_cast<std::size_t>(s.range(0)), static_cast<std::size_t>(s.range(1))));
  double seconds = 0, peak = 0, cpu = 0;
  for (auto _ : s) {
    bench::HeapPeak heap;
    const double cpu0 = cpu_seconds(RUSAGE_SELF);
    const auto start = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(read_crowd_file(crowd_file));
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    cpu = cpu_seconds(RUSAGE_SELF) - cpu0;
    peak = heap.stop();
    s.SetIterationTime(seconds);
  }
  report(s, crowd_file, seconds, peak, cpu);
}
// The default facing alone (PathFacing over every agent and frame, in frame order as the text formats ask).
void derive_facing(benchmark::State& s) {
  const CrowdFile& f = crowd(static_cast<std::size_t>(s.range(0)), static_cast<std::size_t>(s.range(1)));
  for (auto _ : s) {
    const auto start = std::chrono::steady_clock::now();
    PathFacing facing(f.motion);
    double sum = 0;
    for (std::size_t t = 0; t < f.motion.frame_count(); ++t) {
      for (std::size_t n = 0; n < f.motion.agent_count(); ++n) sum += facing.at(t, n).w();
    }
    benchmark::DoNotOptimize(sum);
    s.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
}
// The same a frame at a time (PathFacing::at_frame, as the exporters ask it): the same values.
void derive_facing_by_frame(benchmark::State& s) {
  const CrowdFile& f = crowd(static_cast<std::size_t>(s.range(0)), static_cast<std::size_t>(s.range(1)));
  std::vector<Eigen::Quaterniond> row(f.motion.agent_count());
  for (auto _ : s) {
    const auto start = std::chrono::steady_clock::now();
    PathFacing facing(f.motion);
    double sum = 0;
    for (std::size_t t = 0; t < f.motion.frame_count(); ++t) {
      facing.at_frame(t, 0, f.motion.agent_count(), row.data());
      for (const Eigen::Quaterniond& q : row) sum += q.w();
    }
    benchmark::DoNotOptimize(sum);
    s.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
}
void cat_csv(benchmark::State& s) { cat(s, ".csv", false); }
void cat_gltf(benchmark::State& s) { cat(s, ".glb", false); }
void cat_usd(benchmark::State& s) { cat(s, ".usda", false); }
void cat_pedpy(benchmark::State& s) { cat(s, ".pedpy.h5", false); }
void cat_durable_csv(benchmark::State& s) { cat(s, ".csv", true); }
void cat_durable_gltf(benchmark::State& s) { cat(s, ".glb", true); }
void cat_durable_usd(benchmark::State& s) { cat(s, ".usda", true); }
void cat_durable_pedpy(benchmark::State& s) { cat(s, ".pedpy.h5", true); }
void write_durable_csv(benchmark::State& s) { write_durable(s, ".csv"); }
void write_durable_gltf(benchmark::State& s) { write_durable(s, ".glb"); }
void write_durable_usd(benchmark::State& s) { write_durable(s, ".usda"); }
void write_durable_pedpy(benchmark::State& s) { write_durable(s, ".pedpy.h5"); }

#define THRONG_EXPORT_SIZES ->Args({1000, 100})->Args({10000, 1000})->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(1)
BENCHMARK(export_gltf_case) THRONG_EXPORT_SIZES;
BENCHMARK(cat_gltf) THRONG_EXPORT_SIZES;
BENCHMARK(cat_durable_gltf) THRONG_EXPORT_SIZES;
BENCHMARK(write_durable_gltf) THRONG_EXPORT_SIZES;
BENCHMARK(export_usd_case) THRONG_EXPORT_SIZES;
BENCHMARK(cat_usd) THRONG_EXPORT_SIZES;
BENCHMARK(cat_durable_usd) THRONG_EXPORT_SIZES;
BENCHMARK(write_durable_usd) THRONG_EXPORT_SIZES;
BENCHMARK(export_pedpy_case) THRONG_EXPORT_SIZES;
BENCHMARK(cat_pedpy) THRONG_EXPORT_SIZES;
BENCHMARK(cat_durable_pedpy) THRONG_EXPORT_SIZES;
BENCHMARK(write_durable_pedpy) THRONG_EXPORT_SIZES;
BENCHMARK(export_csv_case) THRONG_EXPORT_SIZES;
BENCHMARK(cat_csv) THRONG_EXPORT_SIZES;
BENCHMARK(cat_durable_csv) THRONG_EXPORT_SIZES;
BENCHMARK(write_durable_csv) THRONG_EXPORT_SIZES;
BENCHMARK(xdmf_from_file) THRONG_EXPORT_SIZES;
BENCHMARK(read_crowd) THRONG_EXPORT_SIZES;
BENCHMARK(derive_facing) THRONG_EXPORT_SIZES;
BENCHMARK(derive_facing_by_frame) THRONG_EXPORT_SIZES;

}  // namespace
