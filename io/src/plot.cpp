#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>
#include <throng/io/plot.h>

#include "plot_animation.h"
#include "plot_svg.h"

#include <algorithm>
#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>
#include <variant>

extern char** environ;

namespace throng {
namespace {

// Builds SVG text with numbers kept short (0.01 px is plenty).
class Svg {
 public:
  void raw(const std::string& s) { text_ += s; }
  void number(double v) {
    char buffer[32];
    const double rounded = std::round(v * 100.0) / 100.0;
    const auto r = std::to_chars(buffer, buffer + sizeof buffer, rounded == 0.0 ? 0.0 : rounded);
    text_.append(buffer, r.ptr);
  }
  void attr(const char* name, double v) {
    text_ += ' ';
    text_ += name;
    text_ += "=\"";
    number(v);
    text_ += '"';
  }
  [[nodiscard]] const std::string& text() const { return text_; }

 private:
  std::string text_;
};

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// A "nice" length (1, 2 or 5 × 10^k) close to `target`.
double nice_length(double target) {
  const double p = std::pow(10.0, std::floor(std::log10(target)));
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * p >= target * 0.7) return m * p;
  }
  return 10 * p;
}

// Where the extra legend entries of every layer go: entries flow left to right from x = 12 and wrap before
// `width`; the widths are estimated from the text (13 px sans-serif: about 7.2 px a character).
struct LegendFlow {
  struct Placed {
    const PlotLegendEntry* entry;
    double x;
    int row;
  };
  std::vector<std::vector<Placed>> per_layer;  // per layer, its entries
  std::vector<int> rows;                       // per layer, rows its entries take
};

std::size_t glyphs(const std::string& s) {
  std::size_t n = 0;
  for (unsigned char c : s) n += (c & 0xC0) != 0x80;
  return n;
}

LegendFlow flow_legend(const std::vector<PlotLayer>& layers, double width) {
  LegendFlow flow;
  for (const PlotLayer& layer : layers) {
    std::vector<LegendFlow::Placed> placed;
    double x = 12;
    int row = 0;
    for (const PlotLegendEntry& e : layer.legend) {
      const double w = 34 + 7.2 * static_cast<double>(glyphs(e.label)) + 16;
      if (x > 12 && x + w > width - 12) {
        x = 12;
        ++row;
      }
      placed.push_back({&e, x, row});
      x += w;
    }
    flow.rows.push_back(layer.legend.empty() ? 0 : row + 1);
    flow.per_layer.push_back(std::move(placed));
  }
  return flow;
}

std::string length_label(double metres) {
  char buffer[32];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, metres);
  return std::string(buffer, r.ptr) + " m";
}

void draw_obstacle(Svg& svg, const View& v, const Obstacle& o, double time, double opacity) {
  const Eigen::Isometry2d pose = pose_at(o, time);
  std::visit(
      [&](const auto& s) {
        using S = std::decay_t<decltype(s)>;
        svg.raw("<");
        if constexpr (std::is_same_v<S, Circle>) {
          const Eigen::Vector2d c = pose * s.center;
          svg.raw("circle");
          svg.attr("cx", v.px(c.x()));
          svg.attr("cy", v.py(c.y()));
          svg.attr("r", s.radius * v.scale);
          svg.raw(" fill=\"#8c8c8c\" stroke=\"#404040\"");
        } else if constexpr (std::is_same_v<S, ConvexPolygon>) {
          svg.raw("polygon points=\"");
          for (const auto& p : s.vertices) {
            const Eigen::Vector2d q = pose * p;
            svg.number(v.px(q.x()));
            svg.raw(",");
            svg.number(v.py(q.y()));
            svg.raw(" ");
          }
          svg.raw("\" fill=\"#8c8c8c\" stroke=\"#404040\"");
        } else {
          const Eigen::Vector2d a = pose * s.a, b = pose * s.b;
          svg.raw("line");
          svg.attr("x1", v.px(a.x()));
          svg.attr("y1", v.py(a.y()));
          svg.attr("x2", v.px(b.x()));
          svg.attr("y2", v.py(b.y()));
          svg.attr("stroke-width", std::max(2.0, s.thickness * v.scale));
          svg.raw(" stroke=\"#404040\" stroke-linecap=\"round\"");
        }
        svg.attr("opacity", opacity);
        svg.raw("/>\n");
      },
      o.shape);
}

