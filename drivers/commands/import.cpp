// throng import DATASET -o OUT.h5: recorded trajectories (an ETH/UCY dataset folder or obsmat.txt, or a
// time,id,x,y,z CSV table) become a crowd file.
#include "factories.h"

#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>
#include <throng/io/config.h>
#include <throng/io/csv.h>
#include <throng/io/real_dataset.h>

#include <cmath>
#include <set>
#include <string>

namespace throng::cli {
namespace {

// A CLI11 check: a finite number > 0 (`positive`) or ≥ 0, with a message a person can read (CLI11's
// PositiveNumber and NonNegativeNumber print the largest double in full, and let NaN through).
CLI::Validator finite_number(bool positive) {
  const std::string expected = positive ? "> 0" : "≥ 0";
  return CLI::Validator(
      [positive, expected](std::string& text) -> std::string {
        double v = 0;
        std::size_t used = 0;
        try {
          v = std::stod(text, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used == 0 || used != text.size() || !std::isfinite(v) || (positive ? !(v > 0) : !(v >= 0))) {
          return "expected a finite number " + expected + ", found '" + text + "'";
        }
        return {};
      },
      "NUMBER " + expected);
}

void bind(OptionBinder& b, RealDatasetOptions& o) {
  b.field("fps", o.video_fps, Range::non_negative());
  b.field("radius", o.agent_radius, Range::non_negative());
  b.field("wall_thickness", o.wall_thickness, Range::non_negative());
}

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
    app.add_option("--fps", options_.video_fps, "Video frame rate of obsmat frame numbers (default: known per dataset)")
        ->check(finite_number(true));
    app.add_option("--radius", options_.agent_radius, "Agent radius in metres")->capture_default_str()->check(finite_number(false));
    app.add_option("--wall-thickness", options_.wall_thickness, "Thickness of map.xml walls in metres")
        ->capture_default_str()->check(finite_number(false));
  }

  void run(Context& context) override {
    YAML::Node effective;
    effective["dataset"] = input_.string();
    OptionWriter writer(effective);
    bind(writer, options_);
    if (context.print_config_if_asked(effective)) return;
    check_distinct(input_, output_);

    CrowdFile file = import_any(input_, options_);
    const Provenance source = file.provenance;
    file.provenance = context.provenance(effective, {input_.string()}, {&source});
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

  std::optional<StepResult> run_step(const ConfigNode& step, const std::vector<const CrowdFile*>&, Context&) override {
    const std::filesystem::path dataset = step.at("dataset").as_string();
    RealDatasetOptions options;
    OptionReader reader(step);
    bind(reader, options);
    step.finish();
    return StepResult{import_any(dataset, options), {}};
  }

 private:
  std::filesystem::path input_;
  std::filesystem::path output_;
  RealDatasetOptions options_;
};

}  // namespace

std::unique_ptr<Command> make_import_command() { return std::make_unique<ImportCommand>(); }

}  // namespace throng::cli
