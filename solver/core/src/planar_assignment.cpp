#include <throng/core/planar_assignment.h>

#include <throng/core/errors.h>
#include <throng/core/parallel.h>
#include <throng/core/random.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <string>
#include <utility>
#include <vector>

namespace throng {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();
constexpr std::size_t first_candidates = 8;  // nearest columns per row (and nearest rows per column) to start
constexpr double rounding = 1e-10;           // relative to the sets' extent: reduced costs above −this are ≥ 0
constexpr std::size_t certificate_grain = 64;  // rows per parallel task of the certificate
constexpr std::size_t added_per_row = 8;       // most violated pairs a row found by the certificate gains
constexpr Eigen::Index coarse_ratio = 2;        // the subsample: one row and one column in two
constexpr std::size_t dual_near = 96;          // columns of least reduced cost a row gains from those potentials
constexpr std::uint64_t subsample_seed = 0x5eed;  // the subsample's shuffle (fixed: same input, same pairing)

// x ↦ map·(x − from) + to: the optimal transport map between two Gaussians (means from, to; covariances A, B),
// map = A^−½ (A^½ B A^½)^½ A^−½, symmetric positive definite. With the sets' means and covariances it carries
// one set onto where the other lies, translated, stretched or squeezed alike. A set on a line or at one point
// gives the translation alone.
struct Transport {
  Eigen::Vector2d from, to;
  Eigen::Matrix2d map = Eigen::Matrix2d::Identity();
};

Transport gaussian_transport(const PlanarPoints& rows, const PlanarPoints& cols) {
  Transport t;
  t.from = rows.colwise().mean().transpose();
  t.to = cols.colwise().mean().transpose();
  const auto covariance = [](const PlanarPoints& p, const Eigen::Vector2d& mean) {
    const PlanarPoints centred = p.rowwise() - mean.transpose();
    return Eigen::Matrix2d(centred.transpose() * centred / static_cast<double>(p.rows()));
  };
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> a(covariance(rows, t.from));
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> b(covariance(cols, t.to));
  const auto flat = [](const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>& e) {
    return !(e.eigenvalues()(0) > 1e-12 * e.eigenvalues()(1));
  };
  if (flat(a) || flat(b)) return t;
  const Eigen::Matrix2d root = a.operatorSqrt(), inverse_root = a.operatorInverseSqrt();
  const Eigen::Matrix2d middle = root * b.eigenvectors() * b.eigenvalues().asDiagonal() * b.eigenvectors().transpose() * root;
  t.map = inverse_root * Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(0.5 * (middle + middle.transpose())).operatorSqrt() * inverse_root;
  return t;
}

// Shortest augmenting paths over a sparse candidate graph. State between searches (Jonker–Volgenant):
//   v        column potentials (from the column reduction, a subsample's or a previous call's; searches only
//            lower them);
//   paired rows: c(i, col_of[i]) − v[col_of[i]] = min over the row's candidates k of c(i, k) − v[k] (tight), so
//            every candidate's reduced cost c(i, k) − u_i − v_k is ≥ 0 with u_i the row's own;
//   free rows: no condition (a row whose candidates grow past its pairing is freed).
// When every row is paired and the condition holds for all n² pairs (the certificate), the pairing is optimal:
// Σ c(i, col_of[i]) = Σ u_i + Σ v_k ≤ the cost of any pairing.
class SparseAssignment {
 public:
  SparseAssignment(const PlanarPoints& rows, const PlanarPoints& cols)
      : a_(rows), b_(cols), n_(static_cast<int>(rows.rows())), row_index_(rows), col_index_(cols),
        candidates_(static_cast<std::size_t>(n_)),
        v_(static_cast<std::size_t>(n_), 0.0), col_of_(static_cast<std::size_t>(n_), -1),
        row_of_(static_cast<std::size_t>(n_), -1), distance_(static_cast<std::size_t>(n_), infinity),
        predecessor_(static_cast<std::size_t>(n_), -1), scanned_(static_cast<std::size_t>(n_), 0) {
    const Eigen::Vector2d low = rows.colwise().minCoeff().cwiseMin(cols.colwise().minCoeff()).transpose();
    const Eigen::Vector2d high = rows.colwise().maxCoeff().cwiseMax(cols.colwise().maxCoeff()).transpose();
    tolerance_ = rounding * (1.0 + (high - low).norm());
    // Candidates in two frames: as placed, and with the rows carried by the optimal transport map between the
    // sets' Gaussian fits (when the sets lie apart, or one is a stretched copy of the other, the pairs sought are
    // near in that frame, not in the first).
    const Transport carry = gaussian_transport(rows, cols);
    const Eigen::Matrix2d back = carry.map.inverse();
    std::vector<std::size_t> near;
    for (int i = 0; i < n_; ++i) {
      const Eigen::Vector2d at = a_.row(i).transpose();
      for (const Eigen::Vector2d& q : {at, Eigen::Vector2d(carry.map * (at - carry.from) + carry.to)}) {
        col_index_.nearest(q, first_candidates, near);
        for (std::size_t k : near) candidates_[static_cast<std::size_t>(i)].push_back(static_cast<int>(k));
      }
    }
    for (int k = 0; k < n_; ++k) {
      const Eigen::Vector2d at = b_.row(k).transpose();
      for (const Eigen::Vector2d& q : {at, Eigen::Vector2d(back * (at - carry.to) + carry.from)}) {
        row_index_.nearest(q, first_candidates, near);
        for (std::size_t i : near) candidates_[i].push_back(k);
      }
    }
    for (auto& c : candidates_) tidy(c);
  }

