// The crowd file of a windowed tiling (`throng tile` with `window:`), written window by window as the tiler makes
// each part final (tiling/windowed.h): memory stays bounded by a window whatever the horizon, and a run stopped
// between windows is resumed from its last complete window.
//
// The file is a crowd file (crowd_file.h) holding tiling data (tiling_data.h), in H5MD's form for a changing set
// of particles:
//   - a column of the per-frame elements (position, orientation, action, id) is a *slot*; id/value[T][S] names
//     the agent in each slot at each frame (−1: empty). An agent keeps one slot from its first frame to its last;
//     a slot left free is given to the next agent that appears (the lowest free slot first, agents in id order).
//     (An agent of a tiling is one present run: it never leaves and comes back.)
//     S is the most agents present at once, not every agent of the run: an hour of a plaza stays a few hundred
//     columns wide.
//   - /parameters/throng/agents lists every agent: id int64[A] = 0 .. A − 1 (ids in order of appearance, as
//     lay_out gives them), radius float64[A] (the largest fragment the agent walks), species int32[A] (0).
//   - under /parameters/throng/tiling, besides tiling_data.h's datasets (rows appended per window, instances in
//     their delivered order), windows float64[W][7] (t0, t1, freeze, carried in, instances of the kept chain,
//     carried out, dangling ends at the window's end) and density float64[R][7] (t0, t1, area, target, mean,
//     lowest, highest: per time window and density area, as DensityWindow measures them). The report's fields
//     are attributes, written when the last window is done.
// Every per-frame dataset is chunked by slots and frames and compressed; nothing holds a wall time, so the same
// job and seed give the same data whatever the thread count, resumed or not.
//
// Writing goes to a partial file beside the output (`.NAME.partial`, see resumable_paths()); after each window
// the writer flushes it, and the caller records record() with the tiler's state. The partial becomes the output
// only when the last window is written (the output is never half a file).
#pragma once

#include <throng/core/report.h>
#include <throng/io/crowd_file.h>
#include <throng/io/hdf5.h>
#include <throng/tiling/check.h>
#include <throng/tiling/windowed.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <vector>

namespace throng {

/// What is fixed for the whole stream.
struct TilingStreamSetup {
  const tiling::PatchLibrary* library = nullptr;
  const tiling::Environment* environment = nullptr;
  tiling::CheckOptions check;
  Provenance provenance;
  std::size_t frames_per_window = 600;  ///< chunk rows of the per-frame datasets
  double density_tolerance = 0.1;       ///< a window's density is met within this relative error
};

/// How far a stream got: the sizes of its datasets after its last complete window and the agents holding slots.
/// Saved beside the tiler's state; a resumed writer cuts its datasets back to these sizes.
struct TilingStreamRecord {
  std::uint64_t frames = 0, slots = 0, agents = 0, instances = 0, path_rows = 0, connections = 0, pieces = 0,
                windows = 0, density_rows = 0;
  std::uint64_t lost_dangling = 0;  ///< dangling ends lost so far (tiling/windowed.h WindowOutput): 0 is perfect
  struct Active {
    std::uint64_t slot = 0;
    double radius = 0;
    std::vector<std::array<std::int64_t, 5>> last_pieces;  ///< the agent's pieces of the last window written
  };
  std::map<std::int64_t, Active> active;  ///< agents holding a slot, by id
  double density_worst = 0;               ///< the largest relative density error so far
  bool density_met = true;

  void save(std::vector<std::byte>& out) const;
  /// InputError naming `where` for bytes that are not a record.
  static TilingStreamRecord load(const std::vector<std::byte>& in, std::size_t& at, const std::string& where);
};

/// The report of a finished windowed tiling: on stdout and as attributes of /parameters/throng/tiling.
struct WindowedSummary {
  TilingStreamRecord record;
  std::size_t patch_types = 0;
  double density_tolerance = 0.1;
  bool density_asked = false;
  double seconds = 0;  ///< wall time of this run (stdout only)
};
void describe(ReportWriter& w, const WindowedSummary& s);

class TilingStreamWriter {
 public:
  /// Creates (replacing) the partial file `path` with everything fixed for the run: the H5MD header, the
  /// provenance, the scene, the library and the check options. `display_name`: the output's name, for messages.
  TilingStreamWriter(const std::filesystem::path& path, const std::string& display_name, const TilingStreamSetup& setup);
  /// Reopens the partial file of an interrupted run and cuts it back to `record`. InputError when the file is not
  /// such a partial file or holds less than the record says.
  TilingStreamWriter(const std::filesystem::path& path, const std::string& display_name, const TilingStreamSetup& setup,
                     const TilingStreamRecord& record);
  ~TilingStreamWriter();
  TilingStreamWriter(const TilingStreamWriter&) = delete;
  TilingStreamWriter& operator=(const TilingStreamWriter&) = delete;

  /// Appends what a window made final, then flushes the file. IoError on a failed write (a full disk).
  void append(const tiling::WindowOutput& out);
  [[nodiscard]] const TilingStreamRecord& record() const noexcept;
  /// Writes the report's fields and closes the file (IoError on failure).
  void finish(const WindowedSummary& summary);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The partial file and the resume record of the output `target`: `.NAME.partial` and `.NAME.partial.state` in
/// its folder.
struct ResumablePaths {
  std::filesystem::path partial;
  std::filesystem::path state;
};
[[nodiscard]] ResumablePaths resumable_paths(const std::filesystem::path& target);

}  // namespace throng
