// Turning a Request (pins, drags, general constraints in the user's terms: agent ids and source frames) into
// what the solver needs: handled vertices with targets, and constraint rows C x = d over the unknowns.
#pragma once

#include <throng/edit/edit.h>
#include <throng/linalg/solver_options.h>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace throng::edit {

/// The request in solver terms. Unknown 2v is x of vertex v, 2v + 1 its y.
///   handle_vertices  #handles graph vertices, increasing;   handle_targets  #handles by 2 (metres)
///   C                #rows by 2·#vertices;                    d               #rows
///   row_source       #rows, the index k of constraints[k] each row comes from (a row per axis and sample of
///                    a relative position, velocity, acceleration or sum; one per sample on a line; one per Row)
///   handle_basis     2·#handles by #coordinates, handle_coordinates #coordinates: the pinned unknowns (in the
///                    order of pinned_unknowns()) are handle_basis · handle_coordinates. A pin has 2 coordinates
///                    (its position); a drag 4 (cos θ, sin θ, t): each of its vertices goes to R(θ) p + t with
///                    t = pivot − R(θ) pivot + offset, so the basis depends on the original positions only and a
///                    new drag of the same handles is a new coordinate vector (linalg: set_pin_basis).
struct ResolvedRequest {
  std::vector<Eigen::Index> handle_vertices;
  Eigen::Matrix<double, Eigen::Dynamic, 2> handle_targets;
  linalg::SparseMatrix handle_basis;
  Eigen::VectorXd handle_coordinates;
  linalg::SparseMatrix C;
  Eigen::VectorXd d;
  std::vector<std::size_t> row_source;
  /// What redrag() needs of drags[k]: the handle rows it placed (increasing), whether it placed them alone (no
  /// vertex of them placed twice, by it or by another entry), its first coordinate, and its default pivot (the
  /// centroid of its selected original positions, kept whether or not the drag gives a pivot).
  struct DragPlacement {
    std::vector<Eigen::Index> rows;
    bool alone = true;
    Eigen::Index column = 0;
    Eigen::Vector2d centroid{0, 0};
  };
  std::vector<DragPlacement> drags;

  /// The pinned unknowns: 2v, 2v + 1 for each handled vertex, in handle order.
  [[nodiscard]] std::vector<Eigen::Index> pinned_unknowns() const;
};

/// The source frames the request names, to be made samples: pin frames, both frames of each velocity, the three
/// frames of each acceleration, every frame a row's terms name, and every frame of every drag and constraint range
/// (clamped to the clip), so that the output, which passes through the samples, meets each handle and constraint
/// at every frame it covers (not only at the regular samples). Validates agents and frames against `clip`
/// (built without them; crowd_ids are all the crowd's ids, for messages) and throws ConfigError naming the entry, for example "pins[2].frame 400 is outside
/// the clip [0, 299]" or "drags[0].agents: agent 17 is absent at some frames of the clip ...".
[[nodiscard]] std::vector<std::size_t> required_frames(const Request& request, const Clip& clip,
                                                     const std::vector<std::int64_t>& crowd_ids);

/// Resolves the request on the final clip. Frames of pins, velocities, accelerations and rows must be samples
/// (ConfigError otherwise); ranges act on the samples inside them. A constraint's entries are checked as
/// required_frames checks them (agents, frames, finite numbers, a sum's weights, a row's distinct non-zero terms). Two handles placing one vertex differently are a
/// NumericalError (contradictory).
[[nodiscard]] ResolvedRequest resolve(const Request& request, const Clip& clip, const std::vector<std::int64_t>& crowd_ids);

/// Brings `resolved`, resolve(before, clip, …), to `request` when the two differ only in their drags' offsets,
/// rotations and pivots (an interactive drag of the same handles; every other value the same bit for bit) and
/// every drag that changed placed its vertices alone: only those drags' coordinates and targets are computed
/// again, the values resolve(request, clip, …) gives, bit for bit (handles, basis, constraints and the other
/// drags' targets are unchanged). So a drag costs its own handles, not the request's: a request that holds every
/// agent's first and last frame has 2 × agents handles. Returns false, `resolved` untouched, when the requests
/// differ otherwise or a changed drag's motion or target is not finite: resolve anew (it says what is wrong).
/// Never throws but for memory.
[[nodiscard]] bool redrag(ResolvedRequest& resolved, const Request& before, const Request& request, const Clip& clip);

/// "constraints[3] (velocity of agent 12 at frame 40)": how messages name a general constraint.
[[nodiscard]] std::string describe(const Request& request, std::size_t constraint);

}  // namespace throng::edit
