// The scene's obstacles as agents see them during one step: lists per neighbour-grid cell, the forces of
// Eq. 18–19 (generalised to every core obstacle type) with sliding around obstacles, and the guarantee that a
// move never ends inside an obstacle.
#pragma once

#include <throng/core/obstacle.h>
#include <throng/core/scene.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <span>
#include <vector>

#include "neighbour_grid.h"

namespace throng::sketch::detail {

/// What the obstacles do to a walking agent in one step.
///   push   Σ n (r_block − b) over obstacles whose boundary is nearer than r_block (Eq. 18–19 generalised)
///   pull   the path force, redirected along the boundary when it points into an obstacle (sliding)
///   side   the side the agent goes round on (+1 left of the course, −1 right, 0 no contact), kept across steps
struct ObstacleResponse {
  Eigen::Vector2d push{0, 0};
  Eigen::Vector2d pull{0, 0};
  std::int8_t side = 0;
};

class ObstacleField {
 public:
  /// radius: agent body radius (no move ends closer to a boundary); reach: r_block − ρ, the distance from the
  /// boundary where Eq. 18's push starts; slide: redirect the path force along boundaries.
  ObstacleField(const Scene& scene, double radius, double reach, bool slide)
      : scene_(scene), radius_(radius), reach_(reach), slide_(slide) {}

  /// Lists, for every cell of `grid`, the obstacles whose bounds over [t0, t1], grown by max(reach, radius) and
  /// by radius + look_ahead,
  /// overlap the cell (cells are clamped, so a point outside the grid finds every obstacle near it in its border
  /// cell). `grid` must outlive the next rebuild.
  void rebuild(const NeighbourGrid& grid, double t0, double t1);

  [[nodiscard]] bool empty() const noexcept { return scene_.obstacles.empty(); }

  /// Eq. 18–19 at point p, time t, for a walking agent whose path force is `pull` and whose course direction
  /// (unit) is `heading` at the main-line point `course_point`. With sliding, a pull into the most pressing
  /// obstacle is turned along its boundary, forward along the heading; facing a boundary square-on, the agent
  /// keeps `side`, or picks one: the side the course passes the obstacle on (when its main line runs beside it),
  /// else the side of the obstacle's centre the agent is on (neighbours split the same way, so the two flows
  /// never meet), else the side the pull leans to, else by the parity of `agent`.
  [[nodiscard]] ObstacleResponse respond(const Eigen::Vector2d& p, double t, const Eigen::Vector2d& pull,
                                         const Eigen::Vector2d& heading, const Eigen::Vector2d& course_point,
                                         std::int8_t side, std::uint32_t agent) const;

  /// Eq. 18–19 alone (no sliding): the push on a standing agent.
  [[nodiscard]] Eigen::Vector2d push(const Eigen::Vector2d& p, double t) const;

  /// Obstacles whose boundary lies up to `metres` beyond the agent radius are also listed at the next rebuild, for
  /// brake(); 0 (the default) lists only those within max(reach, radius).
  void look_ahead(double metres) noexcept { look_ahead_ = metres; }

  /// The walking velocity u of an agent at p over the step [t0, t1], limited so that it can still stop short of
  /// every obstacle decelerating at `deceleration` (m/s², > 0): its speed toward an obstacle whose boundary lies g
  /// beyond the agent radius at t0, relative to that boundary, is at most min(√(2 a g), g / (t1 − t0)) (the
  /// braking curve, and no contact within the step). Only the component toward each obstacle is taken away; an
  /// obstacle coming at the agent makes it step aside, and then the rest of u is shortened so that |u| grows
  /// only when the obstacle comes faster than u was. Following the curve costs about `deceleration` more than
  /// the step already changed u. Obstacles beyond look_ahead are not seen.
  [[nodiscard]] Eigen::Vector2d brake(const Eigen::Vector2d& p, double t0, double t1, Eigen::Vector2d u,
                                      double deceleration) const;

  /// The fastest any obstacle's boundary moves (m/s): over each pair of pose keys, the translation's speed plus
  /// the turn rate times the shape's farthest point from its own origin. 0 when every obstacle is static.
  [[nodiscard]] double fastest_boundary_speed() const;

  /// True when a body of the agent radius at p overlaps an obstacle at time t.
  [[nodiscard]] bool overlaps(const Eigen::Vector2d& p, double t) const;

  /// Makes the move from `from` to `to` end clear of obstacles at time t: cut where it first enters one
  /// (sampled every half radius, so no wall can be jumped), project out of any still overlapped, else fall back
  /// to `from` if that is clear. False when no clear place was found (`to` is then the best found).
  bool keep_clear(Eigen::Vector2d from, Eigen::Vector2d& to, double t) const;

 private:
  template <class F>
  void for_each_near(const Eigen::Vector2d& p, F&& f) const {
    const std::size_t c = grid_->cell(p.x(), p.y());
    for (std::uint32_t i = start_[c]; i < start_[c + 1]; ++i) {
      const std::uint32_t o = ids_[i];
      if (boxes_[o].contains(p)) f(o, scene_.obstacles[o]);
    }
  }

  const Scene& scene_;
  double radius_, reach_;
  bool slide_;
  double look_ahead_ = 0.0;
  const NeighbourGrid* grid_ = nullptr;
  std::vector<Eigen::AlignedBox2d> boxes_;        // #obstacles, bounds over the step grown for the cell lists
  std::vector<Eigen::AlignedBox2d> shape_boxes_;  // #obstacles, bounds over the step grown by max(reach, radius)
  std::vector<std::uint32_t> start_;        // #cells + 1
  std::vector<std::uint32_t> ids_;
};

}  // namespace throng::sketch::detail
