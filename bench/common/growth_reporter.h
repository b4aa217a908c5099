// The console reporter, plus the growth exponent of time and peak heap against the crowd's size: after the
// runs, for each benchmark family that sets the counter "individuals", the least-squares slope of log(time) and
// log(peak_heap_mb) against log(individuals) over its sizes (medians when repeated), fitted separately within
// each regime the family reports in its counter "regime" (0 flat, 1 hierarchy: one group's O(n³) against a
// tree of bounded groups), printed as
//   growth BM_Crowd, automatic hierarchy (n = 5000, 10000, 20000): time ~ n^1.05, peak heap ~ n^1.00
// (a family without the counter "regime" is printed without one: "growth methods/collide/agents (n = ...)").
// Shared by bench_formation and bench_methods (bench/scale).
#pragma once

#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace throng::bench {

class GrowthReporter : public benchmark::ConsoleReporter {
 public:
  /// Tabular, coloured on a terminal only (the library's own choice; --benchmark_color is not visible here).
  GrowthReporter() : benchmark::ConsoleReporter(isatty(fileno(stdout)) ? OO_Defaults : OO_Tabular) {}

  void ReportRuns(const std::vector<Run>& runs) override {
    benchmark::ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      const bool single = run.run_type == Run::RT_Iteration && run.repetitions <= 1;
      const bool median = run.run_type == Run::RT_Aggregate && run.aggregate_name == "median";
      if (run.error_occurred || !(single || median)) continue;
      const auto individuals = run.counters.find("individuals");
      if (individuals == run.counters.end()) continue;
      const auto heap = run.counters.find("peak_heap_mb");
      const auto regime = run.counters.find("regime");
      Point p;
      p.n = individuals->second.value;
      p.time = run.GetAdjustedRealTime();
      p.heap = heap == run.counters.end() ? 0.0 : heap->second.value;
      const int r = regime == run.counters.end() ? -1 : static_cast<int>(regime->second.value);
      series_[{run.run_name.function_name, r}].push_back(p);
    }
  }

  void Finalize() override {
    benchmark::ConsoleReporter::Finalize();
    for (const auto& [key, points] : series_) {
      if (points.size() < 2) continue;
      std::string sizes;
      for (const Point& p : points) sizes += (sizes.empty() ? "" : ", ") + std::to_string(static_cast<long>(p.n));
      std::vector<double> x, time, heap;
      for (const Point& p : points) {
        x.push_back(std::log(p.n));
        time.push_back(std::log(p.time));
        heap.push_back(std::log(std::max(p.heap, 1e-9)));
      }
      const std::string regime = key.second < 0 ? "" : key.second == 0 ? ", flat" : ", automatic hierarchy";
      std::printf("growth %s%s (n = %s): time ~ n^%.2f, peak heap ~ n^%.2f\n", key.first.c_str(), regime.c_str(),
                  sizes.c_str(), slope(x, time), slope(x, heap));
    }
    std::fflush(stdout);
  }

 private:
  struct Point {
    double n = 0, time = 0, heap = 0;
  };

  static double slope(const std::vector<double>& x, const std::vector<double>& y) {
    double mx = 0, my = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      mx += x[i] / static_cast<double>(x.size());
      my += y[i] / static_cast<double>(y.size());
    }
    double sxy = 0, sxx = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      sxy += (x[i] - mx) * (y[i] - my);
      sxx += (x[i] - mx) * (x[i] - mx);
    }
    return sxy / sxx;
  }

  std::map<std::pair<std::string, int>, std::vector<Point>> series_;
};

}  // namespace throng::bench
