// Small scenes shared by the tiling tests: hand-built chains of walks, and a small tiler run.
#pragma once

#include <throng/core/progress.h>
#include <throng/tiling/library.h>
#include <throng/tiling/tile.h>

#include <Eigen/Core>

#include <numbers>
#include <vector>

namespace throng::tiling::test {

/// The built-in "walk" alone (2 s, 1.3 m/s, 2.6 m, 21 samples), canonical frame: entry at (−1.3, 0), −1 s.
inline PatchLibrary walk_library() { return builtin_library({"walk"}); }

/// An instance of type 0 of `library` placed undeformed.
Instance placed(const PatchLibrary& library, std::size_t type, const Eigen::Vector2d& at, double angle, double time);

/// A chain of `n` walks along +x at height y, the first entering at (x0, y) at time t0, each exit connected to
/// the next entry.
Tiling walk_chain(const PatchLibrary& library, int n, double x0, double y, double t0);

/// Appends `more` to `into` (instances renumbered, connections shifted).
void append(Tiling& into, const Tiling& more);

/// A region [0, w] × [0, h] × [0, d] with the given periodic flags.
Environment box(double w, double h, double d, std::array<bool, 3> periodic = {false, false, false});

/// Fast options for tests: few failures before phase 1 stops, a capped search.
Options quick_options(std::uint64_t seed = 7, std::size_t chains = 2);

}  // namespace throng::tiling::test
