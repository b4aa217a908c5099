#include "eigenbasis.h"

#include "dense.h"

#include <throng/core/assignment.h>
#include <throng/core/errors.h>

#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

namespace throng::formation {
namespace {

// Repeated eigenvalues: relative spread below this is one eigenspace whose basis LAPACK chose arbitrarily.
constexpr double repeated_eigenvalue_tolerance = 1e-8;

// Rotates the target vectors of each repeated eigenvalue onto the source vectors of the same indices.
void align_repeated_eigenspaces(const Eigen::MatrixXd& source, Eigenbasis& target) {
  const Eigen::Index n = target.values.size();
  const double scale = std::max(std::abs(target.values(n - 1)), std::numeric_limits<double>::min());
  for (Eigen::Index first = 1; first < n;) {
    Eigen::Index last = first + 1;
    while (last < n && target.values(last) - target.values(last - 1) <= repeated_eigenvalue_tolerance * scale) ++last;
    const Eigen::Index size = last - first;
    if (size >= 2) {
      const Eigen::MatrixXd overlap = target.vectors.middleCols(first, size).transpose() * source.middleCols(first, size);
      const Eigen::JacobiSVD<Eigen::MatrixXd> svd(overlap, Eigen::ComputeFullU | Eigen::ComputeFullV);
      const Eigen::MatrixXd rotation = svd.matrixU() * svd.matrixV().transpose();
      target.vectors.middleCols(first, size) = (target.vectors.middleCols(first, size) * rotation).eval();
    }
    first = last;
  }
}

// Maximum bipartite matching size (Hopcroft–Karp) on rows/columns 1..n−1 with edges |g(r, c)| ≥ threshold.
class BottleneckMatcher {
 public:
  explicit BottleneckMatcher(const Eigen::MatrixXd& magnitude) : a_(magnitude), n_(static_cast<int>(magnitude.rows())) {}

  bool perfect(double threshold) {
    threshold_ = threshold;
    match_row_.assign(static_cast<std::size_t>(n_), -1);
    match_col_.assign(static_cast<std::size_t>(n_), -1);
    int matched = 0;
    while (bfs()) {
      for (int r = 1; r < n_; ++r)
        if (match_row_[static_cast<std::size_t>(r)] < 0 && dfs(r)) ++matched;
    }
    return matched == n_ - 1;
  }

 private:
  bool allowed(int r, int c) const { return a_(r, c) >= threshold_; }

  bool bfs() {
    dist_.assign(static_cast<std::size_t>(n_), -1);
    std::queue<int> queue;
    for (int r = 1; r < n_; ++r) {
      if (match_row_[static_cast<std::size_t>(r)] < 0) {
        dist_[static_cast<std::size_t>(r)] = 0;
        queue.push(r);
      }
    }
    bool found = false;
    while (!queue.empty()) {
      const int r = queue.front();
      queue.pop();
      for (int c = 1; c < n_; ++c) {
        if (!allowed(r, c)) continue;
        const int next = match_col_[static_cast<std::size_t>(c)];
        if (next < 0) {
          found = true;
        } else if (dist_[static_cast<std::size_t>(next)] < 0) {
          dist_[static_cast<std::size_t>(next)] = dist_[static_cast<std::size_t>(r)] + 1;
          queue.push(next);
        }
      }
    }
    return found;
  }

  bool dfs(int r) {
    for (int c = 1; c < n_; ++c) {
      if (!allowed(r, c)) continue;
      const int next = match_col_[static_cast<std::size_t>(c)];
      if (next < 0 || (dist_[static_cast<std::size_t>(next)] == dist_[static_cast<std::size_t>(r)] + 1 && dfs(next))) {
        match_row_[static_cast<std::size_t>(r)] = c;
        match_col_[static_cast<std::size_t>(c)] = r;
        return true;
      }
    }
    dist_[static_cast<std::size_t>(r)] = -1;
    return false;
  }