  // Starts from column potentials `v` (n) instead of the column reduction: every row free (so no condition
  // binds yet, whatever v is), and each row's `count` columns of least reduced cost c(i, k) − v_k joined to its
  // candidates (ties to the lowest column). O(n²), rows in parallel.
  void start_from(const std::vector<double>& v, std::size_t count) {
    v_ = v;
    started_ = true;
    start_free_.resize(static_cast<std::size_t>(n_));
    for (int i = 0; i < n_; ++i) start_free_[static_cast<std::size_t>(i)] = i;
    const std::size_t n = static_cast<std::size_t>(n_);
    parallel_for(n, certificate_grain, [&](std::size_t begin, std::size_t end) {
      std::vector<std::pair<double, int>> all(n);
      for (std::size_t i = begin; i < end; ++i) {
        for (std::size_t k = 0; k < n; ++k) all[k] = {reduced(static_cast<int>(i), static_cast<int>(k)), static_cast<int>(k)};
        const std::size_t kept = std::min(count, n);
        std::nth_element(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(kept - 1), all.end());
        for (std::size_t j = 0; j < kept; ++j) candidates_[i].push_back(all[j].second);
        tidy(candidates_[i]);
      }
    });
  }
  [[nodiscard]] const std::vector<double>& potentials() const { return v_; }

  // Starts from a previous call's state (same n): its potentials, its candidates joined to this call's, and its
  // pairs where still tight (the others free).
  void resume(const PlanarAssignmentState& state) {
    v_ = state.potentials;
    for (std::size_t i = 0; i < candidates_.size(); ++i) {
      candidates_[i].insert(candidates_[i].end(), state.candidates[i].begin(), state.candidates[i].end());
      tidy(candidates_[i]);
    }
    start_free_.clear();
    for (int i = 0; i < n_; ++i) {
      const int k = state.column_of_row[static_cast<std::size_t>(i)];
      std::vector<int>& c = candidates_[static_cast<std::size_t>(i)];
      double least = infinity;
      for (int j : c) least = std::min(least, reduced(i, j));
      if (reduced(i, k) - tolerance_ <= least) {
        col_of_[static_cast<std::size_t>(i)] = k;
        row_of_[static_cast<std::size_t>(k)] = i;
      } else {
        start_free_.push_back(i);
      }
    }
    started_ = true;
    resumed_ = true;
  }

