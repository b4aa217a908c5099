// The parts of a crowd file (crowd_file.h) for writers and readers of other layouts: the streamed tiling file
// (io/tiling_stream.h) writes the fixed parts once and grows the per-frame arrays itself, and the tiling reader
// (io/tiling_data.h) reads the scene without the frames.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/core/scene.h>
#include <throng/io/crowd_file.h>
#include <throng/io/hdf5.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace throng::detail {

/// /h5md (version, author, creator, units) and /parameters/throng with the provenance's attributes and the
/// scene. Returns /parameters/throng.
h5::Group write_crowd_header(const h5::Group& root, const Provenance& provenance, const Scene& scene);

/// The orientation element's `components` attribute: quaternions stored x, y, z, w (scalar last).
extern const std::vector<std::string> quaternion_components;

/// The attributes of the orientation element `element`: its quaternion components and body frame.
void write_orientation_attributes(const h5::Group& element);
/// The attributes of the action element `element`: the action table `table` (names, props).
void write_action_attributes(const h5::Group& element, const std::vector<ActionKind>& table);

/// The crowd file's fixed per-agent parts: /connectivity/formation_edges (when `formation_edges` has any, with
/// its particles_group reference) and /parameters/throng/agents id and radius (`parameters` is
/// /parameters/throng).
void write_agent_parts(const h5::Group& root, const h5::Group& parameters, const CrowdMotion& motion,
                       const std::vector<std::array<std::int32_t, 2>>& formation_edges);

/// The H5MD box's attributes (dimension, boundary) on `box`, and its offset when the scene's region wraps in x or
/// y (its edges, a time-dependent element, are the caller's).
void write_box_attributes(const h5::Group& box, const Scene& scene);

/// InputError when the file's /parameters/throng names a format version other than crowd_format_version.
void check_format_version(const h5::Group& root);

/// One frame of the H5MD box's edges for a region periodic in x or y: diag(width, height, 0), row-major 3 × 3 (the
/// form MDAnalysis reads as the box vectors; a zero z side makes it report no box rather than an invented one).
[[nodiscard]] std::array<double, 9> box_edges_frame(const Region& region);

/// The scene stored under `parameters` (/parameters/throng; an empty scene without a scene group), validated.
/// InputError naming the dataset that is malformed.
[[nodiscard]] Scene read_scene(const h5::Group& parameters);

/// The scene of a crowd file (/parameters/throng/scene; an empty scene when absent), with the format version
/// checked, without reading any frame. InputError as read_crowd_file's.
[[nodiscard]] Scene read_crowd_scene(const h5::File& file);

/// The number of agents a crowd file holds (/parameters/throng/agents/id, else the columns of position/value),
/// from the datasets' shapes alone.
[[nodiscard]] std::uint64_t crowd_agent_count(const h5::File& file);

}  // namespace throng::detail
