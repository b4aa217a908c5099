// throng plot CROWD.h5 -o OUT.svg|png: trajectories, obstacles and agents at chosen frames, coloured by group,
// with a scale bar; --overlay draws another crowd underneath (before/after an edit). A file written by
// `throng tile` is drawn as its tiling (io/tiling_plot.h: patches coloured by type, connections marked) unless
// --no-tiling.
#include "factories.h"

#include <throng/io/atomic_output.h>
#include <throng/io/config.h>
#include <throng/io/plot.h>
#include <throng/io/tiling_plot.h>

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
  b.field("min_agent_radius", o.min_agent_radius_px, Range::closed(0, 100));
}

/// The view of 3-D crowds: top (x, y; the default), front (x, z: looking north, +y) or side (y, z: looking
/// west, −x). Front and side views map the chosen axes onto the picture's and leave the ground-plane scene out.
void bind_view(OptionBinder& b, std::string& view) { b.choice("view", view, {"top", "front", "side"}); }

CrowdFile projected(const CrowdFile& file, const std::string& view) {
  CrowdFile out = file;
  if (view == "top") return out;
  const int u = view == "front" ? 0 : 1;
  for (std::size_t k = 0; k + 2 < out.motion.positions.size(); k += 3) {
    const double a = file.motion.positions[k + static_cast<std::size_t>(u)], z = file.motion.positions[k + 2];
    out.motion.positions[k] = a;
    out.motion.positions[k + 1] = z;
    out.motion.positions[k + 2] = 0.0;
  }
  out.motion.velocities.clear();
  out.scene = Scene{};
  return out;
}

/// Draws `main` over `underneath` (each in grey, dashed): the before/after picture of an edit.
/// `tiling`, when given, is the tiling `main` was made from: drawn instead of the plain trajectories.
void plot(const std::filesystem::path& output, const std::vector<std::pair<const CrowdFile*, std::string>>& underneath,
          const CrowdFile& main, const std::string& main_label, PlotOptions options, const TilingData* tiling = nullptr) {
  std::vector<PlotLayer> layers;
  for (const auto& [file, label] : underneath) {
    layers.push_back({.file = file, .label = "before: " + label, .colour = "#9a9a9a", .opacity = 0.8, .dashed = true});
  }
  layers.push_back({.file = &main, .label = underneath.empty() ? main_label : "after: " + main_label});
  if (tiling) add_tiling(layers.back(), *tiling);
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
    app.add_option("--view", view_, "3-D crowds: top (x, y), front (x, z) or side (y, z)")
        ->capture_default_str()->check(CLI::IsMember({"top", "front", "side"}));
    app.add_option("--min-agent-radius", options_.min_agent_radius_px, "Smallest agent disc radius in pixels")
        ->capture_default_str()->check(CLI::Range(0.0, 100.0));
    app.add_flag("!--no-tiling", tiling_, "A file written by throng tile: draw plain trajectories, not the patches");
  }

  void run(Context& context) override {
    YAML::Node effective;
    effective["crowd"] = input_.string();
    if (!overlay_.empty()) effective["overlay"] = overlay_.string();
    OptionWriter writer(effective);
    bind(writer, options_);
    bind_view(writer, view_);
    effective["tiling"] = tiling_;
    if (context.print_config_if_asked(effective)) return;
    check_distinct(input_, output_);

    const CrowdFile file = projected(read_crowd_file(input_), view_);
    std::optional<TilingData> tiling;
    if (tiling_ && view_ == "top" && has_tiling_data(input_)) tiling = read_tiling_data(input_);
    CrowdFile before;
    std::vector<std::pair<const CrowdFile*, std::string>> underneath;
    if (!overlay_.empty()) {
      before = projected(read_crowd_file(overlay_), view_);
      underneath.emplace_back(&before, overlay_.filename().string());
    }
    plot(output_, underneath, file, input_.filename().string(), options_, tiling ? &*tiling : nullptr);
    Report r;
    r["output"] = output_.string();
    r["tiling"] = tiling.has_value();
    context.print(r);
  }

  /// As a step: the last input is drawn over the others (before/after); `output` is the picture.
  std::optional<StepResult> run_step(const ConfigNode& step, const std::vector<const CrowdFile*>& inputs, Context& context) override {
    const std::filesystem::path output = step.at("output").as_string();
    PlotOptions options;
    std::string view = "top";
    OptionReader reader(step);
    bind(reader, options);
    bind_view(reader, view);
    step.finish();
    if (inputs.empty()) step.fail("plot needs a crowd: no earlier step made one and no input is named");
    std::vector<CrowdFile> views;
    views.reserve(inputs.size());
    for (const CrowdFile* c : inputs) views.push_back(projected(*c, view));
    std::vector<std::pair<const CrowdFile*, std::string>> underneath;
    for (std::size_t i = 0; i + 1 < inputs.size(); ++i) underneath.emplace_back(&views[i], "input " + std::to_string(i + 1));
    plot(output, underneath, views.back(), output.stem().string(), options);
    context.info("wrote " + output.string());
    return std::nullopt;
  }
  bool makes_crowd() const override { return false; }

 private:
  std::filesystem::path input_;
  std::filesystem::path output_;
  std::filesystem::path overlay_;
  PlotOptions options_;
  std::string view_ = "top";
  bool tiling_ = true;
};

}  // namespace

std::unique_ptr<Command> make_plot_command() { return std::make_unique<PlotCommand>(); }

}  // namespace throng::cli
