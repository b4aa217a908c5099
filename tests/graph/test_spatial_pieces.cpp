// spatial_pieces and share_groups (solver/graph/src/spatial_pieces.h): a block's agents cut by place into pieces
// of few enough groups for one METIS call each, and groups shared among kept pieces.
#include "spatial_pieces.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <numeric>
#include <random>
#include <set>
#include <stdexcept>
#include <vector>

using throng::detail::AgentPiece;
using throng::detail::share_groups;
using throng::detail::spatial_pieces;
using Places = Eigen::Matrix<double, Eigen::Dynamic, 2>;

namespace {

// rows × cols agents 1 m apart on a grid; agent k at cell k (column k mod cols, row k / cols), or at a cell dealt
// by a seeded permutation when `shuffled` (so agent indices do not follow places).
Places grid(int rows, int cols, bool shuffled = false) {
  std::vector<int> order(static_cast<std::size_t>(rows * cols));
  std::iota(order.begin(), order.end(), 0);
  if (shuffled) std::shuffle(order.begin(), order.end(), std::mt19937(3));
  Places places(rows * cols, 2);
  for (int k = 0; k < rows * cols; ++k) {
    const int cell = order[static_cast<std::size_t>(k)];
    places.row(k) << cell % cols, cell / cols;
  }
  return places;
}

// Every agent in exactly one piece, each piece's agents increasing, groups summing to `groups`.
void check_cover(const std::vector<AgentPiece>& pieces, int agents, int groups) {
  std::vector<int> seen(static_cast<std::size_t>(agents), 0);
  int total = 0;
  for (const auto& piece : pieces) {
    CHECK(std::is_sorted(piece.agents.begin(), piece.agents.end()));
    for (const int a : piece.agents) ++seen[static_cast<std::size_t>(a)];
    total += piece.groups;
  }
  CHECK(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; }));
  CHECK(total == groups);
}

}  // namespace

TEST_CASE("spatial pieces cover every agent once, hold at most the given groups and agents in proportion") {
  const Places places = grid(40, 25, true);  // 1,000 agents
  for (const int groups : {1, 16, 17, 31, 64, 100, 333}) {
    const auto pieces = spatial_pieces(places, groups, 16);
    check_cover(pieces, 1000, groups);
    for (const auto& piece : pieces) {
      CHECK(piece.groups >= 1);
      CHECK(piece.groups <= 16);
      // Agents per group within one agent per cut of the crowd's 1,000 / groups.
      const double per_group = static_cast<double>(piece.agents.size()) / piece.groups;
      CHECK(per_group == Approx(1000.0 / groups).margin(8.0 / piece.groups));
    }
    if (groups <= 16) CHECK(pieces.size() == 1);
  }
}

TEST_CASE("spatial pieces are cut along the wider side, each side wholly on its side of the cut") {
  // 10 rows × 40 columns: 32 groups into two pieces of 16, split along x (the wider side) at x = 20.
  const Places places = grid(10, 40, true);
  const auto pieces = spatial_pieces(places, 32, 16);
  REQUIRE(pieces.size() == 2);
  CHECK(pieces[0].agents.size() == 200);
  CHECK(pieces[1].agents.size() == 200);
  for (const int a : pieces[0].agents) CHECK(places(a, 0) < 20);
  for (const int a : pieces[1].agents) CHECK(places(a, 0) >= 20);
  // Four pieces: each half (10 rows × 20 columns) is cut again along its wider side, x, so quarters of 10 columns.
  const auto quarters = spatial_pieces(places, 64, 16);
  REQUIRE(quarters.size() == 4);
  for (std::size_t k = 0; k < 4; ++k) {
    std::set<double> columns;
    for (const int a : quarters[k].agents) columns.insert(places(a, 0));
    CHECK(columns.size() == 10);
    CHECK(*columns.begin() == 10.0 * static_cast<double>(k));
  }
}

TEST_CASE("spatial pieces break ties between equal places by agent index") {
  // Every agent at the same place: the lower side of each cut is the lower indices, whatever the selection does.
  const Places places = Places::Zero(100, 2);
  const auto pieces = spatial_pieces(places, 40, 16);
  check_cover(pieces, 100, 40);
  int next = 0;
  for (const auto& piece : pieces) {
    CHECK(piece.agents.front() == next);
    CHECK(piece.agents.back() == next + static_cast<int>(piece.agents.size()) - 1);
    next += static_cast<int>(piece.agents.size());
  }
}