// A layer's extra legend entries, their first row at baseline `y`.
void draw_legend_entries(Svg& svg, const std::vector<LegendFlow::Placed>& entries, double y) {
  for (const LegendFlow::Placed& p : entries) {
    const PlotLegendEntry& e = *p.entry;
    const double base = y + 20.0 * p.row;
    switch (e.symbol) {
      case PlotLegendEntry::Symbol::line:
        svg.raw("<line");
        svg.attr("x1", p.x);
        svg.attr("y1", base - 4);
        svg.attr("x2", p.x + 28);
        svg.attr("y2", base - 4);
        svg.raw(" stroke=\"" + e.colour + "\" stroke-width=\"3\"/>\n");
        break;
      case PlotLegendEntry::Symbol::dot:
      case PlotLegendEntry::Symbol::ring:
        svg.raw("<circle");
        svg.attr("cx", p.x + 14);
        svg.attr("cy", base - 4);
        svg.attr("r", 4);
        if (e.symbol == PlotLegendEntry::Symbol::ring) {
          svg.raw(" fill=\"none\" stroke=\"" + e.colour + "\" stroke-width=\"1.5\"/>\n");
        } else {
          svg.raw(" fill=\"" + e.colour + "\"/>\n");
        }
        break;
    }
    svg.raw("<text");
    svg.attr("x", p.x + 34);
    svg.attr("y", base);
    svg.raw(">" + escape(e.label) + "</text>\n");
  }
}

}  // namespace

PlotLayout plot_layout(const std::vector<PlotLayer>& layers, const PlotOptions& options) {
  // Extent of everything drawn.
  Eigen::AlignedBox2d box;
  for (const PlotLayer& layer : layers) {
    const CrowdMotion& m = layer.file->motion;
    for (std::size_t i = 0; i + 2 < m.positions.size(); i += 3) {
      if (std::isfinite(m.positions[i])) box.extend(Eigen::Vector2d(m.positions[i], m.positions[i + 1]));
    }
    if (options.obstacles) {
      const double t0 = m.times.empty() ? 0.0 : m.times.front();
      const double t1 = m.times.empty() ? 0.0 : m.times.back();
      for (const Obstacle& o : layer.file->scene.obstacles) box.extend(bounds_over(o, t0, t1));
    }
    for (const PlotPolyline& line : layer.polylines) {
      for (const auto& p : line.points) box.extend(p);
    }
    for (const PlotMarker& marker : layer.markers) box.extend(marker.at);
    if (layer.file->scene.region) {
      box.extend(layer.file->scene.region->min);
      box.extend(layer.file->scene.region->max);
    }
  }
  if (box.isEmpty()) box = Eigen::AlignedBox2d(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1));
  Eigen::Vector2d size = box.sizes().cwiseMax(Eigen::Vector2d(1e-3, 1e-3));
  // Keep pictures of long, thin scenes readable: at least 1 : 4.
  if (size.y() < size.x() / 4) {
    box.extend(box.center() + Eigen::Vector2d(0, size.x() / 8));
    box.extend(box.center() - Eigen::Vector2d(0, size.x() / 8));
  }
  if (size.x() < size.y() / 4) {
    box.extend(box.center() + Eigen::Vector2d(size.y() / 8, 0));
    box.extend(box.center() - Eigen::Vector2d(size.y() / 8, 0));
  }
  size = box.sizes();
  const double margin = 40;
  const double width = std::max(200.0, options.width_px);
  const LegendFlow legend = flow_legend(layers, width);
  std::size_t legend_lines = options.title.empty() ? 0 : 1;
  for (std::size_t l = 0; l < layers.size(); ++l) {
    legend_lines += (layers[l].label.empty() ? 0 : 1) + static_cast<std::size_t>(legend.rows[l]);
  }
  const double top = margin + 20.0 * static_cast<double>(legend_lines);
  const double scale = (width - 2 * margin) / size.x();
  const double height = size.y() * scale + top + margin + 30;
  return {.view = {box.min().x(), box.max().y(), scale, margin, top}, .width = width, .height = height, .size = size};
}

