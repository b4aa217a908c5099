// Eigenvector reordering (§4.2) removes the path winding caused by eigenvalues changing order.
#include <throng/formation/formation.h>

#include "eigenbasis.h"
#include "fixtures.h"

#include <catch2/catch.hpp>

using namespace throng::formation;

namespace {

// A rows × cols grid with spacings sx, sy and a little seeded jitter (no repeated eigenvalues).
Eigen::MatrixXd grid(int rows, int cols, double sx, double sy, std::uint64_t seed) {
  throng::Rng rng(seed);
  Eigen::MatrixXd p(rows * cols, 2);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) p.row(r * cols + c) << c * sx + 0.05 * rng.uniform(-1, 1), r * sy + 0.05 * rng.uniform(-1, 1);
  return p;
}

}  // namespace

TEST_CASE("reordering removes the winding when the formation's long axis turns from y to x") {
  // Source spaced 1.6 m along y, target 1.6 m along x: the weakest (longest) edges swap direction, so the
  // eigenvectors of the low eigenvalues swap roles (the paper's Figure 7b). Paired by eigenvalue order, the
  // x-wave of the source is rotated into the y-wave of the target and the individuals wind (Figure 8a).
  Problem p;
  p.keyframes.push_back(Keyframe{0.0, grid(4, 4, 1.0, 1.6, 1), {}});
  p.keyframes.push_back(Keyframe{3.0, grid(4, 4, 1.6, 1.0, 2), {}});
  const double straight = (p.keyframes[1].positions - p.keyframes[0].positions).rowwise().norm().sum();
  Options o;
  o.orientation = OrientationAlignment::none;
  o.reordering = Reordering::none;
  const double unordered = throng::test::total_path_length(animate_formation(p, o).motion);
  o.reordering = Reordering::greedy;
  const double greedy = throng::test::total_path_length(animate_formation(p, o).motion);
  o.reordering = Reordering::max_min;
  const double max_min = throng::test::total_path_length(animate_formation(p, o).motion);
  INFO("straight " << straight << ", by eigenvalue order " << unordered << ", greedy " << greedy << ", max-min " << max_min);
  CHECK(unordered > 1.15 * straight);  // the constructed case does wind
  CHECK(greedy < 0.9 * unordered);     // reordering removes most of it
  CHECK(greedy < 1.08 * straight);
  CHECK(max_min < 0.9 * unordered);
}

TEST_CASE("greedy and max-min orders on a known overlap matrix") {
  // |g| for source rows 1..3 against targets 1..3 (index 0 is the barycentre, always paired with itself).
  Eigen::MatrixXd g(4, 4);
  g << 1, 0, 0, 0,  //
      0, 0.60, 0.80, 0.00,  //
      0, -0.79, 0.55, 0.27,  //
      0, 0.10, 0.20, -0.97;
  const std::vector<int> greedy = greedy_order(g);
  CHECK(greedy == std::vector<int>{0, 2, 1, 3});  // row 1 takes 0.80, row 2 the −0.79, row 3 the −0.97
  // Max-min: pairing row 1 with 2 and row 2 with 1 gives min(0.80, 0.79, 0.97) = 0.79; the identity gives 0.55.
  CHECK(max_min_order(g) == std::vector<int>{0, 2, 1, 3});
  Eigen::MatrixXd h(4, 4);
  h << 1, 0, 0, 0,  //
      0, 0.9, 0.8, 0.0,  //
      0, 0.85, 0.1, 0.0,  //
      0, 0.0, 0.0, 1.0;
  CHECK(greedy_order(h) == std::vector<int>{0, 1, 2, 3});   // greedy: row 1 takes 0.9, leaving row 2 with 0.1
  CHECK(max_min_order(h) == std::vector<int>{0, 2, 1, 3});  // max-min: 0.8 and 0.85 instead
}
