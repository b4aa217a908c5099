// The walkable area of a crowd's scene as PedPy wants it: one polygon (with holes) as WKT text.
#pragma once

#include <throng/io/crowd_file.h>

#include <string>

namespace throng::detail {

/// The area free of static obstacles: the scene's region when it has one, else the bounding box of every
/// present position and obstacle widened by 1 m, minus every static obstacle (circles as 32-sided polygons around
/// them, walls as their capsules, at least 1 cm wide). Moving obstacles are not part of a static area and are
/// left out. When the obstacles cut the area into pieces, the largest piece. WKT "POLYGON ((x y, ...), (hole) ...)".
/// ConfigError when the scene has no static obstacle (nothing to build the area from).
[[nodiscard]] std::string walkable_area_wkt(const CrowdFile& crowd);

}  // namespace throng::detail
