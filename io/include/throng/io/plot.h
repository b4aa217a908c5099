// Pictures of crowds: SVG (and PNG through Debian's rsvg-convert) of trajectories, obstacles and agents at chosen
// frames, coloured by group, with a scale bar, a title and a legend — a picture a person looks at instead of
// reading numbers. Several crowds can be drawn over each other (before/after an edit). Animated previews (GIF,
// MP4 through Debian's ffmpeg): the agents as discs moving over their faint trajectories, with a clock.
#pragma once

#include <throng/io/crowd_file.h>

#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace throng {

/// An extra line in world coordinates (metres), drawn over the trajectories: patch paths of a tiling,
/// connections, formation edges, warped paths ...
struct PlotPolyline {
  std::vector<Eigen::Vector2d> points;
  std::string colour = "#000000";
  double width_px = 1.5;
  double opacity = 1.0;
  bool dashed = false;
};

/// An extra marker: a small disc (radius in pixels) at a world point, e.g. a connection between patches; a ring
/// (outline only, of `colour`) when `ring` is set, e.g. a connection across the seam of a repeating tile.
struct PlotMarker {
  Eigen::Vector2d at{0, 0};
  std::string colour = "#000000";
  double radius_px = 3.0;
  bool ring = false;
};

/// An extra legend entry after its layer's line: a short line (what polylines of that colour mean), a dot or a
/// ring (what markers mean). Entries flow left to right and wrap at the picture's width.
struct PlotLegendEntry {
  enum class Symbol { line, dot, ring };
  std::string label;
  std::string colour = "#000000";
  Symbol symbol = Symbol::line;
};

/// The colour of agent `agent` at frame `frame`, overriding the layer's colour and the species colour; none:
/// the usual colour. For example the patch type a tiling's character walks through at that frame.
using AgentColour = std::function<std::optional<std::string>(std::size_t frame, std::size_t agent)>;

/// One crowd to draw.
struct PlotLayer {
  const CrowdFile* file = nullptr;
  std::string label;                   ///< legend text ("before", "after", a file name)
  std::optional<std::string> colour;   ///< one CSS colour for the whole layer; none: colour by species
  double opacity = 0.85;
  bool dashed = false;
  bool draw_agents = true;             ///< discs at the chosen frames
  bool draw_trajectories = true;       ///< this layer's agents' paths (PlotOptions::trajectories turns all off)
  std::vector<PlotPolyline> polylines; ///< drawn after the trajectories
  std::vector<PlotMarker> markers;     ///< drawn last
  std::vector<PlotLegendEntry> legend; ///< extra legend entries (empty: only the layer's line)
  AgentColour agent_colour;            ///< empty: colour by layer or species
};

/// An animated preview (.gif, .mp4): frames every `speed / fps` seconds of crowd time from the first frame of the
/// crowds to the last, shown at `fps`. Without `speed` the crowd plays in real time when that fits in
/// `max_duration_s`, and is sped up to fill exactly `max_duration_s` otherwise.
struct PlotAnimation {
  double fps = 10;                     ///< preview frames per second
  double max_duration_s = 10;          ///< longest preview when `speed` is not given
  std::optional<double> speed;         ///< crowd seconds per preview second (absent: real time or fitted)
  double width_px = 480;               ///< preview width (rounded to an even number of pixels)
};

struct PlotOptions {
  /// Frames at which agents are drawn as discs of their radius; negative counts from the end (−1 = last).
  std::vector<long> frames{0, -1};
  /// Smallest disc radius in pixels: on a large scene a 0.25 m agent would otherwise be a dot of 2 px.
  double min_agent_radius_px = 3.0;
  double width_px = 1200;              ///< picture width; the height follows the scene's aspect ratio
  bool trajectories = true;
  bool obstacles = true;
  std::string title;                   ///< empty: none
  PlotAnimation animation;             ///< .gif and .mp4 only (`frames` and `width_px` are the still picture's)
};

/// Writes the picture of `layers` (drawn in order, the first underneath) to `path`; the format follows the
/// extension: .svg, or .png (rendered by rsvg-convert from librsvg2-bin; IoError if it is missing), or an
/// animated preview .gif or .mp4 (plot_animation.h: rsvg-convert and ffmpeg; IoError naming the Debian package
/// if either is missing). Written atomically. ConfigError for an unknown extension, or for a still picture a
/// frame outside every layer.
void write_plot(const std::filesystem::path& path, const std::vector<PlotLayer>& layers, const PlotOptions& options);

/// A colour for a species or group index (a fixed palette of 12 distinguishable colours, cycled).
[[nodiscard]] std::string group_colour(std::int64_t index);

/// Runs a program (no shell) and waits; returns its exit status, or −1 if it could not be started.
int run_program(const std::vector<std::string>& argv);

}  // namespace throng
