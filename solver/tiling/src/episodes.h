// Episode detection (construct.h steps 3 and 4): events between pairs of tracks, merged into episodes.
#pragma once

#include "real_track.h"

#include <cstddef>
#include <vector>

namespace throng::tiling {

/// Consecutive event samples of two tracks (global sample indices, inclusive).
struct Event {
  std::size_t a = 0, b = 0;   ///< track indices, a < b
  long first = 0, last = 0;
  long closest = 0;           ///< the sample of their closest approach
};

/// Events merged: the tracks (ascending), the union interval and the events themselves.
struct Episode {
  std::vector<std::size_t> tracks;
  long first = 0, last = 0;
  std::vector<Event> events;
};

/// Every event of every pair of tracks of different agents that lasts at least min_contact_s.
[[nodiscard]] std::vector<Event> detect_events(const std::vector<Track>& tracks, const RealPatchOptions& o);

/// Events joined by the merging rule, in order of their first sample.
[[nodiscard]] std::vector<Episode> merge_events(const std::vector<Event>& events, const std::vector<Track>& tracks,
                                                const RealPatchOptions& o);

}  // namespace throng::tiling
