// The built-in stroke font of the `text` shape: capitals A–Z as polylines in a box 0.6 wide and 1 high (origin at
// the bottom-left), round letters drawn as octagons. Enough for formations spelling words (the paper's airshow
// spells T, H, E, E, N, D with ten planes).
#include <throng/core/errors.h>
#include <throng/formation/shapes.h>

#include <cctype>
#include <utility>

namespace throng::formation {
namespace {

using Glyph = std::vector<Line>;

Line l(std::initializer_list<std::pair<double, double>> points) {
  Line line;
  for (const auto& [x, y] : points) line.emplace_back(x, y);
  return line;
}

Glyph glyph(char c) {
  const Line o = l({{0.15, 0}, {0, 0.2}, {0, 0.8}, {0.15, 1}, {0.45, 1}, {0.6, 0.8}, {0.6, 0.2}, {0.45, 0}, {0.15, 0}});
  const Line p = l({{0, 0}, {0, 1}, {0.45, 1}, {0.6, 0.85}, {0.6, 0.6}, {0.45, 0.45}, {0, 0.45}});
  switch (c) {
    case 'A': return {l({{0, 0}, {0.3, 1}, {0.6, 0}}), l({{0.12, 0.4}, {0.48, 0.4}})};
    case 'B': return {l({{0, 0}, {0, 1}, {0.45, 1}, {0.55, 0.9}, {0.55, 0.6}, {0.45, 0.5}, {0, 0.5}}),
                      l({{0.45, 0.5}, {0.6, 0.4}, {0.6, 0.1}, {0.5, 0}, {0, 0}})};
    case 'C': return {l({{0.6, 0.85}, {0.45, 1}, {0.15, 1}, {0, 0.8}, {0, 0.2}, {0.15, 0}, {0.45, 0}, {0.6, 0.15}})};
    case 'D': return {l({{0, 0}, {0, 1}, {0.35, 1}, {0.6, 0.75}, {0.6, 0.25}, {0.35, 0}, {0, 0}})};
    case 'E': return {l({{0.6, 1}, {0, 1}, {0, 0}, {0.6, 0}}), l({{0, 0.5}, {0.45, 0.5}})};
    case 'F': return {l({{0.6, 1}, {0, 1}, {0, 0}}), l({{0, 0.5}, {0.45, 0.5}})};
    case 'G': return {l({{0.6, 0.85}, {0.45, 1}, {0.15, 1}, {0, 0.8}, {0, 0.2}, {0.15, 0}, {0.45, 0}, {0.6, 0.2}, {0.6, 0.45}, {0.35, 0.45}})};
    case 'H': return {l({{0, 0}, {0, 1}}), l({{0.6, 0}, {0.6, 1}}), l({{0, 0.5}, {0.6, 0.5}})};
    case 'I': return {l({{0.3, 0}, {0.3, 1}}), l({{0.1, 1}, {0.5, 1}}), l({{0.1, 0}, {0.5, 0}})};
    case 'J': return {l({{0.6, 1}, {0.6, 0.2}, {0.45, 0}, {0.15, 0}, {0, 0.2}})};
    case 'K': return {l({{0, 0}, {0, 1}}), l({{0.6, 1}, {0, 0.35}}), l({{0.2, 0.55}, {0.6, 0}})};
    case 'L': return {l({{0, 1}, {0, 0}, {0.6, 0}})};
    case 'M': return {l({{0, 0}, {0, 1}, {0.3, 0.5}, {0.6, 1}, {0.6, 0}})};
    case 'N': return {l({{0, 0}, {0, 1}, {0.6, 0}, {0.6, 1}})};
    case 'O': return {o};
    case 'P': return {p};
    case 'Q': return {o, l({{0.35, 0.25}, {0.65, -0.05}})};
    case 'R': return {p, l({{0.3, 0.45}, {0.6, 0}})};
    case 'S': return {l({{0.6, 0.85}, {0.45, 1}, {0.15, 1}, {0, 0.85}, {0, 0.65}, {0.15, 0.5}, {0.45, 0.5}, {0.6, 0.35},
                         {0.6, 0.15}, {0.45, 0}, {0.15, 0}, {0, 0.15}})};
    case 'T': return {l({{0, 1}, {0.6, 1}}), l({{0.3, 1}, {0.3, 0}})};
    case 'U': return {l({{0, 1}, {0, 0.2}, {0.15, 0}, {0.45, 0}, {0.6, 0.2}, {0.6, 1}})};
    case 'V': return {l({{0, 1}, {0.3, 0}, {0.6, 1}})};
    case 'W': return {l({{0, 1}, {0.15, 0}, {0.3, 0.6}, {0.45, 0}, {0.6, 1}})};
    case 'X': return {l({{0, 0}, {0.6, 1}}), l({{0, 1}, {0.6, 0}})};
    case 'Y': return {l({{0, 1}, {0.3, 0.5}, {0.6, 1}}), l({{0.3, 0.5}, {0.3, 0}})};
    case 'Z': return {l({{0, 1}, {0.6, 1}, {0, 0}, {0.6, 0}})};
    default: return {};
  }
}

}  // namespace

std::vector<Line> text_strokes(const std::string& text, double height) {
  constexpr double advance = 0.85;  // letter width 0.6 plus the gap
  std::vector<Line> out;
  double x = 0;
  for (char raw : text) {
    const char c = static_cast<char>(std::toupper(static_cast<unsigned char>(raw)));
    if (c != ' ') {
      Glyph g = glyph(c);
      if (g.empty()) throw ConfigError(std::string("text: the font has no '") + raw + "'; it has the capitals A–Z and spaces");
      for (Line& line : g) {
        for (Eigen::Vector2d& p : line) p.x() += x;
        out.push_back(std::move(line));
      }
    }
    x += advance;
  }
  if (out.empty()) throw ConfigError("text: no letters to draw");
  const double width = x - (advance - 0.6);
  for (Line& line : out)
    for (Eigen::Vector2d& p : line) p = height * (p - Eigen::Vector2d(0.5 * width, 0.5));
  return out;
}

}  // namespace throng::formation
