// Fuzz target: every command's job reader on arbitrary bytes as a YAML job file (issue 18: "job YAML of every
// command"). The bytes are one file; each reader parses it afresh (ConfigNode::load_file: a key is used once per
// read), fills its Job (read_job: schema, scene, the method's own checks, unknown keys) and writes the effective
// job back as --print-config and every output's provenance do. Corpus: tests/fuzz/corpus/job (small jobs for each
// command) and the shipped configs (seed folder configs/, see seed-folders/job).
#include "fuzz_input.h"

#include <throng/check/schema.h>
#include <throng/io/collide_job.h>
#include <throng/io/config.h>
#include <throng/io/edit_job.h>
#include <throng/io/formation_job.h>
#include <throng/io/job_file.h>
#include <throng/io/merge_job.h>
#include <throng/io/sketch_job.h>
#include <throng/io/split_job.h>
#include <throng/io/stitch_job.h>
#include <throng/io/tiling_job.h>
#include <throng/io/timewarp_job.h>
#include <throng/io/transform_job.h>

namespace throng::fuzz {
namespace {

// Inside namespace throng, as the commands call them (drivers/method_command.h): read_job and effective_job are a
// method's own overloads (found by the Job's type) or job_file.h's templates.
template <class Job>
void read_as() {
  expect_only_throng_errors([] {
    const ConfigNode node = ConfigNode::load_file(InputFile::path());
    Job job{};
    read_job(node, job);
    (void)effective_job(job);
  });
}

}  // namespace
}  // namespace throng::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const throng::fuzz::InputFile file(data, size);
  throng::fuzz::read_as<throng::sketch::Job>();
  throng::fuzz::read_as<throng::FormationJob>();
  throng::fuzz::read_as<throng::edit::Job>();
  throng::fuzz::read_as<throng::collide::Job>();
  throng::fuzz::read_as<throng::stitch::StitchJob>();
  throng::fuzz::read_as<throng::stitch::SplitJob>();
  throng::fuzz::read_as<throng::stitch::MergeJob>();
  throng::fuzz::read_as<throng::stitch::TransformJob>();
  throng::fuzz::read_as<throng::timewarp::Job>();
  throng::fuzz::read_as<throng::TilingJob>();
  throng::fuzz::read_as<throng::check::Job>();
  return 0;
}
