// assign_planar against the dense solver (tests/core/test_assignment.cpp checks that one against brute force)
// on the point sets the stitch meets: overlapping crowds, crowds far apart (every row's nearest columns are the
// same few, so the sparse graph must widen), turned and shuffled copies, duplicated points (ties), lattices.
#include <throng/core/assignment.h>
#include <throng/core/errors.h>
#include <throng/core/parallel.h>
#include <throng/core/planar_assignment.h>
#include <throng/core/random.h>

#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include <cmath>
#include <set>

using throng::PlanarPoints;

namespace {

PlanarPoints scattered(throng::Rng& rng, int n, double width, Eigen::Vector2d at = Eigen::Vector2d::Zero()) {
  PlanarPoints p(n, 2);
  for (int i = 0; i < n; ++i) p.row(i) << at.x() + rng.uniform(0, width), at.y() + rng.uniform(0, width);
  return p;
}

Eigen::MatrixXd distances(const PlanarPoints& a, const PlanarPoints& b) {
  Eigen::MatrixXd c(a.rows(), b.rows());
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    for (Eigen::Index k = 0; k < b.rows(); ++k) c(i, k) = (a.row(i) - b.row(k)).norm();
  return c;
}

// A one-to-one pairing of every row whose cost is its entries' sum, and the dense solver's least total.
void check_optimal(const PlanarPoints& a, const PlanarPoints& b, Eigen::Index subsample_from = 2000) {
  const throng::Assignment sparse = throng::assign_planar(a, b, "points", nullptr, subsample_from);
  const auto n = static_cast<std::size_t>(a.rows());
  REQUIRE(sparse.column_of_row.size() == n);
  REQUIRE(sparse.row_of_column.size() == n);
  std::set<int> used;
  double sum = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const int k = sparse.column_of_row[i];
    REQUIRE(k >= 0);
    REQUIRE(static_cast<std::size_t>(k) < n);
    REQUIRE(sparse.row_of_column[static_cast<std::size_t>(k)] == static_cast<int>(i));
    used.insert(k);
    sum += (a.row(static_cast<Eigen::Index>(i)) - b.row(k)).norm();
  }
  CHECK(used.size() == n);
  CHECK(sparse.cost == Catch::Detail::Approx(sum).margin(1e-9));
  const throng::Assignment dense = throng::solve_assignment(distances(a, b));
  CHECK(sparse.cost == Catch::Detail::Approx(dense.cost).epsilon(1e-12).margin(1e-9));
}

}  // namespace

TEST_CASE("planar assignment reaches the dense solver's least total on overlapping random sets") {
  throng::Rng rng(17);
  for (int trial = 0; trial < 40; ++trial) {
    const int n = 1 + static_cast<int>(rng.below(300));
    INFO("trial " << trial << ", n = " << n);
    const double width = rng.uniform(1, 50);
    check_optimal(scattered(rng, n, width), scattered(rng, n, width));
  }
}

TEST_CASE("planar assignment reaches the least total when the sets lie far apart") {
  // Every row's nearest columns are the near edge of the other set: the first candidates cannot pair them all.
  throng::Rng rng(23);
  for (const double gap : {5.0, 40.0, 1000.0}) {
    INFO("gap " << gap);
    check_optimal(scattered(rng, 400, 20), scattered(rng, 400, 20, {gap, 0.5 * gap}));
  }
}

TEST_CASE("planar assignment finds a turned and shuffled copy exactly and handles ties") {
  throng::Rng rng(29);
  const int n = 500;
  const PlanarPoints a = scattered(rng, n, 30);
  PlanarPoints b(n, 2);
  std::vector<int> order(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) order[static_cast<std::size_t>(i)] = i;
  for (int i = n - 1; i > 0; --i) std::swap(order[static_cast<std::size_t>(i)], order[rng.below(static_cast<std::uint64_t>(i) + 1)]);
  for (int i = 0; i < n; ++i) b.row(order[static_cast<std::size_t>(i)]) = a.row(i);
  const throng::Assignment same = throng::assign_planar(a, b);
  CHECK(same.cost == 0.0);
  for (int i = 0; i < n; ++i) CHECK(same.column_of_row[static_cast<std::size_t>(i)] == order[static_cast<std::size_t>(i)]);

  SECTION("a slightly turned copy") {
    const Eigen::Matrix2d turn = Eigen::Rotation2Dd(0.05).toRotationMatrix();
    check_optimal(a, (b * turn.transpose()).eval());
  }
  SECTION("a lattice against itself moved by half a cell: many equal totals") {
    PlanarPoints grid(400, 2), moved(400, 2);
    for (int i = 0; i < 400; ++i) grid.row(i) << i % 20, i / 20;
    moved = grid.rowwise() + Eigen::RowVector2d(0.5, 0.5);
    check_optimal(grid, moved);
  }
  SECTION("duplicated points") {
    PlanarPoints twice(300, 2);
    for (int i = 0; i < 300; ++i) twice.row(i) = a.row(i % 60);
    check_optimal(twice, scattered(rng, 300, 30));
  }
}

