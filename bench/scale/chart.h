// The scaling table and its pictures: scale.csv and scale.json (one row per benchmark case) and one
// scale-<study>.svg per study (time and memory, log–log), written by bench_scale.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace scale {

/// One benchmark case: its name ("local_drag/agents:5000"), the median seconds per iteration and its counters.
struct Row {
  std::string name;
  int ranks = 1;
  int repetitions = 1;  ///< runs the median is taken over
  double seconds = 0;
  std::map<std::string, double> values;
};

/// Writes dir/scale.csv, dir/scale.json and dir/scale-<study>.svg (the folder is created). Rows already in
/// dir/scale.json for other cases (name and rank count) are kept, so separate runs (a cheap sweep with
/// repetitions, the large cases once, runs under mpiexec -np 1 and 2) build one table. Case names are
/// "<study>/<series>/<key>:<x>": studies size (x: the "agents" counter), frames (x: "frames"), strong and weak
/// (x: the "workers" counter, ranks × threads, so runs with different rank counts join one line). Time panel:
/// seconds per drag, and the precompute and region build seconds; memory panel: "memory_max_MB" (max over
/// ranks), else "memory_MB".
void write_results(const std::filesystem::path& dir, std::vector<Row> rows);

}  // namespace scale
