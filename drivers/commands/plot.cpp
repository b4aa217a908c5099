// throng plot CROWD.h5 -o OUT.svg|png: trajectories, obstacles and agents at chosen frames, coloured by group,
// with a scale bar; --overlay draws another crowd underneath (before/after an edit).
#include "factories.h"

#include <throng/io/atomic_output.h>
#include <throng/io/config.h>
#include <throng/io/plot.h>

namespace throng::cli {
namespace {

void bind(OptionBinder& b, PlotOptions& o) {
  std::vector<double> frames(o.frames.begin(), o.frames.end());
  b.field("frames", frames);
  o.frames.assign(frames.begin(), frames.end());
  b.field("width", o.width_px, Range::closed(200, 20000));
  b.field("title", o.title);
  b.field("trajectories", o.trajectories);
  b.field("obstacles", o.obstacles);
}

/// Draws `main` over `underneath` (each in grey, dashed): the before/after picture of an edit.
void plot(const std::filesystem::path& output, const std::vector<std::pair<const CrowdFile*, std::string>>& underneath,
          const CrowdFile& main, const std::string& main_label, PlotOptions options) {
  std::vector<PlotLayer> layers;
  for (const auto& [file, label] : underneath) {
    layers.push_back({.file = file, .label = "before: " + label, .colour = "#9a9a9a", .opacity = 0.8, .dashed = true});
  }
  layers.push_back({.file = &main, .label = underneath.empty() ? main_label : "after: " + main_label});
  if (options.title.empty()) options.title = main_label;
  write_plot(output, layers, options);
}

class PlotCommand final : public Command {
 public:
  std::string name() const override { return "plot"; }
  std::string summary() const override { return "Draw a crowd file as SVG or PNG: trajectories, obstacles, agents at chosen frames"; }

  void setup(CLI::App& app) override {
    app.add_option("crowd", input_, "Crowd file (.h5)")->required();
    app.add_option("-o,--output", output_, "Picture to write: .svg, or .png (through rsvg-convert)")->required();
    app.add_option("--frames", options_.frames, "Frames where agents are drawn; negative counts from the end")
        ->delimiter(',')->capture_default_str();
    app.add_option("--overlay", overlay_, "Another crowd file drawn underneath in grey (for example the input of an edit)");
    app.add_option("--width", options_.width_px, "Picture width in pixels")->capture_default_str()->check(CLI::Range(200.0, 20000.0));
    app.add_option("--title", options_.title, "Title (default: the file name)");
    app.add_flag("!--no-trajectories", options_.trajectories, "Draw agents only");
    app.add_flag("!--no-obstacles", options_.obstacles, "Leave obstacles out");
  }

  void run(Context& context) override {
    YAML::Node effective;
    effective["crowd"] = input_.string();
    if (!overlay_.empty()) effective["overlay"] = overlay_.string();
    OptionWriter writer(effective);
    bind(writer, options_);
    if (context.print_config_if_asked(effective)) return;
    check_distinct(input_, output_);

    const CrowdFile file = read_crowd_file(input_);
    CrowdFile before;
    std::vector<std::pair<const CrowdFile*, std::string>> underneath;
    if (!overlay_.empty()) {
      before = read_crowd_file(overlay_);
      underneath.emplace_back(&before, overlay_.filename().string());
    }
    plot(output_, underneath, file, input_.filename().string(), options_);
    Report r;
    r["output"] = output_.string();
    context.print(r);
  }

  /// As a step: the last input is drawn over the others (before/after); `output` is the picture.
  std::optional<StepResult> run_step(const ConfigNode& step, const std::vector<const CrowdFile*>& inputs, Context& context) override {
    const std::filesystem::path output = step.at("output").as_string();
    PlotOptions options;
    OptionReader reader(step);
    bind(reader, options);
    step.finish();
    if (inputs.empty()) step.fail("plot needs a crowd: no earlier step made one and no input is named");
    std::vector<std::pair<const CrowdFile*, std::string>> underneath;
    for (std::size_t i = 0; i + 1 < inputs.size(); ++i) underneath.emplace_back(inputs[i], "input " + std::to_string(i + 1));
    plot(output, underneath, *inputs.back(), output.stem().string(), options);
    context.info("wrote " + output.string());
    return std::nullopt;
  }
  bool makes_crowd() const override { return false; }

 private:
  std::filesystem::path input_;
  std::filesystem::path output_;
  std::filesystem::path overlay_;
  PlotOptions options_;
};

}  // namespace

std::unique_ptr<Command> make_plot_command() { return std::make_unique<PlotCommand>(); }

}  // namespace throng::cli
