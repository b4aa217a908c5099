// throng plot CROWD.h5 -o OUT.svg|png|gif|mp4: trajectories, obstacles and agents at chosen frames, coloured by
// group, with a scale bar, or an animated preview of the agents moving (io/src/plot_animation.h); --overlay draws
// another crowd underneath (before/after an edit). A file written by
// `throng tile` is drawn as its tiling (io/tiling_plot.h: patches coloured by type, connections marked) unless
// --no-tiling. The options' schema is io/data_options.h (PlotJob).
#include "../option_flags.h"
#include "factories.h"

#include <throng/io/atomic_output.h>
#include <throng/io/data_options.h>
#include <throng/io/tiling_plot.h>

namespace throng::cli {
namespace {

/// The crowd seen from `view`: front and side views map the chosen axes onto the picture's and leave the
/// ground-plane scene out.
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

/// Draws the last crowd over the others (each in grey, dashed): the before/after picture of an edit. `tiling`,
/// when given, is the tiling the last crowd was made from: drawn instead of its plain trajectories.
void plot(const std::filesystem::path& output, const std::vector<const CrowdFile*>& crowds, const std::vector<std::string>& labels,
          const PlotJob& job, const TilingData* tiling = nullptr) {
  std::vector<CrowdFile> views;
  for (const CrowdFile* c : crowds) views.push_back(projected(*c, job.view));
  std::vector<PlotLayer> layers;
  for (std::size_t i = 0; i + 1 < views.size(); ++i) {
    layers.push_back({.file = &views[i], .label = "before: " + labels[i], .colour = "#9a9a9a", .opacity = 0.8, .dashed = true});
  }
  layers.push_back({.file = &views.back(), .label = views.size() == 1 ? labels.back() : "after: " + labels.back()});
  if (tiling) add_tiling(layers.back(), *tiling);
  PlotOptions options = job.picture;
  if (options.title.empty()) options.title = labels.back();
  write_plot(output, layers, options);
}

class PlotCommand final : public Command {
 public:
  std::string name() const override { return "plot"; }
  std::string summary() const override { return "Draw a crowd file as SVG or PNG (trajectories, obstacles, agents at chosen frames) or animate it as GIF or MP4"; }

  void setup(CLI::App& app) override {
    app.add_option("crowd", input_, "Crowd file (.h5)")->required();
    app.add_option("-o,--output", output_, "Picture to write: .svg, .png (through rsvg-convert), or an animated preview .gif or .mp4 (through ffmpeg)")->required();
    app.add_option("--overlay", overlay_, "Another crowd file drawn underneath in grey (for example the input of an edit)");
    flags_.add(app, static_cast<void (*)(OptionBinder&, PlotJob&)>(describe));
  }

  void run(Context& context) override {
    PlotJob job;
    const YAML::Node effective =
        context.options(flags_.overrides(), name(), describe, job, {{"crowd", input_.string()}, {"overlay", overlay_.string()}});
    if (context.print_config_if_asked(effective)) return;
    check_distinct(input_, output_);

    std::vector<CrowdFile> files;
    std::vector<std::string> labels;
    if (!overlay_.empty()) files.push_back(read_crowd_file(overlay_)), labels.push_back(overlay_.filename().string());
    files.push_back(read_crowd_file(input_));
    labels.push_back(input_.filename().string());
    std::optional<TilingData> tiling;
    if (job.tiling && job.view == "top" && has_tiling_data(input_)) tiling = read_tiling_data(input_);
    std::vector<const CrowdFile*> crowds;
    for (const CrowdFile& f : files) crowds.push_back(&f);
    plot(output_, crowds, labels, job, tiling ? &*tiling : nullptr);
    Report r;
    r["output"] = output_.string();
    r["tiling"] = tiling.has_value();
    context.print(r);
  }

  /// As a step: the last input is drawn over the others (before/after); `output` is the picture.
  std::optional<StepResult> run_step(const ConfigNode& step, const std::vector<const CrowdFile*>& inputs, Context& context) override {
    const std::filesystem::path output = step.at("output").as_string();
    PlotJob job;
    read_options(step, describe, job);
    step.finish();
    if (inputs.empty()) step.fail("plot needs a crowd: no earlier step made one and no input is named");
    std::vector<std::string> labels;
    for (std::size_t i = 0; i + 1 < inputs.size(); ++i) labels.push_back("input " + std::to_string(i + 1));
    labels.push_back(output.stem().string());
    plot(output, inputs, labels, job);
    context.info("wrote " + output.string());
    return std::nullopt;
  }
  bool makes_crowd() const override { return false; }

 private:
  std::filesystem::path input_, output_, overlay_;
  OptionFlags flags_;
};

}  // namespace

std::unique_ptr<Command> make_plot_command() { return std::make_unique<PlotCommand>(); }

}  // namespace throng::cli
