// throng export CROWD.h5 --format F [-o OUT]: a crowd file as the files other tools open (xdmf for ParaView, gltf
// for Blender and every DCC, usd for Solaris/Golaem/Omniverse, pedpy for PedPy, csv tables), through io/export's
// export_crowd. The request's schema (format, pose thresholds, pedpy's walkable area) is
// io/export/include/throng/io/export/request.h; docs/commands/export.md is the README section.
#include "../option_flags.h"
#include "factories.h"

#include <throng/core/errors.h>
#include <throng/io/export/format.h>
#include <throng/io/export/request.h>

namespace throng::cli {
namespace {

/// What the command and the step print: the files written and the crowd's size.
Report summary_report(ExportFormat format, const ExportSummary& s) {
  Report r;
  r["output"] = s.files.front().string();
  r["format"] = export_format_names()[static_cast<std::size_t>(format)];
  std::vector<std::string> files;
  for (const auto& f : s.files) files.push_back(f.string());
  r["files"] = files;
  r["agents"] = s.agents;
  r["frames"] = s.frames;
  if (format == ExportFormat::csv || format == ExportFormat::pedpy) r["rows"] = s.rows;
  return r;
}

class ExportCommand final : public Command {
 public:
  std::string name() const override { return "export"; }
  std::string summary() const override {
    return "Write a crowd file for other tools: xdmf (ParaView), gltf (Blender, DCCs), usd (Solaris), pedpy (PedPy), csv";
  }

  void setup(CLI::App& app) override {
    app.add_option("crowd", input_, "Crowd file (.h5)")->required();
    app.add_option("-o,--output", output_,
                   "File to write (default: beside the crowd, its name with the format's extension; "
                   "pedpy: NAME.pedpy.h5)");
    flags_.add(app, static_cast<void (*)(OptionBinder&, ExportRequest&)>(describe));
  }

  void run(Context& context) override {
    ExportRequest request;
    const YAML::Node effective = context.options(flags_.overrides(), name(), describe, request,
                                                 {{"crowd", input_.string()}, {"output", output_.string()}});
    if (context.print_config_if_asked(effective)) return;
    std::filesystem::path output = output_;
    if (output.empty()) {
      if (request.format.empty()) {
        throw ConfigError("export: give --format (" + join_export_format_names() + ") or an output file (-o)");
      }
      output = default_export_output(parse_export_format(request.format), input_);
    }
    const ExportFormat format = resolve_format(request, output);
    const ExportSummary s = export_crowd(format, input_, output, request.options, pedpy_options(request));
    context.print(summary_report(format, s));
  }

  /// As a step: `output` (required; relative to the working folder) and the request's keys. The crowd is the
  /// step's input, held in memory (xdmf, which points into a crowd file, is refused: export the written file).
  std::optional<StepResult> run_step(const ConfigNode& step, const std::vector<const CrowdFile*>& inputs, Context& context) override {
    const std::filesystem::path output = step.at("output").as_string();
    ExportRequest request;
    read_options(step, describe, request);
    step.finish();
    if (inputs.size() != 1) step.fail("export takes one crowd, found " + std::to_string(inputs.size()));
    const ExportFormat format = resolve_format(request, output);
    const ExportSummary s = export_crowd(format, *inputs.front(), output, request.options, pedpy_options(request));
    std::string files;
    for (const auto& f : s.files) files += (files.empty() ? "" : ", ") + f.string();
    context.info("wrote " + files);
    return std::nullopt;
  }
  bool makes_crowd() const override { return false; }

 private:
  std::filesystem::path input_, output_;
  OptionFlags flags_;
};

}  // namespace

std::unique_ptr<Command> make_export_command() { return std::make_unique<ExportCommand>(); }

}  // namespace throng::cli
