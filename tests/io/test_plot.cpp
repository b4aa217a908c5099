#include "crowd_fixtures.h"
#include "test_paths.h"

#include <throng/core/errors.h>
#include <throng/io/plot.h>

#include <catch2/catch.hpp>

#include <fstream>
#include <iterator>
#include <regex>

using namespace throng;

namespace {
std::string text(const std::filesystem::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (auto p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}
}  // namespace

TEST_CASE("the SVG shows a trajectory per presence span, agents at the chosen frames, obstacles and a scale bar") {
  const auto dir = test::scratch_dir("io_plot");
  const CrowdFile f = test::rich_crowd();
  PlotOptions o;
  o.frames = {2, -1};
  o.title = "rich";
  write_plot(dir / "p.svg", {{.file = &f, .label = "after"}}, o);
  const std::string svg = text(dir / "p.svg");
  CHECK(count(svg, "<polyline") == 4);   // each agent's presence is one span
  // Frame 2: all 4 agents; last frame: 3 present. Plus the circular obstacle.
  CHECK(count(svg, "<circle") == 4 + 3 + 1);
  CHECK(count(svg, "<polygon") == 2);    // the moving cart at its two drawn frames
  CHECK(std::regex_search(svg, std::regex(">[0-9.]+ m</text>")));
  CHECK(svg.find(">rich</text>") != std::string::npos);
  CHECK(svg.find("after — 4 agents, 5 frames") != std::string::npos);
}

TEST_CASE("an overlay is drawn first in one colour, dashed") {
  const auto dir = test::scratch_dir("io_plot_overlay");
  const CrowdFile a = test::rich_crowd();
  CrowdFile b = a;
  for (double& x : b.motion.positions) x += 1.0;
  write_plot(dir / "p.svg", {{.file = &a, .label = "before", .colour = "#9a9a9a", .opacity = 0.8, .dashed = true}, {.file = &b, .label = "after"}}, {});
  const std::string svg = text(dir / "p.svg");
  CHECK(count(svg, "<polyline stroke=\"#9a9a9a\"") == 4);
  CHECK(svg.find("stroke-dasharray") < svg.find("<polyline stroke=\"#1f77b4\""));
}

TEST_CASE("PNG goes through rsvg-convert and bad extensions and frames are config errors") {
  const auto dir = test::scratch_dir("io_plot_png");
  const CrowdFile f = test::rich_crowd();
  write_plot(dir / "p.png", {{.file = &f, .label = "x"}}, {});
  std::ifstream in(dir / "p.png", std::ios::binary);
  char magic[4]{};
  in.read(magic, 4);
  CHECK(std::string(magic + 1, 3) == "PNG");
  CHECK_FALSE(std::filesystem::exists(dir / "p.svg"));
  CHECK_THROWS_AS(write_plot(dir / "p.bmp", {{.file = &f, .label = "x"}}, {}), ConfigError);
  PlotOptions o;
  o.frames = {99};
  CHECK_THROWS_AS(write_plot(dir / "q.svg", {{.file = &f, .label = "x"}}, o), ConfigError);
  CHECK_FALSE(std::filesystem::exists(dir / "q.svg"));
}

TEST_CASE("extra polylines and markers are drawn in world coordinates") {
  const auto dir = test::scratch_dir("io_plot_extra");
  const CrowdFile f = test::rich_crowd();
  PlotLayer layer{.file = &f, .label = "x"};
  layer.draw_trajectories = false;
  layer.polylines.push_back({.points = {{0, 0}, {40, 0}}, .colour = "#123456", .width_px = 2.0, .dashed = true});
  layer.markers.push_back({.at = {40, 0}, .colour = "#abcdef", .radius_px = 4.0});
  write_plot(dir / "p.svg", {layer}, {});
  const std::string svg = text(dir / "p.svg");
  CHECK(count(svg, "<polyline") == 1);  // the extra line only: trajectories are off
  CHECK(svg.find("stroke=\"#123456\"") != std::string::npos);
  CHECK(svg.find("fill=\"#abcdef\"") != std::string::npos);
}

TEST_CASE("agent discs keep a minimum size in pixels on a large scene") {
  const auto dir = test::scratch_dir("io_plot_min_disc");
  // A 140 m course at 1200 px: 8 px a metre, a 0.25 m agent would be a disc of 2 px.
  CrowdFile f;
  f.motion = CrowdMotion::with_shape(2, 2, 0.25);
  f.motion.times = {0.0, 1.0};
  for (std::size_t t = 0; t < 2; ++t) {
    f.motion.position(t, 0) = Eigen::Vector3d(0, 0, 0);
    f.motion.position(t, 1) = Eigen::Vector3d(140, 10, 0);
  }
  const auto radii = [&](const PlotOptions& o) {
    write_plot(dir / "p.svg", {{.file = &f, .label = "course"}}, o);
    const std::string svg = text(dir / "p.svg");
    std::vector<double> r;
    const std::regex circle("<circle cx=\"[-0-9.]+\" cy=\"[-0-9.]+\" r=\"([0-9.]+)\"");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), circle); it != std::sregex_iterator(); ++it) {
      r.push_back(std::stod((*it)[1].str()));
    }
    return r;
  };
  PlotOptions o;
  const std::vector<double> r = radii(o);
  REQUIRE(r.size() == 4);  // 2 agents at 2 frames
  for (double v : r) CHECK(v == o.min_agent_radius_px);
  CHECK(o.min_agent_radius_px >= 3.0);
  // Where the scale makes discs larger than the minimum, they keep their true radius.
  o.min_agent_radius_px = 0.5;
  for (double v : radii(o)) CHECK_THAT(v, Catch::Matchers::WithinAbs(0.25 * 1120.0 / 140.0, 0.01));
}

TEST_CASE("legend entries flow after their layer, ring markers are outlines, agents take their own colours") {
  const auto dir = test::scratch_dir("io_plot_legend");
  const CrowdFile f = test::rich_crowd();
  PlotLayer layer{.file = &f, .label = "tiling"};
  for (int k = 0; k < 30; ++k) layer.legend.push_back({"patch type number " + std::to_string(k), group_colour(k), PlotLegendEntry::Symbol::line});
  layer.legend.push_back({"seam", "#000000", PlotLegendEntry::Symbol::ring});
  layer.markers.push_back({.at = {1, 1}, .colour = "#0a0b0c", .radius_px = 4.0, .ring = true});
  layer.agent_colour = [](std::size_t, std::size_t agent) -> std::optional<std::string> {
    if (agent == 0) return "#fedcba";
    return std::nullopt;
  };
  PlotOptions o;
  o.frames = {2, -1};
  write_plot(dir / "p.svg", {layer}, o);
  const std::string svg = text(dir / "p.svg");
  for (int k = 0; k < 30; ++k) CHECK(svg.find(">patch type number " + std::to_string(k) + "</text>") != std::string::npos);
  CHECK(count(svg, "fill=\"none\" stroke=\"#0a0b0c\"") == 1);
  CHECK(count(svg, "fill=\"#fedcba\"") == 2);  // agent 0 at both frames
  // 30 entries of about 200 px do not fit one 1200 px row: the legend wraps and the drawing starts below it.
  std::smatch m;
  REQUIRE(std::regex_search(svg, m, std::regex(">seam</text>")));
  const std::regex text_y("<text x=\"[0-9.]+\" y=\"([0-9.]+)\">patch type number 29</text>");
  std::smatch last;
  REQUIRE(std::regex_search(svg, last, text_y));
  CHECK(std::stod(last[1].str()) > 44 + 20 * 3);
}
