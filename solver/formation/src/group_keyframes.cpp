#include "group_keyframes.h"

namespace throng::formation {

Adjacency keyframe_graph(const GroupKeyframes& keyframes, std::size_t k) {
  const std::string what = keyframes.what + " keyframe " + std::to_string(k);
  const std::string place = k < keyframes.places.size() ? keyframes.places[k] : std::string();
  const std::string placed = place.empty() ? what : place + ": " + what;  // edits name their own place
  Adjacency graph = delaunay_adjacency(keyframes.positions[k], placed, keyframes.item_names);
  apply_edits(graph, keyframes.positions[k], keyframes.edits[k], what, keyframes.item_names);
  require_connected(graph, placed, keyframes.item_names);
  return graph;
}

}  // namespace throng::formation