TEST_CASE("spatial pieces never leave a piece fewer agents than groups, and refuse groups below 1") {
  // As many groups as agents: every piece has exactly as many agents as groups.
  const Places places = grid(5, 7);
  const auto pieces = spatial_pieces(places, 35, 4);
  check_cover(pieces, 35, 35);
  for (const auto& piece : pieces) CHECK(static_cast<int>(piece.agents.size()) == piece.groups);
  CHECK(spatial_pieces(Places(0, 2), 3, 16).empty());
  CHECK_THROWS_AS(spatial_pieces(places, 0, 16), std::invalid_argument);
  CHECK_THROWS_AS(spatial_pieces(places, 4, 0), std::invalid_argument);
}

TEST_CASE("groups shared among kept pieces in proportion to their agents, by largest remainder") {
  auto pieces_of = [](std::vector<int> sizes) {
    std::vector<AgentPiece> pieces;
    int next = 0;
    for (const int size : sizes) {
      AgentPiece piece;
      for (int k = 0; k < size; ++k) piece.agents.push_back(next++);
      pieces.push_back(piece);
    }
    return pieces;
  };
  auto groups_of = [](const std::vector<AgentPiece>& pieces) {
    std::vector<int> out;
    for (const auto& piece : pieces) out.push_back(piece.groups);
    return out;
  };
  std::vector<AgentPiece> pieces = pieces_of({100, 100, 200});
  REQUIRE(share_groups(pieces, 8, 16));
  CHECK(groups_of(pieces) == std::vector<int>{2, 2, 4});
  // Quotas 2.5, 2.5, 5: the one group left goes to the earlier tie.
  REQUIRE(share_groups(pieces, 10, 16));
  CHECK(groups_of(pieces) == std::vector<int>{3, 2, 5});
  // Quotas 1.4, 1.6, 3.0 (sizes 70, 80, 150 of 300, 6 groups): floors 1, 1, 3, the rest to the 0.6.
  pieces = pieces_of({70, 80, 150});
  REQUIRE(share_groups(pieces, 6, 16));
  CHECK(groups_of(pieces) == std::vector<int>{1, 2, 3});
  // At least one group a piece and at most its agents: quotas 0.03, 0.03 and 2.94 become 1, 1, 1.
  pieces = pieces_of({1, 1, 98});
  REQUIRE(share_groups(pieces, 3, 16));
  CHECK(groups_of(pieces) == std::vector<int>{1, 1, 1});
  REQUIRE(share_groups(pieces, 100, 98));
  CHECK(groups_of(pieces) == std::vector<int>{1, 1, 98});
  // Impossible: fewer groups than pieces, more than agents, more than max_groups allows; the pieces are left as
  // they were.
  CHECK_FALSE(share_groups(pieces, 2, 98));
  CHECK_FALSE(share_groups(pieces, 101, 98));
  CHECK_FALSE(share_groups(pieces, 40, 16));
  CHECK(groups_of(pieces) == std::vector<int>{1, 1, 98});
  std::vector<AgentPiece> none = pieces_of({10, 0});
  CHECK_FALSE(share_groups(none, 2, 16));
  // A cap moves what the largest piece cannot hold to the others: quotas 4, 4, 16, 8 (sizes 40, 40, 160, 80 of 320,
  // 32 groups), floors 4, 4, 12 (capped), 8; the 4 left go one at a time to the largest remainder among the pieces
  // below their cap, ties to the earlier: pieces 0, 1, 3, then 0 again.
  pieces = pieces_of({40, 40, 160, 80});
  REQUIRE(share_groups(pieces, 32, 12));
  CHECK(groups_of(pieces) == std::vector<int>{6, 5, 12, 9});
  // Quotas 0.08 (three times), 2.38, 2.38; floors 1, 1, 1, 2, 2 are two too many: taken from the smallest
  // remainder among the pieces above 1 group, ties to the earlier: pieces 3, then 4.
  pieces = pieces_of({1, 1, 1, 30, 30});
  REQUIRE(share_groups(pieces, 5, 16));
  CHECK(groups_of(pieces) == std::vector<int>{1, 1, 1, 1, 1});
}
