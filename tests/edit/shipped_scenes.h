// The shipped editing scene for the tests and benchmarks: the battlefield edit (configs/edit-battlefield.yaml)
// on the crowd of configs/sketch-paper.yaml, simulated with seed 1 as `throng sketch` does by default.
#pragma once

#include <throng/core/progress.h>
#include <throng/io/edit_job.h>
#include <throng/io/sketch_job.h>
#include <throng/sketch/sketch.h>

#include <filesystem>
#include <utility>

namespace throng::test {

struct ShippedEdit {
  CrowdMotion crowd;
  edit::Job job;
};

/// `source` is the project's root (tests: test_paths.h source_dir(); benchmarks: THRONG_SOURCE_DIR).
inline ShippedEdit battlefield(const std::filesystem::path& source) {
  sketch::Job sketch_job;
  sketch::read_job(ConfigNode::load_file(source / "configs" / "sketch-paper.yaml"), sketch_job);
  sketch_job.options.seed = 1;
  NoProgress quiet;
  sketch::SimulationResult simulated = sketch::simulate(sketch_job.drawing, sketch_job.scene, sketch_job.options, quiet);
  ShippedEdit shipped{std::move(simulated.motion), {}};
  edit::read_job(ConfigNode::load_file(source / "configs" / "edit-battlefield.yaml"), shipped.job);
  return shipped;
}

}  // namespace throng::test
