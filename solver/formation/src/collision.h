// Collision avoidance after the spectral paths (§4.3): social forces, then smoothing that keeps a minimum
// distance.
#pragma once

#include <throng/formation/formation.h>

#include <cstddef>
#include <vector>

namespace throng::formation {

/// Moves `positions` ([frame][individual][3], row-major, the spectral paths on entry) so individuals keep
/// `options.min_distance_m` apart, staying close to their spectral paths:
///   1. social forces (Helbing & Molnár 1995): each individual, with the spectral position at t as its goal,
///      accelerates by (v_desired − v)/τ with v_desired = path velocity + (path point − position)/tracking time,
///      and is pushed by every near individual with A·exp((min_distance − d)/B) along their separation
///      (the model's circular form: no field-of-view anisotropy, as formation members look at each other);
///      semi-implicit Euler with frames sub-stepped to time_step_s, every step computing all forces from the
///      frozen previous state (two buffers) so the result does not depend on the thread count;
///   2. `smoothing_passes` times: each coordinate path smoothed (least squares with a second-difference penalty,
///      extent smoothing_time_s) with the frames in `pinned` (the keyframes) held at their spectral positions,
///      then every other frame projected to the minimum distance (Gauss–Seidel sweeps over close pairs, in a
///      fixed order, frames in parallel).
/// The pinned frames must already satisfy the minimum distance (the caller checks the keyframes). Returns what
/// was achieved; never throws for an unmet distance (the report says so).
[[nodiscard]] CollisionReport avoid_collisions(std::vector<double>& positions, std::size_t individuals,
                                               const std::vector<double>& times, const std::vector<std::size_t>& pinned,
                                               const CollisionOptions& options, Progress& progress);

/// Smallest centre distance between two individuals over the frames of `positions` (same layout), with where.
[[nodiscard]] CollisionReport closest_approach(const std::vector<double>& positions, std::size_t individuals,
                                               std::size_t frames, double min_distance_m);

}  // namespace throng::formation
