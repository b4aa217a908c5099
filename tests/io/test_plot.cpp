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
  CHECK_THROWS_AS(write_plot(dir / "p.gif", {{.file = &f, .label = "x"}}, {}), ConfigError);
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
