#include "plot_animation.h"

#include "plot_raster.h"
#include "plot_svg.h"
#include "spawned_program.h"

#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <limits>
#include <optional>
#include <unistd.h>

namespace throng {
namespace {

constexpr std::size_t max_preview_frames = 36000;

std::string number_text(double v) {
  char buffer[32];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, r.ptr);
}

/// The last lines of what a helper program wrote to stderr, for a message.
std::string tail_of(const ScratchFile& err) {
  std::string text = err.content(2000);
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  return text.empty() ? "" : ": " + text;
}

std::string missing_ffmpeg(const std::filesystem::path& path) {
  return path.string() + ": GIF and MP4 previews need ffmpeg (Debian package ffmpeg); write .svg or .png instead";
}

/// The still picture (no agents) as width × height × 3 RGB bytes: SVG → rsvg-convert → PNG → ffmpeg → raw RGB.
std::vector<std::uint8_t> render_background(const std::filesystem::path& path, const std::string& svg, int width, int height) {
  ScratchFile svg_file, png, raw, err;
  svg_file.assign(svg);
  {
    SpawnedProgram rsvg({"rsvg-convert", "--format=png"}, svg_file.descriptor(), png.descriptor(), err.descriptor());
    if (!rsvg.started()) {
      throw IoError(path.string() + ": GIF and MP4 previews need rsvg-convert (Debian package librsvg2-bin)");
    }
    const int status = rsvg.wait();
    if (status != 0) throw IoError(path.string() + ": rsvg-convert failed with status " + std::to_string(status) + tail_of(err));
  }
  png.rewind();
  err.clear();
  SpawnedProgram decode({"ffmpeg", "-hide_banner", "-loglevel", "error", "-f", "png_pipe", "-i", "pipe:0", "-f", "rawvideo",
                         "-pix_fmt", "rgb24", "pipe:1"},
                        png.descriptor(), raw.descriptor(), err.descriptor());
  if (!decode.started()) throw IoError(missing_ffmpeg(path));
  const int status = decode.wait();
  if (status != 0) throw IoError(path.string() + ": ffmpeg could not decode the background picture (status " + std::to_string(status) + ")" + tail_of(err));
  const std::string bytes = raw.content();
  const std::size_t expected = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3;
  if (bytes.size() != expected) {
    throw IoError(path.string() + ": the background picture decoded to " + std::to_string(bytes.size()) + " bytes, expected " +
                  std::to_string(width) + " × " + std::to_string(height) + " × 3");
  }
  return {bytes.begin(), bytes.end()};
}

/// The ffmpeg command that reads raw RGB frames on stdin and writes the preview to its stdout (the output's
/// temporary file, reopened by name so that MP4 can seek back to write its index at the front).
std::vector<std::string> encoder_command(const std::string& extension, int width, int height, double fps,
                                         const std::string& output_name) {
  std::vector<std::string> args = {"ffmpeg", "-hide_banner", "-loglevel", "error", "-f", "rawvideo", "-pix_fmt", "rgb24",
                                   "-s", std::to_string(width) + "x" + std::to_string(height), "-framerate", number_text(fps),
                                   "-i", "pipe:0", "-threads", "1", "-filter_complex_threads", "1"};
  if (extension == ".gif") {
    // One palette for the whole preview (made from every frame), ordered dithering, only the changed rectangle of
    // each frame stored; -loop 0 repeats forever.
    args.insert(args.end(), {"-filter_complex",
                             "[0:v]split[a][b];[a]palettegen=max_colors=256[p];[b][p]paletteuse=dither=bayer:bayer_scale=5:diff_mode=rectangle",
                             "-loop", "0", "-f", "gif"});
  } else {
    args.insert(args.end(), {"-c:v", "libx264", "-preset", "medium", "-crf", "23", "-pix_fmt", "yuv420p", "-movflags",
                             "+faststart", "-f", "mp4"});
  }
  args.insert(args.end(), {"-fflags", "+bitexact", "-flags:v", "+bitexact", "-map_metadata", "-1", "-y", output_name});
  return args;
}

/// The frame of `times` nearest to `t`; none when t lies outside [first, last].
std::optional<std::size_t> nearest_frame(const std::vector<double>& times, double t) {
  if (times.empty()) return std::nullopt;
  const double tolerance = 1e-9 * (1.0 + std::abs(t));
  if (t < times.front() - tolerance || t > times.back() + tolerance) return std::nullopt;
  const auto it = std::lower_bound(times.begin(), times.end(), t);
  if (it == times.end()) return times.size() - 1;
  const auto k = static_cast<std::size_t>(it - times.begin());
  if (k > 0 && t - times[k - 1] <= *it - t) return k - 1;
  return k;
}

/// The clock: crowd time with as many decimals as the frame step needs, and the speed-up when there is one.
std::string clock_text(const PreviewTimeline& timeline, double t) {
  const int decimals = timeline.step > 0 ? std::clamp(static_cast<int>(std::ceil(-std::log10(timeline.step) - 1e-9)), 0, 3) : 1;
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f s", decimals, t);
  std::string text = buffer;
  if (std::abs(timeline.speed - 1.0) > 1e-9) {
    std::snprintf(buffer, sizeof buffer, "  x%.*f", timeline.speed < 10 ? 1 : 0, timeline.speed);
    text += buffer;
  }
  return text;
}

/// One frame: the background with the moving obstacles, formation edges, agents and clock at crowd time `t`.
void draw_frame(RgbCanvas& canvas, const std::vector<PlotLayer>& layers, const PlotOptions& options, const PlotLayout& layout,
                const PreviewTimeline& timeline, double t) {
  const View& v = layout.view;
  const auto to_px = [&](const Eigen::Vector2d& p) { return Eigen::Vector2d(v.px(p.x()), v.py(p.y())); };
  if (options.obstacles) {
    for (const PlotLayer& layer : layers) {
      if (layer.file->scene.obstacles.empty()) continue;
      for (const Obstacle& o : layer.file->scene.obstacles) {
        if (!o.is_moving()) continue;
        const Eigen::AlignedBox2d world = bounds_at(o, t);
        Eigen::AlignedBox2d box(to_px(world.min()));
        box.extend(to_px(world.max()));
        canvas.fill(box,
                    [&](const Eigen::Vector2d& p) {
                      const Eigen::Vector2d w(v.x0 + (p.x() - v.margin) / v.scale, v.y1 - (p.y() - v.top) / v.scale);
                      return distance_to(o, w, t).signed_distance * v.scale;
                    },
                    parse_colour("#8c8c8c"), 0.9);
      }
      break;  // the obstacles of the first layer that has any, as the still picture draws them
    }
  }
  for (const PlotLayer& layer : layers) {
    const CrowdMotion& m = layer.file->motion;
    const std::optional<std::size_t> frame = nearest_frame(m.times, t);
    if (!frame || !layer.draw_agents) continue;
    const std::size_t f = *frame;
    for (const auto& e : layer.file->formation_edges) {
      const auto a = static_cast<std::size_t>(e[0]), b = static_cast<std::size_t>(e[1]);
      if (!m.present(f, a) || !m.present(f, b)) continue;
      canvas.segment(to_px(m.position(f, a).head<2>()), to_px(m.position(f, b).head<2>()), 1.0, parse_colour("#707070"),
                     0.6 * layer.opacity);
    }
    for (std::size_t n = 0; n < m.agent_count(); ++n) {
      if (!m.present(f, n)) continue;
      std::optional<std::string> own;
      if (layer.agent_colour) own = layer.agent_colour(f, n);
      const std::string colour = own ? *own : layer.colour ? *layer.colour : group_colour(m.species[n]);
      canvas.disc(to_px(m.position(f, n).head<2>()), std::max(options.min_agent_radius_px, m.radii[n] * v.scale),
                  parse_colour(colour), 0.9 * layer.opacity);
    }
  }
  const int scale = std::max(2, static_cast<int>(layout.width) / 240);  // 10 × 14 px glyphs at 480 px wide
  canvas.text(static_cast<int>(layout.width) - 12, static_cast<int>(layout.height) - 12, clock_text(timeline, t), scale, {});
}

}  // namespace