std::string svg_document(const std::vector<PlotLayer>& layers, const PlotOptions& options, const PlotLayout& layout) {
  const View& v = layout.view;
  const double width = layout.width, height = layout.height, scale = v.scale, margin = v.margin;
  const Eigen::Vector2d size = layout.size;
  const LegendFlow legend = flow_legend(layers, width);
  std::size_t total_agents = 0;
  for (const PlotLayer& layer : layers) total_agents += layer.file->motion.agent_count();

  Svg svg;
  svg.raw("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\"");
  svg.attr("width", width);
  svg.attr("height", height);
  svg.raw(" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\" font-size=\"13\">\n");
  svg.raw("<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n");

  // Region outline.
  for (const PlotLayer& layer : layers) {
    if (const auto& r = layer.file->scene.region) {
      svg.raw("<rect");
      svg.attr("x", v.px(r->min.x()));
      svg.attr("y", v.py(r->max.y()));
      svg.attr("width", (r->max.x() - r->min.x()) * scale);
      svg.attr("height", (r->max.y() - r->min.y()) * scale);
      svg.raw(" fill=\"none\" stroke=\"#b0b0b0\" stroke-dasharray=\"6 4\"/>\n");
      break;
    }
  }

  // Obstacles (of the first layer that has any): static once; moving ones at every drawn frame, fainter.
  if (options.obstacles) {
    for (const PlotLayer& layer : layers) {
      const auto& scene = layer.file->scene;
      if (scene.obstacles.empty()) continue;
      const CrowdMotion& m = layer.file->motion;
      for (const Obstacle& o : scene.obstacles) {
        if (!o.is_moving()) {
          draw_obstacle(svg, v, o, 0.0, 0.9);
          continue;
        }
        for (long f : options.frames) {
          const long T = static_cast<long>(m.frame_count());
          const long frame = f < 0 ? T + f : f;
          if (frame >= 0 && frame < T) draw_obstacle(svg, v, o, m.times[static_cast<std::size_t>(frame)], 0.45);
        }
      }
      break;
    }
  }

  const double line_width = total_agents > 2000 ? 0.6 : (total_agents > 300 ? 0.9 : 1.4);
  for (const PlotLayer& layer : layers) {
    const CrowdMotion& m = layer.file->motion;
    const std::size_t T = m.frame_count(), N = m.agent_count();
    if (options.trajectories && layer.draw_trajectories) {
      svg.raw("<g fill=\"none\" stroke-linejoin=\"round\" stroke-linecap=\"round\"");
      svg.attr("stroke-width", line_width);
      svg.attr("opacity", layer.opacity);
      if (layer.dashed) svg.raw(" stroke-dasharray=\"5 3\"");
      svg.raw(">\n");
      for (std::size_t n = 0; n < N; ++n) {
        const std::string colour = layer.colour ? *layer.colour : group_colour(m.species[n]);
        bool open = false;
        double last_x = 0, last_y = 0;
        for (std::size_t t = 0; t <= T; ++t) {
          const bool here = t < T && m.present(t, n);
          if (!here) {
            if (open) svg.raw("\"/>\n");
            open = false;
            continue;
          }
          const auto p = m.position(t, n);
          const double x = v.px(p.x()), y = v.py(p.y());
          const bool last_of_span = t + 1 >= T || !m.present(t + 1, n);
          if (!open) {
            svg.raw("<polyline stroke=\"" + colour + "\" points=\"");
            open = true;
          } else if (std::hypot(x - last_x, y - last_y) < 0.75 && !last_of_span) {
            continue;  // closer than a pixel to the last point drawn
          }
          svg.number(x);
          svg.raw(",");
          svg.number(y);
          svg.raw(" ");
          last_x = x;
          last_y = y;
        }
      }
      svg.raw("</g>\n");
    }
    for (const PlotPolyline& line : layer.polylines) {
      if (line.points.size() < 2) continue;
      svg.raw("<polyline fill=\"none\" stroke-linejoin=\"round\" stroke=\"" + line.colour + "\"");
      svg.attr("stroke-width", line.width_px);
      svg.attr("opacity", line.opacity);
      if (line.dashed) svg.raw(" stroke-dasharray=\"5 3\"");
      svg.raw(" points=\"");
      for (const auto& p : line.points) {
        svg.number(v.px(p.x()));
        svg.raw(",");
        svg.number(v.py(p.y()));
        svg.raw(" ");
      }
      svg.raw("\"/>\n");
    }
    // Formation edges (the file's connectivity) between the agents at each drawn frame, under the discs.
    if (layer.draw_agents && !layer.file->formation_edges.empty()) {
      for (long f : options.frames) {
        const long frame = f < 0 ? static_cast<long>(T) + f : f;
        if (frame < 0 || frame >= static_cast<long>(T)) continue;
        svg.raw("<g stroke=\"#707070\" stroke-linecap=\"round\"");
        svg.attr("stroke-width", std::max(0.4, 0.6 * line_width));
        svg.attr("opacity", 0.6 * layer.opacity);
        svg.raw(">\n");
        for (const auto& e : layer.file->formation_edges) {
          const auto a = static_cast<std::size_t>(e[0]), b = static_cast<std::size_t>(e[1]);
          if (!m.present(static_cast<std::size_t>(frame), a) || !m.present(static_cast<std::size_t>(frame), b)) continue;
          const auto p = m.position(static_cast<std::size_t>(frame), a), q = m.position(static_cast<std::size_t>(frame), b);
          svg.raw("<line");
          svg.attr("x1", v.px(p.x()));
          svg.attr("y1", v.py(p.y()));
          svg.attr("x2", v.px(q.x()));
          svg.attr("y2", v.py(q.y()));
          svg.raw("/>\n");
        }
        svg.raw("</g>\n");
      }
    }
    if (layer.draw_agents) {
      const std::size_t frames = options.frames.size();
      for (std::size_t k = 0; k < frames; ++k) {
        const long f = options.frames[k];
        const long frame = f < 0 ? static_cast<long>(T) + f : f;
        if (frame < 0 || frame >= static_cast<long>(T)) continue;
        // Later frames more opaque: the picture reads as motion from faint to solid.
        const double opacity = frames == 1 ? 0.9 : 0.35 + 0.55 * static_cast<double>(k) / static_cast<double>(frames - 1);
        svg.raw("<g stroke=\"white\" stroke-width=\"0.5\"");
        svg.attr("opacity", opacity * layer.opacity);
        svg.raw(">\n");
        for (std::size_t n = 0; n < N; ++n) {
          if (!m.present(static_cast<std::size_t>(frame), n)) continue;
          const auto p = m.position(static_cast<std::size_t>(frame), n);
          std::optional<std::string> own;
          if (layer.agent_colour) own = layer.agent_colour(static_cast<std::size_t>(frame), n);
          const std::string colour = own ? *own : layer.colour ? *layer.colour : group_colour(m.species[n]);
          svg.raw("<circle");
          svg.attr("cx", v.px(p.x()));
          svg.attr("cy", v.py(p.y()));
          svg.attr("r", std::max(options.min_agent_radius_px, m.radii[n] * scale));
          svg.raw(" fill=\"" + colour + "\"/>\n");
        }
        svg.raw("</g>\n");
      }
    }
  }

  for (const PlotLayer& layer : layers) {
    for (const PlotMarker& m : layer.markers) {
      svg.raw("<circle");
      svg.attr("cx", v.px(m.at.x()));
      svg.attr("cy", v.py(m.at.y()));
      svg.attr("r", m.radius_px);
      if (m.ring) {
        svg.raw(" fill=\"none\" stroke=\"" + m.colour + "\" stroke-width=\"1.5\"/>\n");
      } else {
        svg.raw(" fill=\"" + m.colour + "\" stroke=\"white\" stroke-width=\"0.5\"/>\n");
      }
    }
  }

  // Scale bar, bottom left.
  const double bar = nice_length(size.x() / 5);
  const double bx = margin, by = height - 22;
  svg.raw("<g stroke=\"black\" stroke-width=\"2\">");
  svg.raw("<line");
  svg.attr("x1", bx);
  svg.attr("y1", by);
  svg.attr("x2", bx + bar * scale);
  svg.attr("y2", by);
  svg.raw("/><line");
  svg.attr("x1", bx);
  svg.attr("y1", by - 5);
  svg.attr("x2", bx);
  svg.attr("y2", by + 5);
  svg.raw("/><line");
  svg.attr("x1", bx + bar * scale);
  svg.attr("y1", by - 5);
  svg.attr("x2", bx + bar * scale);
  svg.attr("y2", by + 5);
  svg.raw("/></g>\n<text");
  svg.attr("x", bx + bar * scale + 8);
  svg.attr("y", by + 4);
  svg.raw(">" + length_label(bar) + "</text>\n");

  // Title and legend, top.
  if (!options.title.empty()) svg.raw("<text x=\"12\" y=\"22\" font-size=\"16\" font-weight=\"bold\">" + escape(options.title) + "</text>\n");
  double ly = options.title.empty() ? 22 : 44;
  for (std::size_t l = 0; l < layers.size(); ++l) {
    const PlotLayer& layer = layers[l];
    if (layer.label.empty()) {
      draw_legend_entries(svg, legend.per_layer[l], ly);
      ly += 20.0 * legend.rows[l];
      continue;
    }
    const CrowdMotion& m = layer.file->motion;
    std::string text = layer.label + " — " + std::to_string(m.agent_count()) + " agents, " + std::to_string(m.frame_count()) + " frames";
    if (!m.times.empty()) {
      char buffer[64];
      std::snprintf(buffer, sizeof buffer, ", %.2f–%.2f s", m.times.front(), m.times.back());
      text += buffer;
    }
    const std::string colour = layer.colour ? *layer.colour : group_colour(0);
    svg.raw("<line");
    svg.attr("x1", 12);
    svg.attr("y1", ly - 4);
    svg.attr("x2", 40);
    svg.attr("y2", ly - 4);
    svg.raw(" stroke=\"" + colour + "\" stroke-width=\"3\"" + (layer.dashed ? " stroke-dasharray=\"5 3\"" : "") + "/>\n<text");
    svg.attr("x", 46);
    svg.attr("y", ly);
    svg.raw(">" + escape(text) + "</text>\n");
    ly += 20;
    draw_legend_entries(svg, legend.per_layer[l], ly);
    ly += 20.0 * legend.rows[l];
  }
  svg.raw("</svg>\n");
  return svg.text();
}

