// A small RGB canvas for the frames of the animated previews (plot_animation.cpp): anti-aliased shapes given by
// their signed distance in pixels (discs, thick segments, any obstacle), blended over a background picture, and a
// clock in a built-in 5 × 7 pixel font. Plain arithmetic in a fixed order: the same frame gives the same bytes.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace throng {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
};

/// "#rrggbb" or "#rgb" (the colours the plot uses); black for anything else.
[[nodiscard]] Rgb parse_colour(const std::string& css);

class RgbCanvas {
 public:
  /// `pixels`: width × height × 3 bytes, rows top to bottom.
  RgbCanvas(int width, int height, std::vector<std::uint8_t> pixels);

  /// Blends `colour` at `opacity` over every pixel whose centre lies inside the shape, with a one-pixel soft edge:
  /// the coverage of a pixel is clamp(0.5 − d, 0, 1) for the signed distance d (pixels, negative inside) of its
  /// centre. Only pixels of `box` (pixels) are visited.
  void fill(const Eigen::AlignedBox2d& box, const std::function<double(const Eigen::Vector2d&)>& signed_distance, Rgb colour,
            double opacity);
  void disc(const Eigen::Vector2d& centre, double radius, Rgb colour, double opacity);
  /// The segment a–b drawn `width` pixels wide with round ends.
  void segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double width, Rgb colour, double opacity);
  /// `text` (digits, ". - s t = x : " and space; x is drawn as ×) in the built-in font magnified `scale` times, its
  /// right end at `right` and its bottom at `bottom`, over a white box; other characters are left blank.
  void text(int right, int bottom, const std::string& text, int scale, Rgb colour);

  [[nodiscard]] const std::vector<std::uint8_t>& pixels() const noexcept { return pixels_; }

 private:
  void blend(int x, int y, Rgb colour, double alpha);

  int width_, height_;
  std::vector<std::uint8_t> pixels_;
};

}  // namespace throng
