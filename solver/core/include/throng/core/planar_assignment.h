// The minimum-total-distance assignment between two point sets in the plane, without the n × n cost matrix:
// what the stitch's boundary matching needs at 10,000 agents (the dense solver's O(n³) time and n² memory,
// 800 MB and hours there, are what it replaces).
#pragma once

#include <throng/core/assignment.h>
#include <throng/core/planar_index.h>

#include <vector>

namespace throng {

/// The exact minimum-cost assignment of `rows` to `cols` (both n × 2, finite, the same n) for the cost
/// |rows_i − cols_k| (Euclidean distance): the same least total as solve_assignment on the dense matrix of those
/// distances, up to rounding (among pairings of equal total, which one is returned may differ). Every row is
/// paired. Throws InputError naming `what` when the counts differ or a coordinate is not finite.
///
/// Algorithm: shortest augmenting paths with dual potentials (Jonker–Volgenant: column reduction, then one
/// Dijkstra search per free row) over a sparse candidate graph: each row's 8 nearest columns and each column's 8
/// nearest rows (k-d trees), as placed and through the optimal transport map between the two sets' Gaussian fits
/// (so that sets lying apart or stretched one against the other still meet their partners); a row whose search
/// reaches no free column gains the free column of least reduced cost. Then the dual certificate over all n²
/// pairs (compared squared, vectorised, rows in parallel): each row with a pair whose reduced
/// cost is negative beyond rounding gains its 8 most violated pairs and is paired again; repeated until no row
/// has one. The certificate makes the result exact, not a heuristic. From `subsample_from` points on, the search starts
/// instead from the potentials of a half subsample's optimum (found the same way), with each row's 96 columns of
/// least reduced cost under them as candidates: where very many pairings cost nearly the same, the
/// optimum's pairs lie far outside any geometric neighbourhood.
/// Cost: memory O(n) times the candidates a row has (about 100; a state carried over many calls keeps the
/// candidates of all of them); time grows with how far the optimum lies from the candidates. Sets
/// that overlap take a few rounds; stretched lattices apart, tens (two 10,000-point lattices 35 m apart: 7.2 s on
/// 2 cores; two 5,000-point ones 5.3 s).
/// Deterministic: rows are paired in index order, ties in the searches go to the lowest column index, the
/// subsample is a fixed shuffle, and the certificate's parallel rows do not interact, so the pairing is the same whatever the thread count.
///
/// `state` (optional): what the previous call on sets of the same size left, to start from; this call's is
/// left in it. For a series of calls on the same points moved a little (the stitch's rounds of match and
/// align), where most pairs stay optimal: the previous potentials and candidates are kept, the previous pairs
/// that are still the least over their row's candidates stay, the other rows are paired again, and the
/// certificate decides as always (so the total is the same as without it; among equal totals the pairing may
/// differ). When a point moved farther than the columns' typical spacing (median nearest-neighbour distance)
/// since the state's call (starting from it was then measured slower than afresh), or the state is of another
/// size or broken, the call starts afresh and replaces it.
/// `subsample_from`: the size from which a search without a state starts from a subsample (a tuning knob, the
/// total is the same; tests lower it to exercise that path on sets the dense solver checks quickly).
struct PlanarAssignmentState {
  std::vector<double> potentials;                ///< per column
  std::vector<std::vector<int>> candidates;      ///< per row: candidate columns, increasing
  std::vector<int> column_of_row;                ///< the pairing
  PlanarPoints rows, cols;                       ///< the points it was found for
  bool resumed = false;                          ///< whether that call started from the state before it
};
[[nodiscard]] Assignment assign_planar(const Eigen::Ref<const PlanarPoints>& rows,
                                       const Eigen::Ref<const PlanarPoints>& cols, const char* what = "points",
                                       PlanarAssignmentState* state = nullptr, Eigen::Index subsample_from = 2000);

}  // namespace throng
