// The crowd dataset file: H5MD 1.1-compatible HDF5, so existing readers (h5py, MDAnalysis, ParaView through an
// XDMF sidecar) open it, with throng's own data under /parameters/throng.
//
//   /h5md                              version = [1, 1]; author/name; creator/name, creator/version
//   /h5md/modules/units                version = [1, 0], system = "SI"
//   /particles/trajectory/box          dimension = 3, boundary = ["none"|"periodic" ×3]: x and y "periodic" where
//                                      the scene's region wraps, z "none"; when one is periodic, edges (element:
//                                      step/time hard links, value float64[T][3][3] = diag(width, height, 0), the
//                                      form MDAnalysis reads) and offset float64[3] (the region's lower corner)
//   /particles/trajectory/position     step int64[T], time float64[T] (unit "s"), value float64[T][N][3]
//                                      (metres; no unit attribute: MDAnalysis rejects "m"); NaN where absent.
//                                      The N columns are agents, or slots in a slotted file (below)
//   /particles/trajectory/velocity     optional; step/time hard links; value float64[T][N][3]
//   /particles/trajectory/id           step/time hard links; value int64[T][N], −1 where absent
//   /particles/trajectory/species      int32[N]
//   /connectivity/formation_edges      optional int32[E][2] agent indices; attribute particles_group
//   /parameters/throng                 attributes format_version (= 1), program, program_version, command_line,
//                                      seed, options (YAML text of the run's effective options), inputs,
//                                      credits (authors of real data the file derives from)
//   /parameters/throng/agents          id int64[N], radius float64[N]; a slotted file's: id int64[A],
//                                      radius float64[A], species int32[A] (optional)
//   /parameters/throng/scene           obstacles and region (see crowd_file.cpp for the layout)
//   /parameters/throng/<method>        method data: strokes, keyframes, patches, tilings, time warps ...
//
// Large datasets are chunked by frames and compressed (shuffle + deflate). Files are written atomically.
//
// Columns are agents or slots. In the classic layout (what write_crowd_file writes) column n is one agent at every
// frame. A file is *slotted* (H5MD's variable particle set: a long crowd written as it goes, hours of it with a
// few hundred agents at once) when id/value exists and some column holds two different ids ≥ 0 at different
// frames; otherwise it is classic. In a slotted file column s is a slot, id/value[t][s] names the agent in it at
// frame t (−1: empty) and a slot holds several agents one after another, so S is about the most agents present
// at once. read_crowd_file turns a slotted file into the usual CrowdMotion, one column per agent:
//  - the agents, with /parameters/throng/agents: exactly the ids of agents/id[A] (A may differ from S), in that
//    order, with agents/radius[A] and agents/species[A] (species 0 without it). Every id ≥ 0 of id/value must be
//    listed; an id listed twice is refused; a listed id that is never present is an agent with no present frame.
//    Without /parameters/throng/agents (another program's file): the distinct ids ≥ 0 of id/value in order of
//    first appearance (frame by frame, then slot), radius 0.25 m, species the slot's (/particles/trajectory/
//    species[S], else 0) at the agent's first appearance.
//  - an agent in two slots at one frame is refused. Each present slot's position (and velocity, orientation and
//    action when the file has them) moves to its agent's column, checked as in the classic layout: a finite
//    position (NaN or infinity in a present slot is refused, naming frame and slot), a unit quaternion, an action
//    in the table. Absent entries are NaN (action −1).
//  - the memory bound covers the agent columns: before they are built, frames × A of them are charged to the
//    read's budget on top of the slot arrays read (frames × S), and refused with the estimate beyond the limit
//    (a file naming 10^9 agents is refused from the shapes or while its ids are counted, before allocating).
//  - /connectivity/formation_edges is refused: edges name columns, and a slot is no agent.
// The scene, the provenance and the box read as in the classic layout.
#pragma once

#include <throng/core/crowd.h>
#include <throng/io/hdf5.h>
#include <throng/io/read_limits.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace throng {

/// The format version this program writes and reads.
inline constexpr std::int64_t crowd_format_version = 1;

/// What made a file: recorded in every output, shown by `throng info`.
struct Provenance {
  std::string program_version;        ///< "0.1.0"
  std::string command_line;           ///< the full command line of the run
  std::string options;                ///< YAML text of the run's effective options (what --print-config shows)
  std::uint64_t seed = 0;
  std::vector<std::string> inputs;    ///< input files (names as given) or data sources
  std::vector<std::string> credits;   ///< authors of data the file derives from; carried through every method

  /// Adds the credits not yet listed, in order (every place that merges credits does it this way).
  void add_credits(const std::vector<std::string>& more) {
    for (const std::string& c : more) {
      bool listed = false;
      for (const std::string& have : credits) listed = listed || have == c;
      if (!listed) credits.push_back(c);
    }
  }
};

/// A crowd (motion, scene, formation edges) and what made it.
struct CrowdFile : Crowd {
  Provenance provenance;
};

/// Adds method data under /parameters/throng (the group is passed in) before the file is closed and moved into place.
using ExtraWriter = std::function<void(const h5::Group& throng_parameters)>;

/// How the per-frame arrays are stored: shuffled and deflated (outputs: a third to a tenth of the bytes), or plain
/// (a file read back soon by the same program, as run's checkpoints are: deflate costs more time than it saves).
enum class CrowdStorage { compressed, plain };

/// Validates `file` (InputError), then writes it atomically to `path` (IoError on failure; nothing is left behind).
void write_crowd_file(const std::filesystem::path& path, const CrowdFile& file, const ExtraWriter& extra = {},
                      CrowdStorage storage = CrowdStorage::compressed);

/// Reads and validates a crowd file, classic or slotted (see the top of this file). Throws IoError (missing or
/// unreadable file) or InputError naming the dataset and the problem: not HDF5, truncated, missing dataset, wrong
/// rank or shape, NaN for a present agent, times not increasing, a column whose id is not its agent's (classic),
/// unknown format version, a periodic box without edges or that disagrees with the stored region, and a slotted
/// file's refusals above. H5MD files from other programs (no /parameters/throng) are accepted: ids from id/value
/// (or 0..N-1), radius 0.25 m, no obstacles, and a region from the box when it is periodic in x or y.
///
/// Bounded (see hdf5.h): before the first array is read, the memory the crowd needs (frames × columns for the
/// positions, ids and velocities) is estimated from the datasets' shapes and refused with the estimate when it
/// exceeds `limits`; every dataset is then checked against the file's size and charged as it is read, and a
/// slotted file's agent columns are charged before they are built.
[[nodiscard]] CrowdFile read_crowd_file(const std::filesystem::path& path, const ReadLimits& limits = {});
/// The same from a file already open for reading, within its one budget: a reader of a file that holds more than
/// the crowd (tiling data) reads the crowd and the rest under one limit.
[[nodiscard]] CrowdFile read_crowd_file(const h5::File& file);

/// Opens a crowd file's /parameters/throng group for method data, with `h5::File` kept alive by the caller.
[[nodiscard]] h5::Group open_throng_parameters(const h5::File& file);

}  // namespace throng
