// The option schemas (throng/core/schema.h) of the commands that read and write data files rather than run a
// method: import (ImportOptions, import_crowd.h) and plot (PlotOptions, plot.h, with the view and the
// tiling switch). Their steps of `throng run` read the same keys.
#pragma once

#include <throng/core/schema.h>
#include <throng/io/plot.h>
#include <throng/io/import_crowd.h>

#include <string>

namespace throng {

/// import_crowd's options: `fps` (absent: the rate the data states), `credit`, `species_from`, `obstacles`,
/// `columns`, `units`, `radius`, `wall_thickness`.
void describe(OptionBinder& b, ImportOptions& o);

/// The options that say how to read the data's content, for a recorded crowd another job reads (a tiling
/// library's `library.real`): `fps`, `credit`, `columns`, `units` (import's keys and flags; the rest —
/// species, obstacles, radius — is import's own: a tiling library takes only the paths).
void describe_reading(OptionBinder& b, ImportOptions& o);

/// What `throng plot` and the `plot` step draw.
struct PlotJob {
  PlotOptions picture;
  std::string view = "top";  ///< 3-D crowds: top (x, y), front (x, z: looking north) or side (y, z: looking west)
  bool tiling = true;        ///< a file written by `throng tile` is drawn as its tiling (io/tiling_plot.h)
};

void describe(OptionBinder& b, PlotJob& job);

/// What `throng check-tiling` lists.
struct CheckTilingJob {
  std::size_t max_failures = 1000;  ///< failures listed at most (all are counted)
};

void describe(OptionBinder& b, CheckTilingJob& job);

}  // namespace throng
