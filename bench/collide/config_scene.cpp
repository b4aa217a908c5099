#include "config_scene.h"

#include <throng/core/errors.h>
#include <throng/core/progress.h>
#include <throng/io/collide_job.h>
#include <throng/io/config.h>
#include <throng/io/crowd_file.h>
#include <throng/io/merge_job.h>
#include <throng/io/sketch_job.h>
#include <throng/sketch/sketch.h>

#include <yaml-cpp/yaml.h>

#include <map>

namespace throng::bench {

namespace {

// The step's own keys: the step without the pipeline's (step, name, input, inputs, job, output).
ConfigNode step_keys(const YAML::Node& step, const std::string& source) {
  YAML::Node keys = YAML::Clone(step);
  for (const char* key : {"step", "name", "input", "inputs", "job", "output"}) keys.remove(key);
  return ConfigNode(keys, source);
}

}  // namespace

ConfigScene config_scene(const std::string& path) {
  const ConfigNode job = ConfigNode::load_file(path);
  std::map<std::string, CrowdFile> named;
  CrowdFile last;
  NoProgress quiet;
  for (const YAML::Node& step : job.yaml()["steps"]) {
    const std::string kind = step["step"].as<std::string>();
    const ConfigNode keys = step_keys(step, path);
    CrowdFile made;
    if (kind == "sketch") {
      auto sketch_job = read_job<sketch::Job>(keys);
      sketch_job.options.seed = 1;
      made.motion = sketch::simulate(sketch_job.drawing, sketch_job.scene, sketch_job.options, quiet).motion;
      made.scene = sketch_job.scene;
    } else if (kind == "merge") {
      Crowds inputs;
      for (const YAML::Node& name : step["inputs"]) inputs.push_back(&named.at(name.as<std::string>()));
      static_cast<Crowd&>(made) = stitch::run(inputs, read_job<stitch::MergeJob>(keys), quiet, Communicator::single()).crowd;
    } else if (kind == "collide") {
      const auto collide_job = read_job<collide::Job>(keys);
      ConfigScene out;
      out.crowd = last.motion;
      out.obstacles = last.scene.obstacles;
      out.obstacles.insert(out.obstacles.end(), collide_job.scene.obstacles.begin(), collide_job.scene.obstacles.end());
      out.options = collide_job.options;
      return out;
    } else {
      throw ConfigError(path + ": bench config_scene runs sketch and merge steps only, found " + kind);
    }
    if (step["name"]) named[step["name"].as<std::string>()] = made;
    last = std::move(made);
  }
  throw ConfigError(path + ": no collide step");
}

}  // namespace throng::bench
