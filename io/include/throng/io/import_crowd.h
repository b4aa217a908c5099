// The one importer of recorded crowds: every caller that reads recorded trajectories (the `import` command and
// step, tiling libraries from real data, any pipeline step) calls import_crowd and so reads every format below.
// The format is told by the CONTENT (never by the file's or folder's name or extension):
//
//   obsmat        ETH/UCY "obsmat.txt": 8 numbers a row, `frame id x z y vx vz vy` (metres), a folder holding it
//                 or the file; map.xml and groups.txt beside it (see real_dataset.h)
//   frame-id-x-y  the trajectory-prediction benchmarks' files: 4 numbers a row `frame id x y` (metres), separated
//                 by spaces or tabs; frames are video frames: needs fps
//   petrack       Jülich/PeTrack text files: 5 numbers a row `id frame x y z`, in CENTIMETRES unless the header
//                 says otherwise; `#` comment lines (the header, which may state "framerate: 16 fps" and the unit,
//                 "x/cm" or "(in m)"), CRLF or LF line ends, no header row. A 4-number file whose header names
//                 the columns `id frame x y` is PeTrack too
//   csv           a table with a header row (separator `,` or `;`); columns found by name (time|t|seconds,
//                 frame|fr, id|pid|person|agent|track, x, y, z, species|group, radius, any case) or given by
//                 ImportOptions::columns; units by ImportOptions::units; a header-less table of numbers needs
//                 `columns` by index
//   pedpy         JuPedSim/PedPy HDF5: /trajectory compound rows {frame, id, x, y, z, ...} with attribute fps;
//                 the root attribute wkt_geometry (the walkable area) becomes obstacles (see import_pedpy.h)
//   crowd         throng's own crowd files (H5MD)
//
// When the content matches none of them: InputError (exit 3) listing the formats it knows and what it found,
// before anything asks for a frame rate.
#pragma once

#include <throng/io/crowd_file.h>
#include <throng/io/read_limits.h>

#include <filesystem>
#include <string>
#include <vector>

namespace throng {

enum class ImportFormat { obsmat, frame_id_x_y, petrack, csv, pedpy, crowd };

/// "obsmat", "frame-id-x-y", "petrack", "csv", "pedpy", "crowd".
[[nodiscard]] const char* format_name(ImportFormat format);

struct ImportOptions {
  /// Frames per second of the frame numbers. 0: the rate the data states (PeTrack header, PedPy attribute, a known
  /// ETH/UCY recording, ETH's info.txt). Needed only where the data has frame numbers and states no rate; a rate
  /// that contradicts the one the data states is a ConfigError.
  double fps = 0.0;
  /// Added to the crowd's provenance credits (after any the data's content gives).
  std::string credit;
  /// Where species come from: "" the format's own (groups.txt beside obsmat.txt; a CSV column named species or
  /// group), "none", "groups.txt" or a path to a groups file (one walking group of ids per line: species 1, 2 ...),
  /// or a CSV column name.
  std::string species_from;
  /// Obstacles instead of the data's own: a map.xml (OpenTraj walls and circles) or a throng crowd file (its scene).
  std::filesystem::path obstacles;
  /// CSV column map "time=t,id=pid,x=X,y=Y[,z=Z][,species=S][,radius=R]" (names or 0-based indices; `frame=` instead
  /// of `time=`). Empty: found by name. Also applies to header-less tables (indices only).
  std::string columns;
  /// Unit of the positions in the file: "m", "cm" or "mm". Empty: the format's own (metres; PeTrack centimetres
  /// unless its header says).
  std::string units;
  double radius = 0.25;          ///< metres, every agent's radius (unless a CSV radius column gives them)
  double wall_thickness = 0.1;   ///< metres, for map.xml walls
};

struct ImportedCrowd {
  CrowdFile crowd;
  ImportFormat format;
  /// What the import did not take over and why (extra CSV columns, PedPy orientation columns ...): for the report.
  std::vector<std::string> notes;
};

/// What `path` holds (content sniffing, see above). IoError (missing, unreadable, a device), InputError listing
/// the known formats when it matches none.
[[nodiscard]] ImportFormat detect_import_format(const std::filesystem::path& path, const ReadLimits& limits = {});

/// Detects and reads `path` (a file or a dataset folder, any spelling: "x.csv", "./X.CSV", "folder/", "."). Exit
/// codes by exception: ConfigError (2) for impossible options, InputError (3) for malformed or unknown content and
/// sizes beyond `limits`, IoError (4) for missing or unreadable files. The input is never changed.
[[nodiscard]] ImportedCrowd import_crowd(const std::filesystem::path& path, const ImportOptions& options = {},
                                         const ReadLimits& limits = {});

}  // namespace throng
