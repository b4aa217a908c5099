// spatial_pieces (spatial_pieces.h): median cuts along the wider side until each piece holds few enough groups.
#include "spatial_pieces.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <span>
#include <stdexcept>
#include <string>

namespace throng::detail {
namespace {

using Places = Eigen::Matrix<double, Eigen::Dynamic, 2>;

// Cuts `agents` (any order; reordered in place) holding `groups` groups and appends its pieces to `out`.
void cut(const Places& places, std::span<int> agents, int groups, int max_groups, std::vector<AgentPiece>& out) {
  if (agents.empty()) return;
  if (groups <= max_groups) {
    AgentPiece piece{{agents.begin(), agents.end()}, groups};
    std::sort(piece.agents.begin(), piece.agents.end());
    out.push_back(std::move(piece));
    return;
  }
  Eigen::Vector2d low = places.row(agents.front()).transpose(), high = low;
  for (const int a : agents) {
    low = low.cwiseMin(places.row(a).transpose());
    high = high.cwiseMax(places.row(a).transpose());
  }
  const int axis = high.y() - low.y() > high.x() - low.x() ? 1 : 0;
  const int lower_groups = groups / 2, upper_groups = groups - lower_groups;
  const auto m = static_cast<long>(agents.size());
  long lower = std::lround(static_cast<double>(m) * lower_groups / groups);
  if (m >= groups) lower = std::clamp<long>(lower, lower_groups, m - upper_groups);
  // A strict order (place, then index): the lower side is the same set whatever the selection's algorithm.
  const auto before = [&](int a, int b) {
    const double pa = places(a, axis), pb = places(b, axis);
    return pa < pb || (pa == pb && a < b);
  };
  std::nth_element(agents.begin(), agents.begin() + lower, agents.end(), before);
  cut(places, agents.first(static_cast<std::size_t>(lower)), lower_groups, max_groups, out);
  cut(places, agents.subspan(static_cast<std::size_t>(lower)), upper_groups, max_groups, out);
}

}  // namespace

std::vector<AgentPiece> spatial_pieces(const Places& places, int groups, int max_groups) {
  assert(places.allFinite());  // nth_element needs a strict weak order
  if (groups < 1 || max_groups < 1) {
    throw std::invalid_argument("spatial_pieces: " + std::to_string(groups) + " groups, at most " +
                                std::to_string(max_groups) + " a piece: expected both ≥ 1");
  }
  std::vector<int> agents(static_cast<std::size_t>(places.rows()));
  for (std::size_t a = 0; a < agents.size(); ++a) agents[a] = static_cast<int>(a);
  std::vector<AgentPiece> out;
  if (agents.empty()) return out;
  cut(places, agents, groups, max_groups, out);
  return out;
}

bool share_groups(std::vector<AgentPiece>& pieces, int groups, int max_groups) {
  const std::size_t count = pieces.size();
  std::vector<long> room(count);  // the most groups piece k can take
  long agents = 0, rooms = 0;
  for (std::size_t k = 0; k < count; ++k) {
    if (pieces[k].agents.empty()) return false;
    agents += static_cast<long>(pieces[k].agents.size());
    room[k] = std::min<long>(static_cast<long>(pieces[k].agents.size()), max_groups);
    rooms += room[k];
  }
  if (count == 0 || groups < static_cast<long>(count) || groups > rooms) return false;
  // Each piece's quota, its floor (within [1, its room]), then the rest one at a time by the largest remainder.
  std::vector<double> quota(count);
  std::vector<long> share(count);
  long given = 0;
  for (std::size_t k = 0; k < count; ++k) {
    quota[k] = static_cast<double>(pieces[k].agents.size()) * groups / static_cast<double>(agents);
    share[k] = std::clamp<long>(static_cast<long>(std::floor(quota[k])), 1, room[k]);
    given += share[k];
  }
  const auto left = [&](std::size_t k) { return quota[k] - static_cast<double>(share[k]); };
  while (given != groups) {
    const bool add = given < groups;
    std::size_t best = count;
    for (std::size_t k = 0; k < count; ++k) {
      if (add ? share[k] >= room[k] : share[k] <= 1) continue;
      if (best == count || (add ? left(k) > left(best) : left(k) < left(best))) best = k;
    }
    share[best] += add ? 1 : -1;  // a piece can always take or give one: groups is within [#pieces, rooms]
    given += add ? 1 : -1;
  }
  for (std::size_t k = 0; k < count; ++k) pieces[k].groups = static_cast<int>(share[k]);
  return true;
}

}  // namespace throng::detail
