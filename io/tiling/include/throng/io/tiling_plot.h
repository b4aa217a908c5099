// The picture of a tiling (`throng plot TILING.h5`): what the patches are and where they join, drawn over the
// crowd of the characters they make.
//
//   patch paths   every instance's character paths as lines in the colour of its patch type (props dashed), in
//                 every laid copy of a repeating tile (shifted by whole periods); the copies' seams dashed grey
//   connections   a dot where an exit is stitched to an entry; across a seam of a repeating tile a ring at the
//                 exit and another at the entry it continues in the neighbouring copy
//   agents        discs at the chosen frames in the colour of the patch the character walks through then
//   legend        one entry per patch type used (name and instance count), then the connection symbols
// Type colours follow the types used, in library order: the first twelve are group_colour(0..11), the next
// eight lighter variants, then they cycle.
#pragma once

#include <throng/io/plot.h>
#include <throng/io/tiling_job.h>

#include <cstddef>
#include <string>

namespace throng {

/// The colour of the `rank`-th patch type used in a picture (see the file comment).
[[nodiscard]] std::string patch_type_colour(std::size_t rank);

/// Adds the tiling of `data` to `layer`, whose file is the crowd the tiling's characters make (the same file
/// `data` was read from): patch paths, connection markers, legend entries and agent colours; turns the layer's
/// own trajectories off (the patch paths are them). `data` is copied where the layer needs it later.
void add_tiling(PlotLayer& layer, const TilingData& data);

}  // namespace throng
