// Starts for a sequence of solves A x = b₁, b₂, ... with one Hermitian positive definite A and right-hand sides
// that change a little from one to the next (the drags of one interactive gesture): the Galerkin solution in
// the span V of the last few solutions,
//     x₀ = V (Vᴴ A V)⁻¹ Vᴴ b,   r₀ = b − (A V)(Vᴴ A V)⁻¹ Vᴴ b,
// which costs no product with A (A V is kept from the solves themselves: b − r at their end). V is kept
// A-orthonormal (Vᴴ A V = I), so the start is V Vᴴ b. It is the best approximation of the new solution in the
// energy norm within that span: for right-hand sides that move along a smooth path it is already close, and
// the solver then only refines it.
//
// The kept span slides: when full, a new solution replaces the oldest direction. A solution already in the
// span (to rounding) adds nothing. Sums have a fixed order (hermitian.h): the same bits for any thread count.
#pragma once

#include <throng/linalg/hermitian.h>

namespace throng::linalg {

class SolutionHistory {
 public:
  explicit SolutionHistory(int capacity = 8);

  /// Forgets every solution (A changed).
  void clear();

  /// x = the start for b (zero when nothing is kept) and r = b − A x. b, x, r: #unknowns by 1.
  void start(const ComplexBlock& b, ComplexBlock& x, ComplexBlock& r) const;

  /// The same over the span of the kept solutions and one more direction g, a guess at this solution that the
  /// caller has (with A g: one product with A). The Galerkin start in the larger span is at least as close in
  /// the energy norm as either alone; g lying in the kept span adds nothing.
  void start(const ComplexBlock& b, const ComplexBlock& g, const ComplexBlock& Ag, ComplexBlock& x, ComplexBlock& r) const;

  /// Keeps the solution x of a solve and A x (both #unknowns by 1).
  void add(const ComplexBlock& x, const ComplexBlock& Ax);

  [[nodiscard]] int size() const noexcept { return size_; }

 private:
  // cᵢ = columns(M)ᵢᴴ y for the kept columns.
  [[nodiscard]] Eigen::VectorXcd adjoint_times(const ComplexBlock& M, const ComplexBlock& y) const;

  int capacity_;
  int size_ = 0;
  int next_ = 0;         // the slot the next direction goes to
  ComplexBlock V_, W_;   // #unknowns by capacity: directions (A-orthonormal) and A times them
};

}  // namespace throng::linalg
