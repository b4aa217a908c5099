// A method's job file, the same way for every method: read_job fills the method's Job from a ConfigNode (then
// job.finish(): an unknown key is an error with its line), effective_job writes it back (--print-config and the
// provenance of every output), and `write_data(record, run)` stores what the method leaves beside its report in
// the output's record (every method declares one, an empty one when it stores nothing).
//
// The defaults below serve a job of options (its schema: `describe(OptionBinder&, Job&)` in the method's folder)
// and the pieces every job writes the same way: a `scene` (obstacles, region: scene_config.h) and formation edits
// (`options.formation.edits`: edge_edits.h; read by the method, which says what their frames index). A method
// whose job holds more (a request, strokes) or checks how its keys go together declares its own overloads in its
// namespace, next to its Job, in io/<method>/include/throng/io/<method>_job.h. Callers find them by the Job's
// type (argument-dependent lookup): `read_job(node, job)`.
#pragma once

#include <throng/io/config.h>
#include <throng/io/edge_edits.h>
#include <throng/io/hdf5.h>
#include <throng/io/scene_config.h>

namespace throng {

/// The options `describe` declares, then job.finish().
template <class Job>
void read_job(const ConfigNode& node, Job& job) {
  OptionReader reader(node);
  describe(reader, job);
  if constexpr (requires { job.scene = Scene{}; }) job.scene = read_scene(node);
  node.finish();
}

/// Every option at its effective value.
template <class Job>
YAML::Node effective_job(const Job& job) {
  YAML::Node out(YAML::NodeType::Map);
  Job copy = job;
  OptionWriter writer(out);
  describe(writer, copy);
  if constexpr (requires { job.scene.obstacles; }) write_scene(out, job.scene);
  if constexpr (requires { job.options.formation.edits; }) write_edge_edits(out, job.options.formation);
  return out;
}

/// A job read from `node` (the method's read_job).
template <class Job>
Job read_job(const ConfigNode& node) {
  Job job{};
  read_job(node, job);
  return job;
}

}  // namespace throng