TEST_CASE("planar assignment started from a subsample reaches the least total on stretched lattices apart") {
  // The path the stitch takes from 2,000 agents on, here from 100 points so that the dense solver checks it
  // quickly: 800 → 400 → 200 → 100 → 50 points, four subsample levels.
  PlanarPoints a(800, 2), b(800, 2);
  throng::Rng rng(37);
  for (int i = 0; i < 800; ++i) {
    a.row(i) << (i % 40) * 1.0 + 0.1 * rng.normal(), (i / 40) * 1.2 + 0.1 * rng.normal();
    b.row(i) << 35 + (i % 40) * 1.2 + 0.1 * rng.normal(), 8 + (i / 40) * 1.3 + 0.1 * rng.normal();
  }
  check_optimal(a, b, 100);
  throng::Rng random(41);
  check_optimal(scattered(random, 700, 30), scattered(random, 700, 30, {10, 0}), 100);
}

TEST_CASE("planar assignment started from the previous call's state reaches the same least totals") {
  // The stitch's rounds: the same rows against columns turned a little further about their centre each call
  // (the farthest moves 0.1 m a round, under the 0.5 m spacing: each call after the first starts from the state).
  throng::Rng rng(43);
  const PlanarPoints a = scattered(rng, 600, 25), b = scattered(rng, 600, 25, {3, 1});
  const Eigen::RowVector2d centre = b.colwise().mean();
  throng::PlanarAssignmentState state;
  for (int round = 0; round < 4; ++round) {
    INFO("round " << round);
    const Eigen::Matrix2d turn = Eigen::Rotation2Dd(0.005 * round).toRotationMatrix();
    const PlanarPoints moved = ((b.rowwise() - centre) * turn.transpose()).rowwise() + centre;
    const throng::Assignment resumed = throng::assign_planar(a, moved, "points", &state);
    CHECK(state.column_of_row == resumed.column_of_row);
    CHECK(state.resumed == (round > 0));
    CHECK(resumed.cost == Catch::Detail::Approx(throng::assign_planar(a, moved).cost).epsilon(1e-12).margin(1e-9));
    CHECK(resumed.cost == Catch::Detail::Approx(throng::solve_assignment(distances(a, moved)).cost).epsilon(1e-12).margin(1e-9));
  }
  SECTION("a state of another size or a broken one is not used") {
    throng::PlanarAssignmentState broken = state;
    broken.column_of_row[0] = broken.column_of_row[1];
    CHECK(throng::assign_planar(a, b, "points", &broken).cost == Catch::Detail::Approx(throng::assign_planar(a, b).cost));
    CHECK_FALSE(broken.resumed);
    CHECK(broken.column_of_row != state.column_of_row);  // replaced by this call's
    throng::PlanarAssignmentState far = state;
    const PlanarPoints shifted = b.rowwise() + Eigen::RowVector2d(5, 0);  // every point moved 5 m: afresh
    CHECK(throng::assign_planar(a, shifted, "points", &far).cost == Catch::Detail::Approx(throng::assign_planar(a, shifted).cost));
    CHECK_FALSE(far.resumed);
    const PlanarPoints fewer = a.topRows(100);
    CHECK(throng::assign_planar(fewer, b.topRows(100), "points", &state).column_of_row.size() == 100);
    CHECK(state.column_of_row.size() == 100);
  }
}

TEST_CASE("planar assignment gives the same pairing whatever the thread count") {
  throng::Rng rng(31);
  const PlanarPoints a = scattered(rng, 2000, 60), b = scattered(rng, 2000, 60, {30, 0});
  std::vector<int> one, two;
  {
    throng::ThreadLimit limit(1);
    one = throng::assign_planar(a, b).column_of_row;
  }
  {
    throng::ThreadLimit limit(2);
    two = throng::assign_planar(a, b).column_of_row;
  }
  CHECK(one == two);
}

TEST_CASE("planar assignment refuses unequal counts and points that are not finite") {
  PlanarPoints a(3, 2), b(2, 2);
  a.setZero();
  b.setZero();
  CHECK_THROWS_AS(throng::assign_planar(a, b, "boundary"), throng::InputError);
  CHECK_THROWS_WITH(throng::assign_planar(a, b, "boundary"), Catch::Contains("boundary") && Catch::Contains("3 points against 2"));
  PlanarPoints c = a;
  c(1, 1) = std::nan("");
  CHECK_THROWS_WITH(throng::assign_planar(a, c), Catch::Contains("point 1 of the second set is not finite"));
  CHECK(throng::assign_planar(PlanarPoints(0, 2), PlanarPoints(0, 2)).column_of_row.empty());
}
