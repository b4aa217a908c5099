// Export to XDMF: a sidecar .xmf (plain XML, no data copied) that points into a crowd's .h5, so ParaView and
// VisIt open the crowd as a time series of points. ParaView opens the .xmf with its "XDMF Reader" (File > Open,
// or XDMFReader(FileNames=[...]) in pvpython): one time step per frame, one point per agent (absent agents at
// NaN, id −1: a Threshold on id ≥ 0 hides them), with point data
//
//   id           int64, −1 where absent                  particles/trajectory/id/value, frame t
//   radius       float64 (crowd files of throng)          parameters/throng/agents/radius
//   species      int32 (when stored)                      particles/trajectory/species
//   orientation  4 components (x, y, z, w), when stored   particles/trajectory/orientation/value, frame t
//   facing       the unit vector the agent faces (a glyph's orientation), computed by the reader from the
//                stored quaternion: (1 − 2(y² + z²), 2(xy + wz), 2(xz − wy))
//   action       int32 index into the action table, −1 where absent, when stored; the names are the
//                attribute names of particles/trajectory/action in the .h5
//
// A crowd file without stored facing or actions (older files, methods that fill neither yet) has no facing,
// orientation or action to point at: those arrays are left out (the sidecar copies no data). Every frame
// selects its slice of the .h5 datasets with an XDMF HyperSlab, which ParaView's legacy "XDMF Reader" reads.
#pragma once

#include <cstddef>
#include <filesystem>

namespace throng {

/// The size of the crowd a sidecar describes.
struct CrowdShape {
  std::size_t frames = 0, agents = 0;
};

/// Writes `output` (conventionally the crowd's name with .xmf, beside it) atomically, referring to `crowd` by its
/// path relative to the .xmf's folder. Reads the crowd's layout and frame times only. IoError / InputError for a missing or
/// malformed crowd file, IoError when the output folder does not exist.
CrowdShape export_xdmf(const std::filesystem::path& crowd, const std::filesystem::path& output);

}  // namespace throng