  // This call's state, for the next.
  void keep(PlanarAssignmentState& state) {
    state.potentials = v_;
    state.candidates = candidates_;
    state.column_of_row = col_of_;
    state.rows = a_;
    state.cols = b_;
    state.resumed = resumed_;
  }

  // The median distance from a column to its nearest other column (0 for one column).
  [[nodiscard]] double column_spacing() const {
    if (n_ < 2) return 0;
    std::vector<double> nearest(static_cast<std::size_t>(n_));
    std::vector<std::size_t> two;
    for (int k = 0; k < n_; ++k) {
      col_index_.nearest(b_.row(k).transpose(), 2, two);
      const std::size_t other = two[0] == static_cast<std::size_t>(k) ? two[1] : two[0];
      nearest[static_cast<std::size_t>(k)] = (b_.row(k) - b_.row(static_cast<Eigen::Index>(other))).norm();
    }
    std::nth_element(nearest.begin(), nearest.begin() + n_ / 2, nearest.end());
    return nearest[static_cast<std::size_t>(n_ / 2)];
  }

  Assignment solve() {
    std::vector<int> free_rows = started_ ? start_free_ : column_reduction();
    while (true) {
      pair_all(free_rows);
      free_rows = certify();
      if (free_rows.empty()) break;
    }
    Assignment out;
    out.column_of_row = col_of_;
    out.row_of_column = row_of_;
    for (int i = 0; i < n_; ++i) out.cost += cost(i, col_of_[static_cast<std::size_t>(i)]);
    return out;
  }

 private:
  [[nodiscard]] double cost(int i, int k) const {
    const double dx = a_(i, 0) - b_(k, 0), dy = a_(i, 1) - b_(k, 1);
    return std::sqrt(dx * dx + dy * dy);
  }
  [[nodiscard]] double reduced(int i, int k) const { return cost(i, k) - v_[static_cast<std::size_t>(k)]; }

  static void tidy(std::vector<int>& c) {
    std::sort(c.begin(), c.end());
    c.erase(std::unique(c.begin(), c.end()), c.end());
  }

  // Column reduction (Jonker–Volgenant's start): v_k = the distance from column k to its nearest row, so every
  // reduced cost c(i, k) − v_k is ≥ 0 for all n² pairs; each column, in order, is paired with its nearest row
  // when that row is still free (reduced cost 0: tight). The potentials absorb what all pairings share (when the
  // sets lie apart, most of the distance), which keeps the searches short.
  std::vector<int> column_reduction() {
    for (int k = 0; k < n_; ++k) {
      const int i = static_cast<int>(row_index_.nearest(b_.row(k).transpose()));
      v_[static_cast<std::size_t>(k)] = cost(i, k);
      if (col_of_[static_cast<std::size_t>(i)] < 0) {
        col_of_[static_cast<std::size_t>(i)] = k;
        row_of_[static_cast<std::size_t>(k)] = i;
      }
    }
    std::vector<int> free_rows;
    for (int i = 0; i < n_; ++i) {
      if (col_of_[static_cast<std::size_t>(i)] < 0) free_rows.push_back(i);
    }
    return free_rows;
  }

  // Pairs every row of `pending`, in order.
  void pair_all(const std::vector<int>& pending) {
    std::vector<int> free_columns;
    for (int r : pending) {
      while (!augment(r)) {
        // No free column is reachable through the candidates (rows paired far away are reachable only through
        // their far columns): r, which is free and so under no condition, gets the free column of least
        // reduced cost; the certificate later adds whatever else the optimum needs.
        free_columns.clear();
        for (int k = 0; k < n_; ++k) {
          if (row_of_[static_cast<std::size_t>(k)] < 0) free_columns.push_back(k);
        }
        int best = free_columns.front();
        for (int k : free_columns) {
          if (reduced(r, k) < reduced(r, best)) best = k;
        }
        std::vector<int>& c = candidates_[static_cast<std::size_t>(r)];
        c.insert(std::lower_bound(c.begin(), c.end(), best), best);
      }
    }
  }

