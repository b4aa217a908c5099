#include "deformation.h"

#include <throng/linalg/least_squares.h>

#include "geometry.h"

#include <Eigen/Cholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>

namespace throng::tiling {
namespace {

using Triplet = Eigen::Triplet<double, int>;

// Chords shorter than this in the patch make a Laplacian row keep its absolute (rotated) form.
constexpr double degenerate_chord_m = 1e-6;
// Chords shorter than this say nothing about how a path turned (headings).
constexpr double heading_chord_m = 1e-3;
// Schur pivots below this fraction of the largest are rounding: the coupling row is redundant.
constexpr double redundant_pivot = 1e-10;

// The least-squares pieces of one channel before precomputation.
struct ChannelProblem {
  int width = 1;
  Eigen::Index unknowns = 0;
  std::vector<Triplet> laplacian;   // rows 0 .. laplacian_rows-1
  int laplacian_rows = 0;
  std::vector<double> b_cos, b_sin, b_fixed;  // per Laplacian row
  std::vector<Triplet> constraints;
  int constraint_rows = 0;
  std::vector<double> d_cos, d_sin, d_fixed;  // per constraint row

  int add_laplacian_row(double cos_part, double sin_part, double fixed) {
    b_cos.push_back(cos_part);
    b_sin.push_back(sin_part);
    b_fixed.push_back(fixed);
    return laplacian_rows++;
  }
  int add_constraint_row(double cos_part, double sin_part, double fixed) {
    d_cos.push_back(cos_part);
    d_sin.push_back(sin_part);
    d_fixed.push_back(fixed);
    return constraint_rows++;
  }
};

// Precomputes G and the responses g_c, g_s, g_0 of a channel (see deformation.h).
Channel precompute(const ChannelProblem& p, double anchor_weight) {
  const Eigen::Index n = p.unknowns;
  const Eigen::Index rows = p.laplacian_rows + n;
  std::vector<Triplet> triplets = p.laplacian;
  for (Eigen::Index j = 0; j < n; ++j) triplets.emplace_back(static_cast<int>(p.laplacian_rows + j), static_cast<int>(j), 1.0);
  linalg::SparseMatrix A(rows, n);
  A.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::VectorXd weights = Eigen::VectorXd::Ones(rows);
  weights.tail(n).setConstant(anchor_weight);

  linalg::ConstrainedLeastSquares solver;
  solver.set_objective(A, weights);
  const Eigen::Index m = p.constraint_rows;
  if (m > 0) {
    linalg::SparseMatrix C(m, n);
    C.setFromTriplets(p.constraints.begin(), p.constraints.end());
    solver.set_constraints(C);
  }
  solver.precompute();

  Channel c;
  c.width = p.width;
  c.unknowns = n;
  c.anchor_weight = anchor_weight;
  c.G.resize(n, n);
  // G column j: the solution for AᵀWb = e_j, i.e. b = e_j / w_a on anchor row j, d = 0.
  constexpr Eigen::Index block = 256;
  for (Eigen::Index first = 0; first < n; first += block) {
    const Eigen::Index k = std::min(block, n - first);
    Eigen::MatrixXd b = Eigen::MatrixXd::Zero(rows, k);
    for (Eigen::Index j = 0; j < k; ++j) b(p.laplacian_rows + first + j, j) = 1.0 / anchor_weight;
    c.G.middleCols(first, k) = solver.solve(b, Eigen::MatrixXd(0, k), Eigen::MatrixXd::Zero(m, k));
  }
  // The responses to the rotated (cos, sin) and fixed parts of the Laplacian and constraint values.
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(rows, 3);
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(m, 3);
  for (int r = 0; r < p.laplacian_rows; ++r) {
    b(r, 0) = p.b_cos[static_cast<std::size_t>(r)];
    b(r, 1) = p.b_sin[static_cast<std::size_t>(r)];
    b(r, 2) = p.b_fixed[static_cast<std::size_t>(r)];
  }
  for (int r = 0; r < m; ++r) {
    d(r, 0) = p.d_cos[static_cast<std::size_t>(r)];
    d(r, 1) = p.d_sin[static_cast<std::size_t>(r)];
    d(r, 2) = p.d_fixed[static_cast<std::size_t>(r)];
  }
  const Eigen::MatrixXd g = solver.solve(b, Eigen::MatrixXd(0, 3), d);
  c.g_cos = g.col(0);
  c.g_sin = g.col(1);
  c.g_fixed = g.col(2);
  return c;
}

// Solves the semidefinite S λ = r with rounding-level pivots treated as zero (redundant rows).
Eigen::VectorXd solve_semidefinite(const Eigen::MatrixXd& S, const Eigen::VectorXd& r) {
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(S);
  const Eigen::VectorXd D = ldlt.vectorD();
  const double largest = D.cwiseAbs().maxCoeff();
  Eigen::VectorXd y = ldlt.transpositionsP() * r;
  ldlt.matrixL().solveInPlace(y);
  for (Eigen::Index i = 0; i < y.size(); ++i) y[i] = std::abs(D[i]) > redundant_pivot * largest ? y[i] / D[i] : 0.0;
  ldlt.matrixU().solveInPlace(y);
  return ldlt.transpositionsP().transpose() * y;
}

// One channel of a joint solve; returns the largest row residual.
double solve_channel(const std::vector<Member>& members, bool space, const std::vector<Row>& rows,
                     std::vector<Eigen::VectorXd>& x) {
  const std::size_t K = members.size();
  x.resize(K);
  for (std::size_t k = 0; k < K; ++k) {
    const Channel& c = space ? members[k].system->space : members[k].system->time;
    x[k] = c.free_solution(space ? members[k].space_anchor : members[k].time_anchor, members[k].angle);
  }
  const auto m = static_cast<Eigen::Index>(rows.size());
  if (m == 0) return 0.0;
  // U_k = G_k E_kᵀ (only the columns of rows touching member k are non-zero).
  std::vector<Eigen::MatrixXd> U(K);
  std::vector<bool> touched(K, false);
  for (Eigen::Index r = 0; r < m; ++r) {
    const Row& row = rows[static_cast<std::size_t>(r)];
    for (int i = 0; i < row.size; ++i) {
      const Term& t = row.terms[static_cast<std::size_t>(i)];
      const Channel& c = space ? members[t.member].system->space : members[t.member].system->time;
      if (!touched[t.member]) {
        U[t.member] = Eigen::MatrixXd::Zero(c.unknowns, m);
        touched[t.member] = true;
      }
      U[t.member].col(r) += t.coefficient * c.G.col(t.unknown);
    }
  }
  Eigen::MatrixXd S(m, m);
  Eigen::VectorXd rhs(m);
  for (Eigen::Index s = 0; s < m; ++s) {
    const Row& row = rows[static_cast<std::size_t>(s)];
    double e_x0 = 0;
    Eigen::RowVectorXd srow = Eigen::RowVectorXd::Zero(m);
    for (int i = 0; i < row.size; ++i) {
      const Term& t = row.terms[static_cast<std::size_t>(i)];
      e_x0 += t.coefficient * x[t.member][t.unknown];
      srow += t.coefficient * U[t.member].row(t.unknown);
    }
    S.row(s) = srow;
    rhs[s] = e_x0 - row.value;
  }
  S = 0.5 * (S + S.transpose());
  const Eigen::VectorXd lambda = solve_semidefinite(S, rhs);
  for (std::size_t k = 0; k < K; ++k) {
    if (touched[k]) x[k] -= U[k] * lambda;
  }
  double worst = 0;
  for (const Row& row : rows) {
    double v = -row.value;
    for (int i = 0; i < row.size; ++i) {
      const Term& t = row.terms[static_cast<std::size_t>(i)];
      v += t.coefficient * x[t.member][t.unknown];
    }
    worst = std::max(worst, std::abs(v));
  }
  return worst;
}

}  // namespace

Eigen::VectorXd Channel::free_solution(const Eigen::VectorXd& anchor, double angle) const {
  Eigen::VectorXd x = g_fixed;
  if (width == 2) x += std::cos(angle) * g_cos + std::sin(angle) * g_sin;
  x.noalias() += G * (anchor_weight * anchor);
  return x;
}

PatchSystem::PatchSystem(const PatchType& type, const DeformationOptions& options) {
  offsets_.assign(1, 0);
  for (const Fragment& f : type.fragments) offsets_.push_back(offsets_.back() + static_cast<Eigen::Index>(f.sample_count()));
  const Eigen::Index n = samples();

  ChannelProblem sp, tp;
  sp.width = 2;
  sp.unknowns = 2 * n;
  tp.width = 1;
  tp.unknowns = n;
  for (std::size_t f = 0; f < type.fragments.size(); ++f) {
    const Fragment& fr = type.fragments[f];
    for (std::size_t i = 1; i + 1 < fr.sample_count(); ++i) {
      const int xp = static_cast<int>(2 * sample(f, i - 1)), xi = static_cast<int>(2 * sample(f, i)),
                xn = static_cast<int>(2 * sample(f, i + 1));
      const Eigen::Vector2d c = fr.positions[i + 1] - fr.positions[i - 1];
      const Eigen::Vector2d delta = fr.positions[i] - 0.5 * (fr.positions[i - 1] + fr.positions[i + 1]);
      if (c.norm() > degenerate_chord_m) {
        const double cc = c.squaredNorm();
        const double a = delta.dot(c) / cc;
        const double b = delta.dot(Eigen::Vector2d(-c.y(), c.x())) / cc;
        // x row: δ_x − a c_x + b c_y;  y row: δ_y − a c_y − b c_x.
        const int rx = sp.add_laplacian_row(0, 0, 0);
        sp.laplacian.insert(sp.laplacian.end(), {Triplet(rx, xi, 1.0), Triplet(rx, xp, -0.5 + a), Triplet(rx, xn, -0.5 - a),
                                                 Triplet(rx, xn + 1, b), Triplet(rx, xp + 1, -b)});
        const int ry = sp.add_laplacian_row(0, 0, 0);
        sp.laplacian.insert(sp.laplacian.end(), {Triplet(ry, xi + 1, 1.0), Triplet(ry, xp + 1, -0.5 + a),
                                                 Triplet(ry, xn + 1, -0.5 - a), Triplet(ry, xn, -b), Triplet(ry, xp, b)});
      } else {
        // δ' = R(φ) δ: x = cos φ δx − sin φ δy, y = sin φ δx + cos φ δy.
        const int rx = sp.add_laplacian_row(delta.x(), -delta.y(), 0);
        sp.laplacian.insert(sp.laplacian.end(), {Triplet(rx, xi, 1.0), Triplet(rx, xp, -0.5), Triplet(rx, xn, -0.5)});
        const int ry = sp.add_laplacian_row(delta.y(), delta.x(), 0);
        sp.laplacian.insert(sp.laplacian.end(), {Triplet(ry, xi + 1, 1.0), Triplet(ry, xp + 1, -0.5), Triplet(ry, xn + 1, -0.5)});
      }
      const int tp_row = tp.add_laplacian_row(0, 0, fr.times[i] - 0.5 * (fr.times[i - 1] + fr.times[i + 1]));
      const int ti = static_cast<int>(sample(f, i));
      tp.laplacian.insert(tp.laplacian.end(), {Triplet(tp_row, ti, 1.0), Triplet(tp_row, ti - 1, -0.5), Triplet(tp_row, ti + 1, -0.5)});
    }
  }
  for (const InterpersonalConstraint& ic : type.constraints) {
    const Fragment& fa = type.fragments[ic.fragment_a];
    const Fragment& fb = type.fragments[ic.fragment_b];
    const Eigen::Vector2d d = fb.positions[ic.sample_b] - fa.positions[ic.sample_a];
    const int a = static_cast<int>(sample(ic.fragment_a, ic.sample_a)), b = static_cast<int>(sample(ic.fragment_b, ic.sample_b));
    const int rx = sp.add_constraint_row(d.x(), -d.y(), 0);
    sp.constraints.insert(sp.constraints.end(), {Triplet(rx, 2 * b, 1.0), Triplet(rx, 2 * a, -1.0)});
    const int ry = sp.add_constraint_row(d.y(), d.x(), 0);
    sp.constraints.insert(sp.constraints.end(), {Triplet(ry, 2 * b + 1, 1.0), Triplet(ry, 2 * a + 1, -1.0)});
    const int rt = tp.add_constraint_row(0, 0, fb.times[ic.sample_b] - fa.times[ic.sample_a]);
    tp.constraints.insert(tp.constraints.end(), {Triplet(rt, b, 1.0), Triplet(rt, a, -1.0)});
  }
  space = precompute(sp, options.anchor_weight);
  time = precompute(tp, options.anchor_weight);
}

Eigen::VectorXd PatchSystem::space_anchor(const std::vector<Path>& paths) const {
  Eigen::VectorXd a(2 * samples());
  for (std::size_t f = 0; f < paths.size(); ++f) {
    for (std::size_t s = 0; s < paths[f].positions.size(); ++s) a.segment<2>(2 * sample(f, s)) = paths[f].positions[s];
  }
  return a;
}

Eigen::VectorXd PatchSystem::time_anchor(const std::vector<Path>& paths) const {
  Eigen::VectorXd a(samples());
  for (std::size_t f = 0; f < paths.size(); ++f) {
    for (std::size_t s = 0; s < paths[f].times.size(); ++s) a[sample(f, s)] = paths[f].times[s];
  }
  return a;
}

std::vector<Path> place(const PatchType& type, const Transform& transform) {
  std::vector<Path> paths(type.fragments.size());
  for (std::size_t f = 0; f < type.fragments.size(); ++f) {
    const Fragment& fr = type.fragments[f];
    Path& p = paths[f];
    p.positions.reserve(fr.sample_count());
    for (const Eigen::Vector2d& q : fr.positions) p.positions.push_back(transform.apply(q));
    for (double h : fr.headings) p.headings.push_back(wrap_angle(h + transform.angle));
    for (double t : fr.times) p.times.push_back(t + transform.time_shift);
  }
  return paths;
}

std::vector<Path> paths_from(const PatchType& type, const PatchSystem& system, double angle, const Eigen::VectorXd& space,
                             const Eigen::VectorXd& time) {
  std::vector<Path> paths(type.fragments.size());
  for (std::size_t f = 0; f < type.fragments.size(); ++f) {
    const Fragment& fr = type.fragments[f];
    const std::size_t n = fr.sample_count();
    Path& p = paths[f];
    p.positions.resize(n);
    p.times.resize(n);
    p.headings.resize(n);
    for (std::size_t s = 0; s < n; ++s) {
      p.positions[s] = space.segment<2>(2 * system.sample(f, s));
      p.times[s] = time[system.sample(f, s)];
    }
    // How much each sample's chord turned; NaN where it cannot say.
    std::vector<double> turn(n, std::numeric_limits<double>::quiet_NaN());
    for (std::size_t s = 0; s < n; ++s) {
      const std::size_t lo = s == 0 ? 0 : s - 1, hi = s + 1 == n ? s : s + 1;
      const Eigen::Vector2d before = rotate(fr.positions[hi] - fr.positions[lo], angle);
      const Eigen::Vector2d after = p.positions[hi] - p.positions[lo];
      if (before.norm() > heading_chord_m && after.norm() > heading_chord_m) {
        turn[s] = std::atan2(before.x() * after.y() - before.y() * after.x(), before.dot(after));
      }
    }
    for (std::size_t s = 0; s < n; ++s) {
      double t = turn[s];
      for (std::size_t k = 1; std::isnan(t) && k < n; ++k) {
        if (s >= k && !std::isnan(turn[s - k])) t = turn[s - k];
        else if (s + k < n && !std::isnan(turn[s + k])) t = turn[s + k];
      }
      p.headings[s] = wrap_angle(fr.headings[s] + angle + (std::isnan(t) ? 0.0 : t));
    }
  }
  return paths;
}

JointSolution solve_joint(const JointProblem& problem) {
  JointSolution out;
  const double rs = solve_channel(problem.members, true, problem.space_rows, out.space);
  const double rt = solve_channel(problem.members, false, problem.time_rows, out.time);
  out.max_residual = std::max(rs, rt);
  return out;
}

}  // namespace throng::tiling
