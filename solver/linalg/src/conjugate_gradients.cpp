#include <throng/core/errors.h>
#include <throng/core/parallel.h>
#include <throng/linalg/conjugate_gradients.h>
#include <throng/linalg/spd_solver.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace throng::linalg {
namespace {

constexpr std::size_t row_block = 4096;  // rows per task of the vector updates
// The contraction factor ρ the stopping rule assumes (conjugate_gradients.h), within these bounds.
constexpr double min_contraction = 0.5;
constexpr double max_contraction = 0.95;
// ρ is the largest ratio over this many last steps: the largest move of CG's steps does not fall steadily (it
// may drop 4× in one step and rise again the next), so one ratio can promise far more than the method delivers.
constexpr std::size_t contraction_window = 3;

}  // namespace

CgReport conjugate_gradients(const ComplexSparse& A, Preconditioner& M, const ComplexBlock& B, ComplexBlock& X,
                             const std::vector<double>& tolerance, int max_iterations) {
  CgWorkspace workspace;
  return conjugate_gradients(A, M, B, X, tolerance, max_iterations, workspace);
}

CgReport conjugate_gradients(const ComplexSparse& A, Preconditioner& M, const ComplexBlock& B, ComplexBlock& X,
                             const std::vector<double>& tolerance, int max_iterations, CgWorkspace& workspace) {
  const Eigen::Index n = A.rows(), k = B.cols();
  if (A.cols() != n || B.rows() != n || X.rows() != n || X.cols() != k) {
    throw std::invalid_argument("conjugate_gradients: shapes do not match (A " + std::to_string(A.rows()) + "×" +
                                std::to_string(A.cols()) + ", B " + std::to_string(B.rows()) + "×" + std::to_string(k) +
                                ", X " + std::to_string(X.rows()) + "×" + std::to_string(X.cols()) + ")");
  }
  if (tolerance.size() != 1 && tolerance.size() != static_cast<std::size_t>(k)) {
    throw std::invalid_argument("conjugate_gradients: " + std::to_string(tolerance.size()) + " tolerances for " + std::to_string(k) + " columns");
  }
  auto tol = [&](Eigen::Index c) { return tolerance.size() == 1 ? tolerance[0] : tolerance[static_cast<std::size_t>(c)]; };
  CgReport report;
  report.column_iterations.assign(static_cast<std::size_t>(k), 0);
  report.last_step.assign(static_cast<std::size_t>(k), 0.0);
  report.error_estimate.assign(static_cast<std::size_t>(k), 0.0);
  if (n == 0 || k == 0) return report;

  ComplexBlock& R = workspace.R;
  ComplexBlock& Z = workspace.Z;
  ComplexBlock& P = workspace.P;
  ComplexBlock& AP = workspace.AP;
  if (!workspace.residual_given || R.rows() != n || R.cols() != k) residual(A, X, B, R);
  workspace.residual_given = false;
  std::vector<char> active(static_cast<std::size_t>(k), 1);
  std::vector<std::array<double, contraction_window>> recent_ratios(static_cast<std::size_t>(k));
  for (auto& r : recent_ratios) r.fill(0.0);
  const double prior = workspace.contraction;
  M.apply(R, Z);
  P = Z;
  std::vector<Complex> rz = column_dots(R, Z);
  for (Eigen::Index c = 0; c < k; ++c) {
    if (rz[static_cast<std::size_t>(c)] == Complex(0)) active[static_cast<std::size_t>(c)] = 0;  // already solved
  }
  for (int iteration = 1;; ++iteration) {
    bool any = false;
    for (char a : active) any = any || a;
    if (!any) break;
    if (iteration > max_iterations) {
      std::ostringstream what;
      for (Eigen::Index c = 0; c < k; ++c) {
        if (!active[static_cast<std::size_t>(c)]) continue;
        what << "conjugate gradients did not converge in " << max_iterations << " iterations (column " << c
             << ": estimated error " << report.error_estimate[static_cast<std::size_t>(c)] << ", tolerance " << tol(c)
             << "); raise solver.max_iterations or solver.tolerance_m, or use solver.method: direct";
        break;
      }
      throw NumericalError(what.str());
    }
    multiply(A, P, AP);
    const std::vector<Complex> pap = column_dots(P, AP);
    std::vector<Complex> alpha(static_cast<std::size_t>(k), Complex(0));
    for (Eigen::Index c = 0; c < k; ++c) {
      const auto cu = static_cast<std::size_t>(c);
      if (!active[cu]) continue;
      const double curvature = pap[cu].real();
      if (!(curvature > 0) || !std::isfinite(curvature)) {
        throw SingularMatrixError("the system is not positive definite (conjugate gradients met pᴴAp = " +
                                      std::to_string(curvature) + ")",
                                  -1);
      }
      alpha[cu] = rz[cu] / curvature;
    }
    // x += α p, r −= α Ap; the step's largest move.
    // (Rows in parallel; a maximum does not depend on the order it is taken in.)
    const std::size_t blocks = (static_cast<std::size_t>(n) + row_block - 1) / row_block;
    std::vector<double> block_step(blocks * static_cast<std::size_t>(k), 0.0);
    parallel_for(blocks, 1, [&](std::size_t b0, std::size_t b1) {
      for (std::size_t b = b0; b < b1; ++b) {
        double* largest = block_step.data() + b * static_cast<std::size_t>(k);
        const auto end = static_cast<Eigen::Index>(std::min(static_cast<std::size_t>(n), (b + 1) * row_block));
        for (auto i = static_cast<Eigen::Index>(b * row_block); i < end; ++i) {
          for (Eigen::Index c = 0; c < k; ++c) {
            const auto cu = static_cast<std::size_t>(c);
            if (!active[cu]) continue;
            const Complex move = times(alpha[cu], P(i, c));
            X(i, c) += move;
            R(i, c) -= times(alpha[cu], AP(i, c));
            largest[cu] = std::max(largest[cu], std::norm(move));
          }
        }
      }
    });
    std::vector<double> step(static_cast<std::size_t>(k), 0.0);
    for (std::size_t b = 0; b < blocks; ++b)
      for (std::size_t c = 0; c < static_cast<std::size_t>(k); ++c) step[c] = std::max(step[c], block_step[b * static_cast<std::size_t>(k) + c]);
    for (Eigen::Index c = 0; c < k; ++c) {
      const auto cu = static_cast<std::size_t>(c);
      if (!active[cu]) continue;
      const double previous = report.last_step[cu];
      report.last_step[cu] = std::sqrt(step[cu]);
      // The last contraction_window ratios, newest first; ρ is the largest.
      auto& ratios = recent_ratios[cu];
      std::rotate(ratios.rbegin(), ratios.rbegin() + 1, ratios.rend());
      ratios[0] = previous > 0 ? report.last_step[cu] / previous : 0.0;
      // The first step has no ratio of its own: the previous solve's contraction stands in for it.
      const double measured = iteration == 1 ? prior : *std::max_element(ratios.begin(), ratios.end());
      const double rho = std::clamp(measured, min_contraction, max_contraction);
      report.error_estimate[cu] = report.last_step[cu] * rho / (1.0 - rho);
      report.column_iterations[cu] = iteration;
      report.iterations = std::max(report.iterations, iteration);
      if (report.error_estimate[cu] <= tol(c)) active[cu] = 0;
    }
    bool more = false;
    for (char a : active) more = more || a;
    if (!more) break;
    M.apply(R, Z);
    const std::vector<Complex> rz_next = column_dots(R, Z);
    std::vector<Complex> beta(static_cast<std::size_t>(k), Complex(0));
    for (Eigen::Index c = 0; c < k; ++c) {
      const auto cu = static_cast<std::size_t>(c);
      if (!active[cu]) continue;
      if (rz_next[cu] == Complex(0)) {
        active[cu] = 0;
        continue;
      }
      beta[cu] = rz_next[cu] / rz[cu];
      rz[cu] = rz_next[cu];
    }
    // p = z + β p; stopped columns take no more steps (their direction is zeroed).
    parallel_for(static_cast<std::size_t>(n), row_block, [&](std::size_t begin, std::size_t end) {
      for (auto i = static_cast<Eigen::Index>(begin); i < static_cast<Eigen::Index>(end); ++i) {
        for (Eigen::Index c = 0; c < k; ++c) {
          P(i, c) = active[static_cast<std::size_t>(c)] ? Complex(Z(i, c) + times(beta[static_cast<std::size_t>(c)], P(i, c))) : Complex(0);
        }
      }
    });
  }
  // This solve's contraction, for the next one's first step: the ρ its columns stopped with (the largest of
  // their last ratios; kept from before when no column took two steps).
  double contraction = 0;
  for (std::size_t c = 0; c < static_cast<std::size_t>(k); ++c) {
    if (report.column_iterations[c] < 2) continue;
    contraction = std::max(contraction, *std::max_element(recent_ratios[c].begin(), recent_ratios[c].end()));
  }
  if (contraction > 0) workspace.contraction = contraction;
  return report;
}

}  // namespace throng::linalg
