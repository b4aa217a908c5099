// Animated previews of crowds (.gif, .mp4): the agents as discs moving over their faint trajectories, the
// obstacles (moving ones where they are), the legend, the scale bar and a clock, encoded by Debian's ffmpeg.
//
// The still parts are drawn once as the SVG of a plot without agents (plot_svg.h), rendered by rsvg-convert and
// decoded to RGB by ffmpeg; each frame is that picture with the agents, formation edges, moving obstacles and the
// clock drawn over it (plot_raster.h), piped as raw RGB to one ffmpeg that writes the output's temporary file
// (AtomicOutput): no file per frame, nothing left behind after a failure. The bytes are the same for the same
// crowd and options (ffmpeg with -bitexact, one thread; GIF through a palette made from all frames, MP4 H.264
// through libx264) with the same ffmpeg and rsvg-convert.
#pragma once

#include <throng/io/plot.h>

#include <cstddef>
#include <filesystem>
#include <vector>

namespace throng {

/// The crowd times a preview shows: frame k at min(start + k · step, end), `count` frames played at the
/// options' fps; `speed` = step · fps crowd seconds per preview second.
struct PreviewTimeline {
  double start = 0, end = 0, step = 0, speed = 1;
  std::size_t count = 1;
  [[nodiscard]] double time(std::size_t k) const;
};

/// The timeline for crowds spanning [start, end]: with `animation.speed`, every speed / fps seconds; without, real
/// time (one frame every 1 / fps s, and the last at `end`) when that fits in max_duration_s · fps frames, otherwise
/// exactly that many frames spread evenly from start to end. ConfigError when it would take more than 36,000
/// frames (an hour at 10 fps).
[[nodiscard]] PreviewTimeline preview_timeline(double start, double end, const PlotAnimation& animation);

/// Writes the animated preview of `layers` to `path` (.gif or .mp4 by its extension), atomically. ConfigError when
/// no layer has a frame; IoError naming the Debian package when rsvg-convert (librsvg2-bin) or ffmpeg (ffmpeg) is
/// missing, and with ffmpeg's message when it fails.
void write_animation(const std::filesystem::path& path, const std::vector<PlotLayer>& layers, const PlotOptions& options);

}  // namespace throng
