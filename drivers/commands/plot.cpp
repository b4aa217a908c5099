// throng plot CROWD.h5 -o OUT.svg|png: trajectories, obstacles and agents at chosen frames, coloured by group,
// with a scale bar; --overlay draws another crowd underneath (before/after an edit).
#include "factories.h"

#include <throng/io/atomic_output.h>
#include <throng/io/plot.h>

namespace throng::cli {
namespace {

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
    for (long f : options_.frames) effective["frames"].push_back(f);
    effective["width"] = yaml_number(options_.width_px);
    effective["trajectories"] = options_.trajectories;
    effective["obstacles"] = options_.obstacles;
    if (context.print_config_if_asked(effective)) return;
    check_distinct(input_, output_);

    const CrowdFile file = read_crowd_file(input_);
    CrowdFile before;
    std::vector<PlotLayer> layers;
    if (!overlay_.empty()) {
      before = read_crowd_file(overlay_);
      layers.push_back({.file = &before, .label = "before: " + overlay_.filename().string(), .colour = "#9a9a9a", .opacity = 0.8, .dashed = true});
    }
    layers.push_back({.file = &file, .label = overlay_.empty() ? input_.filename().string() : "after: " + input_.filename().string()});
    if (options_.title.empty()) options_.title = input_.filename().string();
    write_plot(output_, layers, options_);
    Report r;
    r["output"] = output_.string();
    context.print(r);
  }

 private:
  std::filesystem::path input_;
  std::filesystem::path output_;
  std::filesystem::path overlay_;
  PlotOptions options_;
};

}  // namespace

std::unique_ptr<Command> make_plot_command() { return std::make_unique<PlotCommand>(); }

}  // namespace throng::cli
