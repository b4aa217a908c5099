// Which patch types can ever be used inside the region: the impossibility test made before any search.
//
// An exit of pose class c can only be stitched to an entry of class c (and the other way round). A type one of
// whose exits has a class no usable type has as an entry (or one of whose entries has a class no usable type has
// as an exit) leaves that end dangling wherever it lands inside the region; so it is left out, which may leave
// out others in turn: the usable set is the greatest fixed point of that rule. When it is empty, no tiling of
// the region's interior can ever be perfect (an end may still fall outside the region, but nothing inside could
// continue it), and the tiler says so at once instead of searching.
#pragma once

#include <throng/tiling/patch.h>

#include <string>
#include <vector>

namespace throng::tiling {

struct Viability {
  std::vector<bool> usable;        ///< per type
  std::vector<std::string> why;    ///< per type: empty when usable, else the end and class that cannot match
};

[[nodiscard]] Viability find_usable_types(const PatchLibrary& library);

}  // namespace throng::tiling
