// Minimum-cost assignment (the linear assignment problem): pair rows with columns so the summed cost is least.
// Shared by formation (individual matching between keyframes) and stitch (matching characters across clips).
#pragma once

#include <Eigen/Core>

#include <vector>

namespace throng {

/// An optimal pairing of the rows and columns of a cost matrix.
///   column_of_row  #rows; the column paired with each row, −1 for a row left unpaired (only when rows > cols)
///   row_of_column  #cols; the row paired with each column, −1 for a column left unpaired (only when cols > rows)
///   cost           sum of cost(r, column_of_row[r]) over the pairs
struct Assignment {
  std::vector<int> column_of_row;
  std::vector<int> row_of_column;
  double cost = 0.0;
};

/// Exact minimum-cost assignment of `cost` (#rows by #cols, any shape): min(#rows, #cols) pairs, each row and
/// each column used at most once, the sum of the paired costs least. Rectangular matrices are allowed: when
/// #rows ≤ #cols every row is paired, otherwise every column is.
///
/// Entries equal to +infinity are forbidden pairs. Throws InputError when an entry is NaN or −infinity, or when
/// no pairing of the required size avoids the forbidden pairs. `what` names the matrix in messages.
///
/// Algorithm: shortest augmenting paths with dual potentials (Hungarian method in the Jonker–Volgenant form),
/// O(k² · m) for k = min(#rows, #cols), m = max(#rows, #cols); exact for finite costs up to rounding.
/// Deterministic: rows are inserted in index order and, among equally short paths, the lowest column index
/// wins, so equal inputs give the same pairing on every platform and thread count.
[[nodiscard]] Assignment solve_assignment(const Eigen::Ref<const Eigen::MatrixXd>& cost,
                                          const char* what = "cost matrix");

}  // namespace throng
