#include "proxy_mesh.h"

namespace throng::detail {

const ProxyMesh& proxy_mesh() {
  static const ProxyMesh mesh = [] {
    constexpr float height = 4.0f;
    // Footprint counter-clockwise seen from above; the fan from the tip keeps both triangles inside (the notch is
    // the one reflex vertex).
    const std::array<Eigen::Vector2f, 4> footprint{Eigen::Vector2f(1.0f, 0.0f), Eigen::Vector2f(-0.5f, 0.6f),
                                                   Eigen::Vector2f(-0.2f, 0.0f), Eigen::Vector2f(-0.5f, -0.6f)};
    ProxyMesh m;
    for (const float z : {0.0f, height}) {
      for (const auto& p : footprint) m.vertices.emplace_back(p.x(), p.y(), z);
    }
    m.triangles = {{4, 5, 6}, {4, 6, 7},   // top, facing +z
                   {0, 2, 1}, {0, 3, 2}};  // bottom, facing −z
    for (std::uint16_t i = 0; i < 4; ++i) {
      const auto j = static_cast<std::uint16_t>((i + 1) % 4);
      // Side i→j: the outward normal of a counter-clockwise edge points to its right.
      m.triangles.push_back({i, j, static_cast<std::uint16_t>(j + 4)});
      m.triangles.push_back({i, static_cast<std::uint16_t>(j + 4), static_cast<std::uint16_t>(i + 4)});
    }
    return m;
  }();
  return mesh;
}

}  // namespace throng::detail
