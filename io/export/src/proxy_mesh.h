// The proxy shape the 3-D formats (glTF, USD) draw each agent with: an arrowhead prism whose tip shows where the
// agent faces. In the body frame (forward +x, left +y, up +z) for an agent of radius 1; the formats scale it by
// the agent's radius. Its footprint is the tip (1, 0), the back corners (−0.5, ±0.6) and a notch at (−0.2, 0), so
// the tip is the one vertex at distance 1 from the agent's axis (a test finds the heading by it), and it is 4
// radii tall (1 m for the usual 0.25 m).
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <vector>

namespace throng::detail {

struct ProxyMesh {
  std::vector<Eigen::Vector3f> vertices;                   ///< body frame, radius 1
  std::vector<std::array<std::uint16_t, 3>> triangles;     ///< counter-clockwise seen from outside
};

[[nodiscard]] const ProxyMesh& proxy_mesh();

}  // namespace throng::detail
