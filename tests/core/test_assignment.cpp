#include <throng/core/assignment.h>
#include <throng/core/errors.h>
#include <throng/core/random.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <limits>
#include <numeric>
#include <set>

using throng::solve_assignment;

namespace {

constexpr double forbidden = std::numeric_limits<double>::infinity();

// Least cost over every way to pair min(rows, cols) rows and columns, by enumerating permutations of the larger
// side and pairing its first min(rows, cols) entries with the smaller side in order.
double brute_force_cost(const Eigen::MatrixXd& cost) {
  const bool wide = cost.rows() <= cost.cols();
  const int small = static_cast<int>(std::min(cost.rows(), cost.cols()));
  const int large = static_cast<int>(std::max(cost.rows(), cost.cols()));
  std::vector<int> perm(static_cast<std::size_t>(large));
  std::iota(perm.begin(), perm.end(), 0);
  double best = forbidden;
  do {
    double sum = 0.0;
    for (int i = 0; i < small; ++i) sum += wide ? cost(i, perm[static_cast<std::size_t>(i)]) : cost(perm[static_cast<std::size_t>(i)], i);
    best = std::min(best, sum);
  } while (std::next_permutation(perm.begin(), perm.end()));
  return best;
}

// The pairing is one-to-one, complete on the smaller side, and its reported cost is the sum of its entries.
void check_valid(const Eigen::MatrixXd& cost, const throng::Assignment& a) {
  const auto rows = static_cast<std::size_t>(cost.rows());
  const auto cols = static_cast<std::size_t>(cost.cols());
  REQUIRE(a.column_of_row.size() == rows);
  REQUIRE(a.row_of_column.size() == cols);
  std::set<int> columns;
  double sum = 0.0;
  std::size_t pairs = 0;
  for (std::size_t r = 0; r < rows; ++r) {
    const int c = a.column_of_row[r];
    if (c < 0) continue;
    ++pairs;
    REQUIRE(c < static_cast<int>(cols));
    REQUIRE(columns.insert(c).second);
    REQUIRE(a.row_of_column[static_cast<std::size_t>(c)] == static_cast<int>(r));
    sum += cost(static_cast<Eigen::Index>(r), c);
  }
  CHECK(pairs == std::min(rows, cols));
  CHECK(a.cost == Catch::Detail::Approx(sum).margin(1e-12));
}

}  // namespace

TEST_CASE("assignment is optimal against brute force on small random square and rectangular matrices") {
  throng::Rng rng(11);
  for (int trial = 0; trial < 300; ++trial) {
    const int rows = 1 + static_cast<int>(rng.below(7));
    const int cols = 1 + static_cast<int>(rng.below(7));
    Eigen::MatrixXd cost(rows, cols);
    const bool integer = trial % 3 == 0;  // small integers: many ties
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c) cost(r, c) = integer ? static_cast<double>(rng.below(4)) : rng.uniform(-5.0, 10.0);
    INFO("trial " << trial << ", " << rows << " by " << cols << "\n" << cost);
    const auto a = solve_assignment(cost);
    check_valid(cost, a);
    // Rounding of the potentials is the only error source: a few ulps of the summed magnitude.
    CHECK(a.cost == Catch::Detail::Approx(brute_force_cost(cost)).margin(1e-12 * (1.0 + cost.cwiseAbs().sum())));
  }
}

TEST_CASE("forbidden entries are avoided, and an impossible pairing is an InputError") {
  throng::Rng rng(5);
  for (int trial = 0; trial < 100; ++trial) {
    const int n = 2 + static_cast<int>(rng.below(5));
    Eigen::MatrixXd cost(n, n);
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c) cost(r, c) = rng.uniform() < 0.3 && r != c ? forbidden : rng.uniform(0.0, 1.0);
    const auto a = solve_assignment(cost);  // the diagonal is always allowed, so a pairing exists
    check_valid(cost, a);
    CHECK(std::isfinite(a.cost));
    CHECK(a.cost == Catch::Detail::Approx(brute_force_cost(cost)).margin(1e-12));
  }
  Eigen::MatrixXd blocked(3, 3);
  blocked << 1, forbidden, forbidden,  //
      2, forbidden, forbidden,         //
      3, 4, 5;
  CHECK_THROWS_AS(solve_assignment(blocked), throng::InputError);
}

TEST_CASE("NaN and -infinity entries are rejected with their position") {
  Eigen::MatrixXd cost = Eigen::MatrixXd::Ones(2, 3);
  cost(1, 2) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(solve_assignment(cost, "matching"), Catch::Matchers::Contains("matching: entry (1, 2) is NaN"));
  cost(1, 2) = -forbidden;
  CHECK_THROWS_AS(solve_assignment(cost), throng::InputError);
}

TEST_CASE("ties are broken the same way every time, and an identity-optimal matrix gives the identity") {
  const Eigen::MatrixXd zeros = Eigen::MatrixXd::Zero(6, 6);
  const auto a = solve_assignment(zeros);
  const auto b = solve_assignment(zeros);
  CHECK(a.column_of_row == b.column_of_row);
  check_valid(zeros, a);

  // Squared distances between a point set and a shuffled copy: the shuffle is the unique optimum.
  throng::Rng rng(3);
  const int n = 40;
  Eigen::MatrixXd points(n, 2);
  for (int i = 0; i < n; ++i) points.row(i) << rng.uniform(0, 10), rng.uniform(0, 10);
  std::vector<int> shuffle(n);
  std::iota(shuffle.begin(), shuffle.end(), 0);
  for (int i = n - 1; i > 0; --i) std::swap(shuffle[static_cast<std::size_t>(i)], shuffle[rng.below(static_cast<std::uint64_t>(i) + 1)]);
  Eigen::MatrixXd cost(n, n);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) cost(r, c) = (points.row(r) - points.row(shuffle[static_cast<std::size_t>(c)])).squaredNorm();
  const auto s = solve_assignment(cost);
  for (int r = 0; r < n; ++r) CHECK(shuffle[static_cast<std::size_t>(s.column_of_row[static_cast<std::size_t>(r)])] == r);
}

TEST_CASE("empty matrices give empty assignments") {
  const auto a = solve_assignment(Eigen::MatrixXd(0, 4));
  CHECK(a.column_of_row.empty());
  CHECK(a.row_of_column == std::vector<int>(4, -1));
  CHECK(a.cost == 0.0);
}
