// throng import DATASET -o OUT.h5: recorded trajectories (an ETH/UCY dataset folder or obsmat.txt, or a
// time,id,x,y,z CSV table) become a crowd file. The options' schema is io/data_options.h; docs/commands/import.md
// is the README section.
#include "../option_flags.h"
#include "factories.h"

#include <throng/io/atomic_output.h>
#include <throng/io/csv.h>
#include <throng/io/data_options.h>

#include <set>

namespace throng::cli {
namespace {

/// Reads a dataset folder, obsmat.txt or CSV table.
CrowdFile import_any(const std::filesystem::path& input, const RealDatasetOptions& options) {
  if (input.extension() != ".csv") return import_real_dataset(input, options);
  CrowdFile file;
  file.motion = read_csv(input, options.agent_radius);
  file.provenance.inputs.push_back(input.string());
  return file;
}

class ImportCommand final : public Command {
 public:
  std::string name() const override { return "import"; }
  std::string summary() const override {
    return "Turn recorded trajectories (ETH/UCY folder with obsmat.txt, map.xml, groups.txt; or a CSV table) into a crowd file";
  }

  void setup(CLI::App& app) override {
    app.add_option("dataset", input_, "Dataset folder, its obsmat.txt, or a time,id,x,y,z .csv file")->required();
    app.add_option("-o,--output", output_, "Crowd file to write (.h5)")->required();
    flags_.add(app, static_cast<void (*)(OptionBinder&, RealDatasetOptions&)>(describe));
  }

  void run(Context& context) override {
    RealDatasetOptions options;
    const YAML::Node effective = context.options(flags_.overrides(), name(), describe, options, {{"dataset", input_.string()}});
    if (context.print_config_if_asked(effective)) return;
    check_distinct(input_, output_);

    CrowdFile file = import_any(input_, options);
    file.provenance = context.provenance(effective, {input_.string()}, file.provenance.credits);
    write_crowd_file(output_, file);

    const CrowdMotion& m = file.motion;
    std::set<std::int32_t> groups(m.species.begin(), m.species.end());
    groups.erase(0);
    Report r;
    r["output"] = output_.string();
    r["agents"] = m.agent_count();
    r["frames"] = m.frame_count();
    r["duration_s"] = m.frame_count() ? m.times.back() - m.times.front() : 0.0;
    r["walking_groups"] = groups.size();
    r["obstacles"] = file.scene.obstacles.size();
    if (!file.provenance.credits.empty()) r["credit"] = file.provenance.credits;
    context.print(r);
  }

  /// As a step: `dataset` (relative to the job file's folder) and the options' keys.
  std::optional<StepResult> run_step(const ConfigNode& step, const std::vector<const CrowdFile*>&, Context&) override {
    const std::filesystem::path dataset = step.at("dataset").as_path();
    RealDatasetOptions options;
    read_options(step, describe, options);
    step.finish();
    return StepResult{import_any(dataset, options), {}};
  }

 private:
  std::filesystem::path input_, output_;
  OptionFlags flags_;
};

}  // namespace

std::unique_ptr<Command> make_import_command() { return std::make_unique<ImportCommand>(); }

}  // namespace throng::cli
