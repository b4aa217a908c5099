// The tiling a crowd file written by `throng tile` carries under /parameters/throng/tiling, and reading it back
// for `throng check-tiling` and `throng plot`.
#pragma once

#include <throng/io/hdf5.h>
#include <throng/io/read_limits.h>
#include <throng/tiling/runner.h>

#include <array>
#include <filesystem>
#include <vector>

namespace throng {

/// Writes the tiling into /parameters/throng/tiling (the report's fields join it, tiling/runner.h):
///   library/pose_classes string[P]; library/type_name, type_label string[K]; library/type_preference float64[K];
///   library/type_fragments int64[K+1] (first fragment of each type); library/fragment int64[F][4] (kind 0
///   character 1 prop, entry class, exit class, first sample); library/fragment_radius float64[F];
///   library/samples float64[S+…][4] (x, y, heading, t in the type's canonical frame); library/constraints
///   int64[C][5] (type, fragment a, sample a, fragment b, sample b)
///   instances/type int64[I]; instances/transform float64[I][4] (x, y, angle rad, time shift);
///   instances/keyframed int32[I]; instances/paths float64[S'][4] (x, y, heading, t: every instance's fragments
///   in order, each with its type's sample count)
///   connections int64[C][7] (from instance, from fragment, to instance, to fragment, image x, y, t)
///   sources, sinks float64[n][5] (centre x, y, radius, t0, t1)
///   agents/pieces int64[P][6] (agent, instance, fragment, copy x, y, t): the fragments each output agent walks
///   region float64[6] (min x, min y, max x, max y, t0, t1) and region_periodic int32[3]: the tile (the crowd's
///   scene region is the laid extent, see tiling::laid_scene); repeat int64[3]: the copies laid per axis
///   attributes: the check options (limit_*, match_*, obstacle_step, obstacle_step_time) and tile_obstacles (how
///   many of the scene's obstacles, the first ones, are the tile's own). No wall time: the same seed gives the
///   same file.
}  // namespace throng

namespace throng::tiling {

void write_data(const h5::Group& record, const Run& run);

/// Instances and connections as the rows of instances/type, transform, keyframed, paths and connections.
struct TilingRows {
  std::vector<std::int64_t> types;
  std::vector<double> transforms;   ///< 4 per instance
  std::vector<std::int32_t> keyframed;
  std::vector<double> paths;        ///< 4 per sample
  std::vector<std::int64_t> connections;  ///< 7 per connection
};
[[nodiscard]] TilingRows tiling_rows(const std::vector<Instance>& instances, const std::vector<Connection>& connections);

/// The parts of write_data that a streamed tiling (tiling_stream.h) writes once, up front: the library group, and
/// the tile (region, region_periodic, repeat, sources, sinks, tile_obstacles) with the check options' attributes.
void write_library(const h5::Group& record, const PatchLibrary& library);
void write_tile_settings(const h5::Group& record, const Environment& environment, const LayoutOptions& layout,
                         const CheckOptions& check);

}  // namespace throng::tiling

namespace throng {

/// What `throng check-tiling` and `throng plot` need from a tiling file.
struct TilingData {
  tiling::PatchLibrary library;
  tiling::Tiling tiling;
  tiling::Environment environment;  ///< the tile: its region, its own obstacles, sources and sinks
  tiling::CheckOptions check;
  std::array<int, 3> repeat{1, 1, 1};                   ///< copies laid per axis
  std::vector<std::vector<tiling::AgentPiece>> pieces;  ///< per output agent, the fragment copies it walks
};

/// Reads a crowd file written by `throng tile`: its scene, its agent count and its tiling data, not its frames
/// (an hour's streamed crowd is checked without holding it). IoError (missing or unreadable), InputError (no
/// tiling data, bad shapes).
/// Bounded by `limits` as read_crowd_file is; indices and stored check options are range-checked (InputError).
[[nodiscard]] TilingData read_tiling_data(const std::filesystem::path& path, const ReadLimits& limits = {});

/// Whether a crowd file holds /parameters/throng/tiling. IoError when it cannot be opened.
[[nodiscard]] bool has_tiling_data(const std::filesystem::path& path, const ReadLimits& limits = {});

}  // namespace throng
