// The format readers behind import_crowd (io/src, not installed). Each takes the options import_crowd checked
// and returns the crowd with what it left out in `notes`; import_crowd applies credit, obstacles and species
// files afterwards.
#pragma once

#include <throng/io/import_crowd.h>

#include <string>
#include <string_view>

namespace throng::detail {

/// Metres per unit of "m", "cm", "mm"; ConfigError for anything else. `fallback` when `units` is empty.
[[nodiscard]] double metres_per_unit(const std::string& units, double fallback);

/// True when ImportOptions::species_from names a groups file ("groups.txt": the one beside the data; or an existing
/// file) rather than "", "none" or a table column.
[[nodiscard]] bool species_from_file(const std::string& species_from);

/// The frame rate to use: the one the data states (`stated`, 0 for none) or the one given (options.fps, 0 for none).
/// ConfigError naming `source` when neither is there ("give it with --fps") or both are and differ.
[[nodiscard]] double resolve_fps(double stated, double given, const std::string& source, const std::string& stated_where);

/// 4 numbers a row `frame id x y` (whitespace), `#` comments allowed. Needs options.fps.
[[nodiscard]] ImportedCrowd read_frame_id_x_y(const std::string& source, std::string_view text, const ImportOptions& options,
                                              MemoryBudget& budget);

/// PeTrack `id frame x y z` (or `id frame x y`), centimetres unless the `#` header or options.units say otherwise,
/// frame rate from the header or options.fps.
[[nodiscard]] ImportedCrowd read_petrack(const std::string& source, std::string_view text, const ImportOptions& options,
                                         MemoryBudget& budget);

/// A table with a header row (or options.columns by index), see import_crowd.h.
[[nodiscard]] ImportedCrowd read_table(const std::string& source, std::string_view text, const ImportOptions& options,
                                       MemoryBudget& budget);

/// JuPedSim/PedPy HDF5 (/trajectory with fps; wkt_geometry becomes obstacles).
[[nodiscard]] ImportedCrowd read_pedpy(const std::filesystem::path& path, const ImportOptions& options, const ReadLimits& limits);

}  // namespace throng::detail
