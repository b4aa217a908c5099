// The SVG drawing of io/src/plot.cpp, shared with the animated previews (plot_animation.cpp), which draw the
// still parts (trajectories, static obstacles, legend, scale bar) once as SVG and the moving agents over them.
#pragma once

#include <throng/io/plot.h>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace throng {

/// World (metres, y up) to picture (pixels, y down).
struct View {
  double x0, y1, scale, margin, top;
  [[nodiscard]] double px(double x) const { return margin + (x - x0) * scale; }
  [[nodiscard]] double py(double y) const { return top + (y1 - y) * scale; }
};

/// Where everything goes: the world-to-picture mapping and the picture's size in pixels (width from the options,
/// height from the scene's aspect ratio, the title and the legend). `size` is the world extent drawn (metres).
struct PlotLayout {
  View view;
  double width = 0, height = 0;
  Eigen::Vector2d size{1, 1};
};

/// The layout of `layers` at `options.width_px`.
[[nodiscard]] PlotLayout plot_layout(const std::vector<PlotLayer>& layers, const PlotOptions& options);

/// The SVG text of the picture with that layout (its height may have been rounded up by the caller).
[[nodiscard]] std::string svg_document(const std::vector<PlotLayer>& layers, const PlotOptions& options,
                                       const PlotLayout& layout);

}  // namespace throng
