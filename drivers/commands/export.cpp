// throng export CROWD.h5 --csv -o OUT.csv: tables for tools that read them (time,id,x,y,z).
#include "factories.h"

#include <throng/io/atomic_output.h>
#include <throng/io/csv.h>

namespace throng::cli {
namespace {

/// The one key of an export: its format.
struct ExportJob {
  std::string format = "csv";
};

void describe(OptionBinder& b, ExportJob& job) {
  b.choice({.key = "format", .help = "csv: time,id,x,y,z, one row per present agent per frame"}, job.format, {"csv"});
}

class ExportCommand final : public Command {
 public:
  std::string name() const override { return "export"; }
  std::string summary() const override { return "Write a crowd file as a time,id,x,y,z CSV table"; }

  void setup(CLI::App& app) override {
    app.add_option("crowd", input_, "Crowd file (.h5)")->required();
    app.add_flag("--csv", csv_, "CSV table time,id,x,y,z, one row per present agent per frame")->required();
    app.add_option("-o,--output", output_, "File to write")->required();
  }

  void run(Context& context) override {
    ExportJob job;
    const YAML::Node effective = context.options({}, name(), describe, job, {{"crowd", input_.string()}});
    if (context.print_config_if_asked(effective)) return;
    check_distinct(input_, output_);
    const CrowdFile file = read_crowd_file(input_);
    write_csv(output_, file.motion);
    std::size_t rows = 0;
    for (std::size_t t = 0; t < file.motion.frame_count(); ++t) {
      for (std::size_t n = 0; n < file.motion.agent_count(); ++n) rows += file.motion.present(t, n) ? 1 : 0;
    }
    Report r;
    r["output"] = output_.string();
    r["rows"] = rows;
    context.print(r);
  }

  std::optional<StepResult> run_step(const ConfigNode& step, const std::vector<const CrowdFile*>& inputs, Context& context) override {
    const std::filesystem::path output = step.at("output").as_string();
    ExportJob job;
    read_options(step, describe, job);
    step.finish();
    if (inputs.size() != 1) step.fail("export takes one crowd, found " + std::to_string(inputs.size()));
    write_csv(output, inputs.front()->motion);
    context.info("wrote " + output.string());
    return std::nullopt;
  }
  bool makes_crowd() const override { return false; }

 private:
  std::filesystem::path input_, output_;
  bool csv_ = false;
};

}  // namespace

std::unique_ptr<Command> make_export_command() { return std::make_unique<ExportCommand>(); }

}  // namespace throng::cli
