#include <throng/io/command_job.h>

namespace throng {

ConfigNode command_job(const std::filesystem::path& job_file, const YAML::Node& flags, const std::vector<std::string>& set_overrides,
                       const std::string& command) {
  YAML::Node root(YAML::NodeType::Map);
  std::string source = command + " flags";
  if (!job_file.empty()) {
    const ConfigNode file = ConfigNode::load_file(job_file);
    const bool has_flags = flags.IsMap() && flags.size() > 0;
    if (!has_flags && set_overrides.empty()) return file;  // keeps the file's line numbers for messages
    if (!file.is_null()) {
      if (!file.is_map()) file.fail("a job file must hold a mapping of keys");
      root = file.yaml();
    }
    source = job_file.string();
  }
  if (flags.IsMap()) {
    for (auto it = flags.begin(); it != flags.end(); ++it) root[it->first.Scalar()] = it->second;
  }
  apply_overrides(root, set_overrides);
  return ConfigNode(root, source);
}

YAML::Node flow_numbers(const std::vector<double>& values) {
  YAML::Node n(YAML::NodeType::Sequence);
  for (double v : values) n.push_back(yaml_number(v));
  n.SetStyle(YAML::EmitterStyle::Flow);
  return n;
}

YAML::Node flow_integers(const std::vector<std::int64_t>& values) {
  YAML::Node n(YAML::NodeType::Sequence);
  for (std::int64_t v : values) n.push_back(v);
  n.SetStyle(YAML::EmitterStyle::Flow);
  return n;
}

}  // namespace throng