  const Eigen::MatrixXd& a_;
  int n_;
  double threshold_ = 0.0;
  std::vector<int> match_row_, match_col_, dist_;
};

}  // namespace

Eigenbasis laplacian_eigenbasis(Eigen::MatrixXd laplacian) {
  Eigenbasis out;
  dense::symmetric_eigen(laplacian, out.values);
  out.vectors = std::move(laplacian);
  if (out.vectors.cols() > 0) out.vectors.col(0).setConstant(1.0 / std::sqrt(static_cast<double>(out.vectors.rows())));
  return out;
}

std::vector<int> greedy_order(const Eigen::MatrixXd& g) {
  const int n = static_cast<int>(g.rows());
  std::vector<int> order(static_cast<std::size_t>(n), 0);
  std::vector<char> used(static_cast<std::size_t>(n), 0);
  const Eigen::MatrixXd by_row = g.transpose().cwiseAbs();  // column j = |g(j, ·)|, contiguous
  for (int j = 1; j < n; ++j) {
    int best = -1;
    for (int c = 1; c < n; ++c)
      if (!used[static_cast<std::size_t>(c)] && (best < 0 || by_row(c, j) > by_row(best, j))) best = c;
    used[static_cast<std::size_t>(best)] = 1;
    order[static_cast<std::size_t>(j)] = best;
  }
  return order;
}

std::vector<int> max_min_order(const Eigen::MatrixXd& g) {
  const int n = static_cast<int>(g.rows());
  std::vector<int> order(static_cast<std::size_t>(n), 0);
  if (n <= 2) {
    if (n == 2) order[1] = 1;
    return order;
  }
  const Eigen::MatrixXd magnitude = g.cwiseAbs();
  // Candidate thresholds: the distinct magnitudes between the greedy order's minimum (always achievable) and the
  // smallest row maximum (never exceedable).
  const std::vector<int> greedy = greedy_order(g);
  double low = std::numeric_limits<double>::infinity(), high = std::numeric_limits<double>::infinity();
  for (int j = 1; j < n; ++j) {
    low = std::min(low, magnitude(j, greedy[static_cast<std::size_t>(j)]));
    high = std::min(high, magnitude.row(j).tail(n - 1).maxCoeff());
  }
  std::vector<double> candidates;
  for (int c = 1; c < n; ++c)
    for (int r = 1; r < n; ++r)
      if (magnitude(r, c) >= low && magnitude(r, c) <= high) candidates.push_back(magnitude(r, c));
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  BottleneckMatcher matcher(magnitude);
  std::size_t lo = 0, hi = candidates.size() - 1;  // candidates[lo] is feasible (the greedy minimum)
  while (lo < hi) {
    const std::size_t mid = lo + (hi - lo + 1) / 2;
    if (matcher.perfect(candidates[mid])) lo = mid;
    else hi = mid - 1;
  }
  const double bottleneck = candidates[lo];
  Eigen::MatrixXd cost(n - 1, n - 1);
  for (int c = 1; c < n; ++c)
    for (int r = 1; r < n; ++r)
      cost(r - 1, c - 1) = magnitude(r, c) >= bottleneck ? -magnitude(r, c) : std::numeric_limits<double>::infinity();
  const Assignment assignment = solve_assignment(cost, "eigenvector reordering");
  for (int r = 1; r < n; ++r) order[static_cast<std::size_t>(r)] = assignment.column_of_row[static_cast<std::size_t>(r - 1)] + 1;
  return order;
}

Eigenbasis align_basis(const Eigenbasis& source, Eigenbasis target, Reordering reordering) {
  const Eigen::Index n = source.vectors.cols();
  if (n <= 1) return target;
  // The source's own eigenvalue order: visit[j] is the source column holding its j-th smallest eigenvalue
  // (stable: equal values keep their column order; column 0, λ = 0, first).
  std::vector<Eigen::Index> visit(static_cast<std::size_t>(n));
  for (Eigen::Index j = 0; j < n; ++j) visit[static_cast<std::size_t>(j)] = j;
  std::stable_sort(visit.begin() + 1, visit.end(),
                   [&](Eigen::Index a, Eigen::Index b) { return source.values(a) < source.values(b); });
  Eigen::MatrixXd sorted(n, n);
  for (Eigen::Index j = 0; j < n; ++j) sorted.col(j) = source.vectors.col(visit[static_cast<std::size_t>(j)]);
  align_repeated_eigenspaces(sorted, target);

  const Eigen::MatrixXd g = dense::multiply(sorted, true, target.vectors);
  std::vector<int> order(static_cast<std::size_t>(n));
  for (Eigen::Index j = 0; j < n; ++j) order[static_cast<std::size_t>(j)] = static_cast<int>(j);
  if (reordering == Reordering::greedy) order = greedy_order(g);
  if (reordering == Reordering::max_min) order = max_min_order(g);

  Eigenbasis aligned{Eigen::MatrixXd(n, n), Eigen::VectorXd(n)};
  Eigen::MatrixXd g_aligned(n, n);  // sortedᵀ · (the aligned vectors in the sorted order)
  for (Eigen::Index j = 0; j < n; ++j) {
    const int from = order[static_cast<std::size_t>(j)];
    const Eigen::Index column = visit[static_cast<std::size_t>(j)];
    const double sign = g(j, from) < 0 ? -1.0 : 1.0;
    aligned.vectors.col(column) = sign * target.vectors.col(from);
    aligned.values(column) = target.values(from);
    g_aligned.col(j) = sign * g.col(from);
  }
  const int det = dense::determinant_sign(g_aligned);
  if (det == 0) throw NumericalError("spectral formation: eigenbases are not orthogonal (singular rotation)");
  if (det < 0) {
    Eigen::Index least = 1;
    for (Eigen::Index j = 2; j < n; ++j)
      if (std::abs(g_aligned(j, j)) < std::abs(g_aligned(least, least))) least = j;
    aligned.vectors.col(visit[static_cast<std::size_t>(least)]) *= -1.0;
  }
  return aligned;
}

}  // namespace throng::formation