std::string group_colour(std::int64_t index) {
  static const char* palette[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b",
                                  "#e377c2", "#17becf", "#bcbd22", "#393b79", "#637939", "#7f7f7f"};
  const auto k = static_cast<std::size_t>(((index % 12) + 12) % 12);
  return palette[k];
}

// Runs a program with stdin and stdout on the given descriptors; its exit status, or -1 if it could not start.
int run_program(const std::vector<std::string>& argv, int input_fd, int output_fd) {
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, input_fd, 0);
  posix_spawn_file_actions_adddup2(&actions, output_fd, 1);
  pid_t pid = 0;
  const int started = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (started != 0) return -1;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

void write_plot(const std::filesystem::path& path, const std::vector<PlotLayer>& layers, const PlotOptions& options) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  if (extension != ".svg" && extension != ".png" && extension != ".gif" && extension != ".mp4") {
    throw ConfigError(path.string() + ": unknown picture format '" + extension + "', expected .svg, .png, .gif or .mp4");
  }
  if (layers.empty()) throw ConfigError("nothing to plot");
  if (extension == ".gif" || extension == ".mp4") {
    write_animation(path, layers, options);
    return;
  }
  for (long f : options.frames) {
    bool inside = false;
    for (const auto& layer : layers) {
      const long T = static_cast<long>(layer.file->motion.frame_count());
      inside = inside || (f >= 0 ? f < T : -f <= T);
    }
    if (!inside) throw ConfigError("frame " + std::to_string(f) + " is outside every plotted crowd");
  }
  const std::string svg = svg_document(layers, options, plot_layout(layers, options));
  AtomicOutput output(path);
  if (extension == ".svg") {
    output.write(svg);
  } else {
    // rsvg-convert reads the SVG from a temporary file (never committed) and writes the PNG into the output's
    // temporary, both through descriptors: it opens no name in the output folder.
    AtomicOutput source(path.parent_path() / (path.stem().string() + ".svg"));
    source.write(svg);
    const int input = ::open(source.descriptor_path().c_str(), O_RDONLY | O_CLOEXEC);
    if (input < 0) throw IoError(path.string() + ": cannot reopen the SVG for rsvg-convert (" + std::string(std::strerror(errno)) + ")");
    const int status = run_program({"rsvg-convert", "--format=png"}, input, output.descriptor());
    ::close(input);
    if (status == -1) throw IoError(path.string() + ": PNG needs rsvg-convert (Debian package librsvg2-bin); write .svg instead");
    if (status != 0) throw IoError(path.string() + ": rsvg-convert failed with status " + std::to_string(status));
  }
  output.commit();
}

}  // namespace throng