double PreviewTimeline::time(std::size_t k) const { return std::min(start + static_cast<double>(k) * step, end); }

PreviewTimeline preview_timeline(double start, double end, const PlotAnimation& animation) {
  PreviewTimeline timeline{.start = start, .end = end};
  const double duration = std::max(0.0, end - start), fps = animation.fps;
  double frames_after_first = 0;
  if (animation.speed) {
    timeline.step = *animation.speed / fps;
    frames_after_first = duration > 0 ? std::ceil(duration / timeline.step - 1e-9) : 0;
  } else {
    const double most = std::max(1.0, std::floor(animation.max_duration_s * fps + 1e-9));
    const double real_time = duration > 0 ? std::ceil(duration * fps - 1e-9) : 0;
    if (real_time + 1 <= most) {
      timeline.step = 1.0 / fps;
      frames_after_first = real_time;
    } else {
      frames_after_first = most - 1;
      timeline.step = frames_after_first > 0 ? duration / frames_after_first : 1.0 / fps;
    }
  }
  if (frames_after_first + 1 > static_cast<double>(max_preview_frames)) {
    throw ConfigError("the preview would take " + number_text(frames_after_first + 1) + " frames (more than " +
                      std::to_string(max_preview_frames) + "): raise preview.speed or lower preview.fps");
  }
  timeline.count = static_cast<std::size_t>(frames_after_first) + 1;
  timeline.speed = timeline.step * fps;
  return timeline;
}

