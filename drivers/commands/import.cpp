// throng import DATA -o OUT.h5: recorded trajectories, in any format import_crowd tells by content (ETH/UCY,
// frame id x y, PeTrack, CSV, PedPy HDF5, crowd files), become a crowd file. The options' schema is io/data_options.h; docs/commands/import.md
// is the README section.
#include "../option_flags.h"
#include "factories.h"

#include <throng/io/atomic_output.h>
#include <throng/io/data_options.h>
#include <throng/io/import_crowd.h>

#include <set>

namespace throng::cli {
namespace {

class ImportCommand final : public Command {
 public:
  std::string name() const override { return "import"; }
  std::string summary() const override {
    return "Turn recorded trajectories (ETH/UCY, frame id x y, PeTrack, CSV, PedPy HDF5; told by content) into a crowd file";
  }

  void setup(CLI::App& app) override {
    app.add_option("dataset", input_, "Recorded data: a file, or a dataset folder holding obsmat.txt")->required();
    app.add_option("-o,--output", output_, "Crowd file to write (.h5)")->required();
    flags_.add(app, static_cast<void (*)(OptionBinder&, ImportOptions&)>(describe));
  }

  void run(Context& context) override {
    ImportOptions options;
    const YAML::Node effective = context.options(flags_.overrides(), name(), describe, options, {{"dataset", input_.string()}});
    if (context.print_config_if_asked(effective)) return;
    check_distinct(input_, output_);

    ImportedCrowd imported = import_crowd(input_, options);
    CrowdFile& file = imported.crowd;
    file.provenance = context.provenance(effective, {input_.string()}, file.provenance.credits);
    write_crowd_file(output_, file, {}, context.global.storage);

    const CrowdMotion& m = file.motion;
    std::set<std::int32_t> groups(m.species.begin(), m.species.end());
    groups.erase(0);
    Report r;
    r["output"] = output_.string();
    r["format"] = format_name(imported.format);
    r["agents"] = m.agent_count();
    r["frames"] = m.frame_count();
    r["duration_s"] = m.frame_count() ? m.times.back() - m.times.front() : 0.0;
    r["walking_groups"] = groups.size();
    r["obstacles"] = file.scene.obstacles.size();
    if (!file.provenance.credits.empty()) r["credit"] = file.provenance.credits;
    if (!imported.notes.empty()) r["notes"] = imported.notes;
    context.print(r);
  }

  /// As a step: `dataset` and `obstacles` (relative to the job file's folder) and the options' keys.
  std::optional<StepResult> run_step(const ConfigNode& step, const std::vector<const CrowdFile*>&, Context&) override {
    const std::filesystem::path dataset = step.at("dataset").as_path();
    ImportOptions options;
    read_options(step, describe, options);
    if (step.has("obstacles")) options.obstacles = step.at("obstacles").as_path();
    step.finish();
    return StepResult{import_crowd(dataset, options).crowd, {}};
  }

 private:
  std::filesystem::path input_, output_;
  OptionFlags flags_;
};

}  // namespace

std::unique_ptr<Command> make_import_command() { return std::make_unique<ImportCommand>(); }

}  // namespace throng::cli
