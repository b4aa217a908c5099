#include <throng/core/assignment.h>

#include <throng/core/errors.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace throng {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

// Rows ≤ columns. `at(r, c)` gives the cost; returns column_of_row. Classic potentials formulation: for each new
// row, Dijkstra over columns on reduced costs cost − u − v (non-negative), then augment along the shortest path.
// Index 0 of u, v, row_of, way is a sentinel (1-based inside, as in the textbook form).
template <class Cost>
std::vector<int> assign_rows(int rows, int cols, const Cost& at, const char* what, const char* row_name) {
  std::vector<double> u(static_cast<std::size_t>(rows) + 1, 0.0), v(static_cast<std::size_t>(cols) + 1, 0.0);
  std::vector<int> row_of(static_cast<std::size_t>(cols) + 1, 0), way(static_cast<std::size_t>(cols) + 1, 0);
  std::vector<double> min_reduced(static_cast<std::size_t>(cols) + 1);
  std::vector<char> used(static_cast<std::size_t>(cols) + 1);

  for (int r = 1; r <= rows; ++r) {
    row_of[0] = r;
    int col0 = 0;
    std::fill(min_reduced.begin(), min_reduced.end(), infinity);
    std::fill(used.begin(), used.end(), 0);
    do {
      used[static_cast<std::size_t>(col0)] = 1;
      const int row0 = row_of[static_cast<std::size_t>(col0)];
      double delta = infinity;
      int col1 = -1;
      for (int c = 1; c <= cols; ++c) {
        if (used[static_cast<std::size_t>(c)]) continue;
        const double entry = at(row0 - 1, c - 1);
        if (entry != infinity) {
          const double reduced = entry - u[static_cast<std::size_t>(row0)] - v[static_cast<std::size_t>(c)];
          if (reduced < min_reduced[static_cast<std::size_t>(c)]) {
            min_reduced[static_cast<std::size_t>(c)] = reduced;
            way[static_cast<std::size_t>(c)] = col0;
          }
        }
        if (min_reduced[static_cast<std::size_t>(c)] < delta) {
          delta = min_reduced[static_cast<std::size_t>(c)];
          col1 = c;
        }
      }
      if (col1 < 0) {
        throw InputError(std::string(what) + ": no complete assignment avoids the forbidden (+infinity) entries; " +
                         row_name + " " + std::to_string(r - 1) + " cannot be paired with the others");
      }
      for (int c = 0; c <= cols; ++c) {
        if (used[static_cast<std::size_t>(c)]) {
          u[static_cast<std::size_t>(row_of[static_cast<std::size_t>(c)])] += delta;
          v[static_cast<std::size_t>(c)] -= delta;
        } else {
          min_reduced[static_cast<std::size_t>(c)] -= delta;
        }
      }
      col0 = col1;
    } while (row_of[static_cast<std::size_t>(col0)] != 0);
    // Augment along the alternating path back to the sentinel.
    do {
      const int col1 = way[static_cast<std::size_t>(col0)];
      row_of[static_cast<std::size_t>(col0)] = row_of[static_cast<std::size_t>(col1)];
      col0 = col1;
    } while (col0 != 0);
  }

  std::vector<int> column_of_row(static_cast<std::size_t>(rows), -1);
  for (int c = 1; c <= cols; ++c) {
    const int r = row_of[static_cast<std::size_t>(c)];
    if (r > 0) column_of_row[static_cast<std::size_t>(r - 1)] = c - 1;
  }
  return column_of_row;
}

}  // namespace

Assignment solve_assignment(const Eigen::Ref<const Eigen::MatrixXd>& cost, const char* what) {
  const int rows = static_cast<int>(cost.rows());
  const int cols = static_cast<int>(cost.cols());
  for (int c = 0; c < cols; ++c) {
    for (int r = 0; r < rows; ++r) {
      const double x = cost(r, c);
      if (std::isnan(x) || x == -infinity) {
        throw InputError(std::string(what) + ": entry (" + std::to_string(r) + ", " + std::to_string(c) + ") is " +
                         (std::isnan(x) ? "NaN" : "-infinity") + "; expected a finite cost or +infinity (forbidden)");
      }
    }
  }

  Assignment out;
  out.column_of_row.assign(static_cast<std::size_t>(rows), -1);
  out.row_of_column.assign(static_cast<std::size_t>(cols), -1);
  if (rows == 0 || cols == 0) return out;

  if (rows <= cols) {
    out.column_of_row = assign_rows(rows, cols, [&](int r, int c) { return cost(r, c); }, what, "row");
    for (int r = 0; r < rows; ++r) out.row_of_column[static_cast<std::size_t>(out.column_of_row[static_cast<std::size_t>(r)])] = r;
  } else {
    out.row_of_column = assign_rows(cols, rows, [&](int c, int r) { return cost(r, c); }, what, "column");
    for (int c = 0; c < cols; ++c) out.column_of_row[static_cast<std::size_t>(out.row_of_column[static_cast<std::size_t>(c)])] = c;
  }
  for (int r = 0; r < rows; ++r) {
    const int c = out.column_of_row[static_cast<std::size_t>(r)];
    if (c >= 0) out.cost += cost(r, c);
  }
  return out;
}

}  // namespace throng