void write_animation(const std::filesystem::path& path, const std::vector<PlotLayer>& layers, const PlotOptions& options) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  double start = std::numeric_limits<double>::infinity(), end = -start;
  for (const PlotLayer& layer : layers) {
    const auto& times = layer.file->motion.times;
    if (times.empty()) continue;
    start = std::min(start, times.front());
    end = std::max(end, times.back());
  }
  if (!(start <= end)) throw ConfigError(path.string() + ": nothing to animate: no plotted crowd has a frame");
  const PreviewTimeline timeline = preview_timeline(start, end, options.animation);
  check_output_target(path);

  // The still parts: the plot without agents at the preview's width, trajectories faint, height rounded up to an
  // even number of pixels (H.264 in 4:2:0 needs even sides).
  const int width = 2 * std::max(100, static_cast<int>(std::lround(options.animation.width_px / 2)));
  PlotOptions still = options;
  still.frames.clear();
  still.width_px = width;
  std::vector<PlotLayer> faint = layers;
  for (PlotLayer& layer : faint) layer.opacity *= 0.35;
  PlotLayout layout = plot_layout(faint, still);
  const int height = 2 * static_cast<int>(std::ceil(layout.height / 2 - 1e-9));
  layout.height = height;
  const std::vector<std::uint8_t> background = render_background(path, svg_document(faint, still, layout), width, height);

  AtomicOutput output(path);
  const std::string descriptor_name = output.descriptor_path().string();
  const std::string output_name = descriptor_name.rfind("/proc/self/fd/", 0) == 0 ? "/proc/self/fd/1" : descriptor_name;
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0) throw IoError(path.string() + ": cannot make a pipe to ffmpeg (" + std::strerror(errno) + ")");
  ScratchFile err;
  SpawnedProgram encoder(encoder_command(extension, width, height, options.animation.fps, output_name), pipe_fds[0],
                         output.descriptor(), err.descriptor());
  ::close(pipe_fds[0]);
  if (!encoder.started()) {
    ::close(pipe_fds[1]);
    throw IoError(missing_ffmpeg(path));
  }
  bool written = true;
  for (std::size_t k = 0; k < timeline.count && written; ++k) {
    RgbCanvas canvas(width, height, background);
    draw_frame(canvas, layers, options, layout, timeline, timeline.time(k));
    written = write_to_pipe(pipe_fds[1], canvas.pixels().data(), canvas.pixels().size());
  }
  ::close(pipe_fds[1]);
  const int status = encoder.wait();
  if (status != 0 || !written) {
    throw IoError(path.string() + ": ffmpeg failed with status " + std::to_string(status) + tail_of(err));
  }
  output.commit();
}

}  // namespace throng
