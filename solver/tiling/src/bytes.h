// The tiler's values as raw bytes (throng/core/bytes.h): paths, for the best chain sent between MPI ranks
// (serialize.h) and the resumable state of a windowed run (windowed.h).
#pragma once

#include <throng/core/bytes.h>
#include <throng/tiling/tiling.h>

namespace throng::tiling {

inline void put_path(ByteWriter& w, const Path& p) {
  w.put<std::uint64_t>(p.positions.size());
  for (const Eigen::Vector2d& q : p.positions) {
    w.put(q.x());
    w.put(q.y());
  }
  w.put_vector(p.headings);
  w.put_vector(p.times);
}

inline Path get_path(ByteReader& r) {
  Path p;
  p.positions.resize(r.count(2 * sizeof(double)));
  for (Eigen::Vector2d& q : p.positions) {
    q.x() = r.get<double>();
    q.y() = r.get<double>();
  }
  p.headings = r.get_vector<double>();
  p.times = r.get_vector<double>();
  return p;
}

}  // namespace throng::tiling
