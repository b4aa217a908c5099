// The scaling table and its picture: scale.csv and scale.json (one row per benchmark case) and scale.svg (time
// and memory against crowd size, log–log), written by bench_scale.
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

/// Writes dir/scale.csv, dir/scale.json and dir/scale.svg (the folder is created). Rows already in
/// dir/scale.json for other cases (name and rank count) are kept, so separate runs (a cheap sweep with
/// repetitions, the large cases once, a run under mpiexec) build one table. Series are the names up to
/// "/agents:"; x is the "agents" counter (rows without it are listed in the table only). Time panel: seconds per
/// drag, and the precompute and region build seconds; memory panel: the "memory_MB" counter.
void write_results(const std::filesystem::path& dir, std::vector<Row> rows);

}  // namespace scale
