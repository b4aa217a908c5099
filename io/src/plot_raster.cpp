#include "plot_raster.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace throng {
namespace {

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// The 5 × 7 glyphs of the clock, a row a number (bit 4 the leftmost column).
struct Glyph {
  char c;
  std::array<std::uint8_t, 7> rows;
};
constexpr std::array<Glyph, 18> font{{
    {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}}, {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}}, {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
    {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}}, {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
    {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}}, {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}}, {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
    {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}}, {'-', {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}},
    {'s', {0x00, 0x00, 0x0F, 0x10, 0x0E, 0x01, 0x1E}}, {'t', {0x08, 0x08, 0x1C, 0x08, 0x08, 0x09, 0x06}},
    {'=', {0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00}}, {'x', {0x00, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x00}},
    {':', {0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00}}, {' ', {0, 0, 0, 0, 0, 0, 0}},
}};

const Glyph* glyph(char c) {
  for (const Glyph& g : font) {
    if (g.c == c) return &g;
  }
  return nullptr;
}

}  // namespace

Rgb parse_colour(const std::string& css) {
  if (css.size() == 7 && css[0] == '#') {
    int v[6];
    for (int i = 0; i < 6; ++i) {
      if ((v[i] = hex_digit(css[static_cast<std::size_t>(i) + 1])) < 0) return {};
    }
    return {static_cast<std::uint8_t>(v[0] * 16 + v[1]), static_cast<std::uint8_t>(v[2] * 16 + v[3]),
            static_cast<std::uint8_t>(v[4] * 16 + v[5])};
  }
  if (css.size() == 4 && css[0] == '#') {
    int v[3];
    for (int i = 0; i < 3; ++i) {
      if ((v[i] = hex_digit(css[static_cast<std::size_t>(i) + 1])) < 0) return {};
    }
    return {static_cast<std::uint8_t>(v[0] * 17), static_cast<std::uint8_t>(v[1] * 17), static_cast<std::uint8_t>(v[2] * 17)};
  }
  return {};
}

RgbCanvas::RgbCanvas(int width, int height, std::vector<std::uint8_t> pixels)
    : width_(width), height_(height), pixels_(std::move(pixels)) {}

void RgbCanvas::blend(int x, int y, Rgb colour, double alpha) {
  std::uint8_t* p = &pixels_[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x)) * 3];
  const std::uint8_t c[3] = {colour.r, colour.g, colour.b};
  for (int k = 0; k < 3; ++k) {
    p[k] = static_cast<std::uint8_t>(std::lround(p[k] * (1.0 - alpha) + c[k] * alpha));
  }
}

void RgbCanvas::fill(const Eigen::AlignedBox2d& box, const std::function<double(const Eigen::Vector2d&)>& signed_distance,
                     Rgb colour, double opacity) {
  if (box.isEmpty() || !std::isfinite(box.min().x()) || !std::isfinite(box.max().y())) return;
  const int x0 = std::max(0, static_cast<int>(std::floor(std::max(box.min().x() - 1.0, -1.0))));
  const int y0 = std::max(0, static_cast<int>(std::floor(std::max(box.min().y() - 1.0, -1.0))));
  const int x1 = std::min(width_ - 1, static_cast<int>(std::ceil(std::min(box.max().x() + 1.0, width_ + 1.0))));
  const int y1 = std::min(height_ - 1, static_cast<int>(std::ceil(std::min(box.max().y() + 1.0, height_ + 1.0))));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const double d = signed_distance(Eigen::Vector2d(x + 0.5, y + 0.5));
      const double coverage = std::clamp(0.5 - d, 0.0, 1.0);
      if (coverage > 0) blend(x, y, colour, coverage * opacity);
    }
  }
}

void RgbCanvas::disc(const Eigen::Vector2d& centre, double radius, Rgb colour, double opacity) {
  const Eigen::Vector2d r(radius, radius);
  fill(Eigen::AlignedBox2d(centre - r, centre + r), [&](const Eigen::Vector2d& p) { return (p - centre).norm() - radius; },
       colour, opacity);
}

void RgbCanvas::segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double width, Rgb colour, double opacity) {
  const double half = width / 2;
  Eigen::AlignedBox2d box(a);
  box.extend(b);
  box.min() -= Eigen::Vector2d(half, half);
  box.max() += Eigen::Vector2d(half, half);
  const Eigen::Vector2d ab = b - a;
  const double length2 = ab.squaredNorm();
  fill(box,
       [&](const Eigen::Vector2d& p) {
         const double s = length2 > 0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
         return (p - (a + s * ab)).norm() - half;
       },
       colour, opacity);
}

void RgbCanvas::text(int right, int bottom, const std::string& text, int scale, Rgb colour) {
  const int advance = 6 * scale, pad = 2 * scale;
  const int left = right - advance * static_cast<int>(text.size()) + scale;
  const int top = bottom - 7 * scale;
  for (int y = std::max(0, top - pad); y < std::min(height_, bottom + pad); ++y) {
    for (int x = std::max(0, left - pad); x < std::min(width_, right + pad); ++x) blend(x, y, {255, 255, 255}, 0.8);
  }
  for (std::size_t i = 0; i < text.size(); ++i) {
    const Glyph* g = glyph(text[i]);
    if (!g) continue;
    const int gx = left + advance * static_cast<int>(i);
    for (int row = 0; row < 7; ++row) {
      for (int col = 0; col < 5; ++col) {
        if (!(g->rows[static_cast<std::size_t>(row)] & (0x10 >> col))) continue;
        for (int dy = 0; dy < scale; ++dy) {
          for (int dx = 0; dx < scale; ++dx) {
            const int x = gx + col * scale + dx, y = top + row * scale + dy;
            if (x >= 0 && x < width_ && y >= 0 && y < height_) blend(x, y, colour, 1.0);
          }
        }
      }
    }
  }
}

}  // namespace throng
