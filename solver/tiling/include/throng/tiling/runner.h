// Motion-patch tiling as a job: what `throng tile`, the `tile` step of `throng run` and library users run. The job
// file's format is in throng/io/tiling_job.h. A job names its library (built-in patches, patches from a recorded
// crowd) and its keyframes by patch name; prepare() builds the library, so reading a job builds nothing.
#pragma once

#include <throng/core/communicator.h>
#include <throng/core/crowd.h>
#include <throng/core/report.h>
#include <throng/core/schema.h>
#include <throng/tiling/characters.h>
#include <throng/tiling/check.h>
#include <throng/tiling/construct.h>
#include <throng/tiling/density.h>
#include <throng/tiling/library.h>
#include <throng/tiling/tile.h>
#include <throng/tiling/windowed.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace throng::tiling {

/// What the library is made from.
struct LibrarySpec {
  std::vector<std::string> builtin;   ///< built-in patch names or groups (library.h)
  BuiltinOptions builtin_options;
  bool real = false;                  ///< patches from a recorded crowd, given to prepare()
  RealPatchOptions real_options;
  /// A library saved by an earlier run (library.file: the library of a file written by `throng tile`), loaded by
  /// the caller (reading a job builds and loads nothing); its types come first.
  std::optional<PatchLibrary> saved;
  std::vector<std::pair<std::string, double>> preferences;  ///< per type name, the phase-1 sampling weight
};

/// A keyframed instance of a patch named in the library.
struct KeyframeSpec {
  std::string patch;
  Transform transform;
};

struct Job {
  LibrarySpec library;
  Environment environment;
  std::vector<KeyframeSpec> keyframes;
  Options options;                    ///< its seed: the caller's (--seed for the program)
  LayoutOptions layout;
  /// > 0: the horizon is tiled window by window of this many seconds and streamed to the output as it goes
  /// (windowed.h; `throng tile` alone: run() refuses it, a whole crowd in memory is what windows avoid).
  double window_s = 0;
};

/// The job's options: Options, `output:` (LayoutOptions), `library.builtin_options`, `library.real`.
void describe(OptionBinder& b, Job& job);

/// The built-in patch names a list of names and groups stands for, in order, each once. ConfigError naming an
/// unknown one.
[[nodiscard]] std::vector<std::string> builtin_names(const std::vector<std::string>& names_or_groups);

/// A job ready to tile: its library, and its keyframes by type index.
struct Prepared {
  PatchLibrary library;
  std::vector<Keyframe> keyframes;
  std::size_t recorded_types = 0;     ///< the last types of the library: made from the recorded crowd
};

/// Builds the library (the built-in patches, then those from `recorded` when the job asks for them), applies the
/// preferences, resolves the keyframes' names, and bounds the resources tile() would need (tile.h): ConfigError
/// naming the keys to change (library.builtin_options.sample_rate, index.cell ...).
[[nodiscard]] Prepared prepare(const Job& job, const CrowdMotion* recorded);

/// The windowed tiler's options of a job with `window`: its frames as `output:` lays them.
[[nodiscard]] WindowOptions window_options(const Job& job);

/// The check options that go with a job's tiler options (the same limits and thresholds).
[[nodiscard]] CheckOptions check_options_for(const Options& options);

/// The scene of the laid characters (the crowd file's scene): the region covers every laid copy (repeat[a]
/// periods along each periodic axis) and keeps the tile's periodic flags (the laid box repeats as the tile does);
/// obstacles are copied into every laid copy in space (the tile's own first, then copy by copy, x-major).
/// Moving obstacles follow their motion once: a time copy of a periodic-time tile does not repeat it.
[[nodiscard]] Scene laid_scene(const Environment& environment, const LayoutOptions& layout);

/// A finished tiling.
struct Run {
  Crowd crowd;                 ///< the laid characters among the laid scene
  PatchLibrary library;
  TilingResult result;
  Characters characters;       ///< the fragments each agent walks (its motion moved to crowd)
  Environment environment;
  CheckOptions check;
  LayoutOptions layout;
  std::size_t max_steps = 0;
  DensityReport density;       ///< per report window and area, when the job asks for a density per area
  int ranks = 1;               ///< the ranks the chains were spread over
  std::vector<std::string> warnings;
  std::string shortfall;       ///< dangling ends, and why the search stopped
};

/// Prepares and tiles the job (chains spread over `communicator`'s ranks), then lays out the characters. `inputs`:
/// the recorded crowd the library takes patches from (library.real), else none.
[[nodiscard]] Run run(const Crowds& inputs, const Job& job, Progress& progress, const Communicator& communicator);

/// The report: the same fields on stdout and in /parameters/throng/tiling.
void describe(ReportWriter& w, const Run& run);

}  // namespace throng::tiling