  void release(int i) {
    int& paired = col_of_[static_cast<std::size_t>(i)];
    row_of_[static_cast<std::size_t>(paired)] = -1;
    paired = -1;
  }

  // Dijkstra from free row r over the candidates' reduced costs to the nearest free column, then the potentials'
  // update and the augmentation along the path. False (state unchanged) when no free column is reachable.
  bool augment(int r) {
    using Entry = std::pair<double, int>;  // (distance, column): ties to the lowest column
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> heap;
    std::vector<int> touched, finalised;
    auto relax = [&](int k, double d, int from) {
      double& known = distance_[static_cast<std::size_t>(k)];
      if (known == infinity) touched.push_back(k);
      if (d < known) {
        known = d;
        predecessor_[static_cast<std::size_t>(k)] = from;
        heap.emplace(d, k);
      }
    };
    for (int k : candidates_[static_cast<std::size_t>(r)]) relax(k, reduced(r, k), r);
    int sink = -1;
    double shortest = 0;
    while (!heap.empty()) {
      const auto [d, k] = heap.top();
      heap.pop();
      if (scanned_[static_cast<std::size_t>(k)] || d > distance_[static_cast<std::size_t>(k)]) continue;
      scanned_[static_cast<std::size_t>(k)] = 1;
      finalised.push_back(k);
      const int i = row_of_[static_cast<std::size_t>(k)];
      if (i < 0) {
        sink = k;
        shortest = d;
        break;
      }
      const double base = d - reduced(i, k);
      for (int next : candidates_[static_cast<std::size_t>(i)]) {
        if (!scanned_[static_cast<std::size_t>(next)]) relax(next, base + reduced(i, next), i);
      }
    }
    if (sink >= 0) {
      for (int k : finalised) v_[static_cast<std::size_t>(k)] += distance_[static_cast<std::size_t>(k)] - shortest;
      for (int k = sink;;) {
        const int i = predecessor_[static_cast<std::size_t>(k)];
        const int previous = col_of_[static_cast<std::size_t>(i)];
        col_of_[static_cast<std::size_t>(i)] = k;
        row_of_[static_cast<std::size_t>(k)] = i;
        if (i == r) break;
        k = previous;
      }
    }
    for (int k : touched) {
      distance_[static_cast<std::size_t>(k)] = infinity;
      scanned_[static_cast<std::size_t>(k)] = 0;
    }
    return sink >= 0;
  }

  // The dual certificate over all pairs: for each row, a column k with c(i, k) − v_k < u_i beyond rounding
  // (compared squared where u_i + v_k > 0, branch-free, so the scan vectorises). Each row found gains its most
  // violated pairs (8 at most) as candidates and is freed; returns those rows, increasing.
  std::vector<int> certify() {
    const std::size_t n = static_cast<std::size_t>(n_);
    std::vector<double> bx(n), by(n);
    for (std::size_t k = 0; k < n; ++k) bx[k] = b_(static_cast<Eigen::Index>(k), 0), by[k] = b_(static_cast<Eigen::Index>(k), 1);
    std::vector<std::vector<int>> violated(n);
    parallel_for(n, certificate_grain, [&](std::size_t begin, std::size_t end) {
      std::vector<std::pair<double, int>> found;
      for (std::size_t i = begin; i < end; ++i) {
        const int row = static_cast<int>(i);
        const double own = reduced(row, col_of_[i]) - tolerance_;
        const double x = a_(row, 0), y = a_(row, 1);
        int count = 0;
        for (std::size_t k = 0; k < n; ++k) {
          const double reach = own + v_[k];
          const double dx = x - bx[k], dy = y - by[k];
          count += (reach > 0) & (dx * dx + dy * dy < reach * reach);
        }
        if (count == 0) continue;
        found.clear();
        for (std::size_t k = 0; k < n; ++k) {
          const double r = reduced(row, static_cast<int>(k));
          if (r < own) found.emplace_back(r, static_cast<int>(k));
        }
        // Empty only when the squared test and the root disagree in the last bit.
        const std::size_t kept = std::min(found.size(), added_per_row);
        std::partial_sort(found.begin(), found.begin() + static_cast<std::ptrdiff_t>(kept), found.end());
        for (std::size_t j = 0; j < kept; ++j) violated[i].push_back(found[j].second);
      }
    });
    std::vector<int> freed;
    for (int i = 0; i < n_; ++i) {
      const std::vector<int>& more = violated[static_cast<std::size_t>(i)];
      if (more.empty()) continue;
      std::vector<int>& c = candidates_[static_cast<std::size_t>(i)];
      c.insert(c.end(), more.begin(), more.end());
      tidy(c);
      release(i);
      freed.push_back(i);
    }
    return freed;
  }

