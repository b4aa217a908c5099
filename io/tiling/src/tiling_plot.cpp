#include <throng/io/tiling_plot.h>

#include <map>
#include <memory>
#include <tuple>

namespace throng {
namespace {

constexpr const char* connection_colour = "#202020";
constexpr const char* seam_colour = "#000000";
constexpr const char* seam_line_colour = "#b0b0b0";

// When a character walks through a fragment copy: [t0, t1] and the colour of the fragment's patch type.
struct Span {
  double t0, t1;
  std::string colour;
};

}  // namespace

std::string patch_type_colour(std::size_t rank) {
  static const char* lighter[] = {"#aec7e8", "#ffbb78", "#98df8a", "#ff9896", "#c5b0d5", "#c49c94", "#f7b6d2", "#9edae5"};
  const std::size_t k = rank % 20;
  return k < 12 ? group_colour(static_cast<std::int64_t>(k)) : lighter[k - 12];
}

void add_tiling(PlotLayer& layer, const TilingData& data) {
  const tiling::Tiling& t = data.tiling;
  const tiling::PatchLibrary& lib = data.library;
  const Region& tile = *data.environment.scene.region;
  const Eigen::Vector3d L = tiling::periods(tile);

  // Colours by the types used, in library order; instance counts for the legend.
  std::map<std::size_t, std::size_t> used;  // type → instances
  for (const tiling::Instance& i : t.instances) ++used[i.type];
  std::map<std::size_t, std::string> colour;
  for (const auto& [type, count] : used) colour[type] = patch_type_colour(colour.size());

  layer.draw_trajectories = false;
  const double width = t.instances.size() > 1500 ? 0.8 : (t.instances.size() > 300 ? 1.1 : 1.5);
  const int nx = data.repeat[0], ny = data.repeat[1];
  for (int cx = 0; cx < nx; ++cx) {
    for (int cy = 0; cy < ny; ++cy) {
      const Eigen::Vector2d shift(cx * L.x(), cy * L.y());
      for (const tiling::Instance& inst : t.instances) {
        const tiling::PatchType& type = lib.types[inst.type];
        for (std::size_t f = 0; f < inst.paths.size(); ++f) {
          PlotPolyline line;
          for (const Eigen::Vector2d& p : inst.paths[f].positions) line.points.push_back(p + shift);
          line.colour = colour[inst.type];
          line.width_px = type.fragments[f].is_character() ? width : 2 * width;
          line.opacity = 0.9;
          line.dashed = !type.fragments[f].is_character();
          layer.polylines.push_back(std::move(line));
        }
      }
      for (const tiling::Connection& c : t.connections) {
        const tiling::Path& from = t.instances[c.from.instance].paths[c.from.fragment];
        const tiling::Path& to = t.instances[c.to.instance].paths[c.to.fragment];
        if (c.image == std::array<int, 3>{0, 0, 0}) {
          layer.markers.push_back({.at = from.positions.back() + shift, .colour = connection_colour, .radius_px = 2.2});
        } else {
          layer.markers.push_back({.at = from.positions.back() + shift, .colour = seam_colour, .radius_px = 4.0, .ring = true});
          layer.markers.push_back({.at = to.positions.front() + shift, .colour = seam_colour, .radius_px = 4.0, .ring = true});
        }
      }
      // The copy's outline: where the seams run.
      if (nx * ny > 1) {
        const Eigen::Vector2d a = tile.min + shift, b = tile.max + shift;
        layer.polylines.push_back({.points = {a, {b.x(), a.y()}, b, {a.x(), b.y()}, a},
                                   .colour = seam_line_colour, .width_px = 1.0, .opacity = 1.0, .dashed = true});
      }
    }
  }

  for (const auto& [type, count] : used) {
    layer.legend.push_back({lib.types[type].name + " (" + std::to_string(count) + ")", colour[type], PlotLegendEntry::Symbol::line});
  }
  std::size_t joins = 0, seams = 0;
  for (const tiling::Connection& c : t.connections) (c.image == std::array<int, 3>{0, 0, 0} ? joins : seams) += 1;
  layer.legend.push_back({"connection (" + std::to_string(joins) + ")", connection_colour, PlotLegendEntry::Symbol::dot});
  if (seams > 0) {
    layer.legend.push_back({"seam connection (" + std::to_string(seams) + ")", seam_colour, PlotLegendEntry::Symbol::ring});
  }

  // Each agent's colour over time: the type of the fragment copy it walks through.
  auto spans = std::make_shared<std::vector<std::vector<Span>>>(data.pieces.size());
  for (std::size_t a = 0; a < data.pieces.size(); ++a) {
    for (const tiling::AgentPiece& piece : data.pieces[a]) {
      const tiling::Instance& inst = t.instances[piece.fragment.instance];
      const tiling::Path& p = inst.paths[piece.fragment.fragment];
      const double shift = piece.copy[2] * L.z();
      (*spans)[a].push_back({p.times.front() + shift, p.times.back() + shift, colour[inst.type]});
    }
  }
  const std::vector<double> times = layer.file->motion.times;
  layer.agent_colour = [spans, times](std::size_t frame, std::size_t agent) -> std::optional<std::string> {
    if (agent >= spans->size() || frame >= times.size()) return std::nullopt;
    for (const Span& s : (*spans)[agent]) {
      if (times[frame] >= s.t0 && times[frame] <= s.t1) return s.colour;
    }
    return std::nullopt;
  };
}

}  // namespace throng