  const PlanarPoints& a_;
  const PlanarPoints& b_;
  int n_;
  PlanarIndex row_index_, col_index_;
  std::vector<std::vector<int>> candidates_;  // per row: candidate columns, increasing
  std::vector<double> v_;
  std::vector<int> col_of_, row_of_;
  double tolerance_ = 0;
  bool started_ = false;        // start_from or resume was called
  std::vector<int> start_free_;  // then, the rows they left free
  bool resumed_ = false;         // resume was called
  // One search's workspace, reset after it (only the entries it touched).
  std::vector<double> distance_;
  std::vector<int> predecessor_;
  std::vector<char> scanned_;
};

Assignment solve_levels(const PlanarPoints& a, const PlanarPoints& b, Eigen::Index subsample_from, std::vector<double>& v,
                        PlanarAssignmentState* state);

// Whether `state` can start a call on n points: its sizes are n, its pairing a permutation, its potentials
// finite and its candidates columns.
bool usable(const PlanarAssignmentState* state, Eigen::Index n) {
  const auto size = static_cast<std::size_t>(n);
  if (state == nullptr || state->column_of_row.size() != size || state->potentials.size() != size ||
      state->candidates.size() != size || state->rows.rows() != n || state->cols.rows() != n) {
    return false;
  }
  std::vector<char> seen(size, 0);
  for (int k : state->column_of_row) {
    if (k < 0 || static_cast<std::size_t>(k) >= size || seen[static_cast<std::size_t>(k)]) return false;
    seen[static_cast<std::size_t>(k)] = 1;
  }
  for (double v : state->potentials) {
    if (!std::isfinite(v)) return false;
  }
  for (const auto& c : state->candidates) {
    for (int k : c) {
      if (k < 0 || static_cast<std::size_t>(k) >= size) return false;
    }
  }
  return true;
}

// Whether no point moved farther than the columns' typical spacing since the state's call: then starting from
// it pays. Measured on the stitch's rounds (5,000 agents): moves of 0.3 spacings and less took 0.1–0.8 s from
// the state against 1.1–1.3 s afresh, 0.9 spacings about the same, 5 spacings 2.6 s against 1.3 s.
bool moved_little(const PlanarAssignmentState& state, const PlanarPoints& a, const PlanarPoints& b,
                  double spacing) {
  const double moved = std::max((a - state.rows).rowwise().norm().maxCoeff(), (b - state.cols).rowwise().norm().maxCoeff());
  return moved <= spacing;
}

// Column potentials for the whole sets from a subsample half the size: its optimum (solve_levels, so
// recursively) and potentials, extended to every column by the c-transform over the subsample's rows
// (v_k = min over them of c(i, k) − u_i, the largest potential they allow). The subsample is every other row
// and column of a fixed shuffle (a stride would alias with lattices).
std::vector<double> subsample_potentials(const PlanarPoints& a, const PlanarPoints& b, Eigen::Index subsample_from) {
  const Eigen::Index n = a.rows(), m = n / coarse_ratio;
  std::vector<Eigen::Index> rows(static_cast<std::size_t>(n)), cols(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) rows[static_cast<std::size_t>(i)] = cols[static_cast<std::size_t>(i)] = i;
  Rng rng(subsample_seed);
  for (std::size_t i = static_cast<std::size_t>(n) - 1; i > 0; --i) {
    std::swap(rows[i], rows[rng.below(i + 1)]);
    std::swap(cols[i], cols[rng.below(i + 1)]);
  }
  PlanarPoints sa(m, 2), sb(m, 2);
  for (Eigen::Index i = 0; i < m; ++i) {
    sa.row(i) = a.row(rows[static_cast<std::size_t>(i)]);
    sb.row(i) = b.row(cols[static_cast<std::size_t>(i)]);
  }
  std::vector<double> sv;
  const Assignment coarse = solve_levels(sa, sb, subsample_from, sv, nullptr);
  std::vector<double> su(static_cast<std::size_t>(m));
  for (Eigen::Index i = 0; i < m; ++i) {
    const int k = coarse.column_of_row[static_cast<std::size_t>(i)];
    su[static_cast<std::size_t>(i)] = (sa.row(i) - sb.row(k)).norm() - sv[static_cast<std::size_t>(k)];
  }
  std::vector<double> v(static_cast<std::size_t>(n));
  parallel_for(static_cast<std::size_t>(n), certificate_grain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      double least = infinity;
      for (Eigen::Index i = 0; i < m; ++i) {
        least = std::min(least, (sa.row(i) - b.row(static_cast<Eigen::Index>(k))).norm() - su[static_cast<std::size_t>(i)]);
      }
      v[k] = least;
    }
  });
  return v;
}

// The optimum of a and b; `v` gets its column potentials. With a usable `state`, starts from it (and leaves this
// call's in it). Otherwise, sets of subsample_from points or more start from a
// subsample's potentials. Reason: where very many pairings cost nearly the same (lattices apart or stretched),
// the optimum pairs rows with columns far from any geometric neighbourhood (measured: 29 % of 2,000 rows beyond
// their 512 nearest), so the candidates must come from potentials. Two stretched 10,000-point lattices 35 m
// apart: from the column reduction, 64 certificate rounds and 103 s; from a quarter subsample's potentials with
// 16 candidates a row, 19 rounds and 19–24 s; from a half subsample's with 96, 7.2 s (8.4 s for the lattices
// overlapping; a quarter with 96: 13.8 and 17.5 s; half with 48: 9.5 and 8.7 s).
Assignment solve_levels(const PlanarPoints& a, const PlanarPoints& b, Eigen::Index subsample_from, std::vector<double>& v,
                        PlanarAssignmentState* state) {
  SparseAssignment level(a, b);
  if (usable(state, a.rows()) && moved_little(*state, a, b, level.column_spacing())) {
    level.resume(*state);
  } else {
    if (a.rows() >= std::max<Eigen::Index>(subsample_from, 2 * coarse_ratio)) {
      level.start_from(subsample_potentials(a, b, subsample_from), dual_near);
    }
  }
  Assignment out = level.solve();
  v = level.potentials();
  if (state != nullptr) level.keep(*state);
  return out;
}

}  // namespace

Assignment assign_planar(const Eigen::Ref<const PlanarPoints>& rows, const Eigen::Ref<const PlanarPoints>& cols,
                         const char* what, PlanarAssignmentState* state, Eigen::Index subsample_from) {
  if (rows.rows() != cols.rows()) {
    throw InputError(std::string(what) + ": " + std::to_string(rows.rows()) + " points against " +
                     std::to_string(cols.rows()) + "; expected the same count");
  }
  for (const auto* set : {&rows, &cols}) {
    for (Eigen::Index i = 0; i < set->rows(); ++i) {
      if (!set->row(i).allFinite()) {
        throw InputError(std::string(what) + ": point " + std::to_string(i) + " of the " +
                         (set == &rows ? "first" : "second") + " set is not finite");
      }
    }
  }
  if (rows.rows() == 0) return {};
  const PlanarPoints a(rows), b(cols);
  std::vector<double> v;
  return solve_levels(a, b, subsample_from, v, state);
}

}  // namespace throng
