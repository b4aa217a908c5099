// Patch construction from recorded trajectories (construct.h).
#include <throng/tiling/construct.h>

#include <throng/core/errors.h>

#include "geometry.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace throng::tiling {
namespace {

// One agent's resampled, uninterrupted span.
struct Track {
  std::size_t agent = 0;
  double t0 = 0;                        // time of sample 0
  std::vector<Eigen::Vector2d> p;       // positions
  std::vector<Eigen::Vector2d> v;       // velocities (central differences)
  std::vector<double> heading;          // of the velocity, held while standing
  std::vector<bool> standing;
  std::vector<bool> clean;              // a boundary may fall here
};

std::vector<Track> resample(const CrowdMotion& m, const RealPatchOptions& o) {
  std::vector<Track> tracks;
  const double dt = 1.0 / o.sample_rate_hz;
  for (std::size_t a = 0; a < m.agent_count(); ++a) {
    // Recorded samples of the agent, split at gaps.
    std::vector<std::pair<double, Eigen::Vector2d>> run;
    const auto flush = [&]() {
      if (run.size() >= 2 && run.back().first - run.front().first >= 2 * dt) {
        Track tr;
        tr.agent = a;
        tr.t0 = std::ceil(run.front().first / dt - 1e-9) * dt;
        std::size_t k = 0;
        for (double t = tr.t0; t <= run.back().first + 1e-9; t += dt) {
          while (k + 2 < run.size() && run[k + 1].first < t) ++k;
          const double u = std::clamp((t - run[k].first) / (run[k + 1].first - run[k].first), 0.0, 1.0);
          tr.p.push_back(run[k].second + u * (run[k + 1].second - run[k].second));
        }
        if (tr.p.size() >= 3) tracks.push_back(std::move(tr));
      }
      run.clear();
    };
    for (std::size_t f = 0; f < m.frame_count(); ++f) {
      if (!m.present(f, a)) {
        flush();
        continue;
      }
      if (!run.empty() && m.times[f] - run.back().first > o.max_gap_s) flush();
      const auto q = m.position(f, a);
      run.emplace_back(m.times[f], Eigen::Vector2d(q.x(), q.y()));
    }
    flush();
  }
  for (Track& tr : tracks) {
    const std::size_t n = tr.p.size();
    tr.v.resize(n);
    for (std::size_t s = 0; s < n; ++s) {
      const std::size_t lo = s == 0 ? 0 : s - 1, hi = s + 1 == n ? s : s + 1;
      tr.v[s] = (tr.p[hi] - tr.p[lo]) / (static_cast<double>(hi - lo) * dt);
    }
    tr.heading.resize(n);
    tr.standing.resize(n);
    tr.clean.resize(n);
    // Heading: of the velocity where moving; held (backwards first, then forwards) where standing.
    double last = std::nan("");
    for (std::size_t s = 0; s < n; ++s) {
      tr.standing[s] = tr.v[s].norm() < o.standing_speed_mps;
      if (!tr.standing[s]) last = std::atan2(tr.v[s].y(), tr.v[s].x());
      tr.heading[s] = last;
    }
    double first = 0;
    for (std::size_t s = 0; s < n; ++s) {
      if (!std::isnan(tr.heading[s])) {
        first = tr.heading[s];
        break;
      }
    }
    for (std::size_t s = 0; s < n && std::isnan(tr.heading[s]); ++s) tr.heading[s] = first;
    for (std::size_t s = 1; s + 1 < n; ++s) {
      const double accel = (tr.v[s + 1] - tr.v[s - 1]).norm() / (2 * dt);
      tr.clean[s] = tr.standing[s] ? tr.v[s].norm() < o.standing_speed_mps / 3 : accel < o.clean_acceleration_mps2;
    }
  }
  return tracks;
}

// The clean sample of `tr` nearest to `s` within [lo, hi]; n (none) when there is none.
std::size_t nearest_clean(const Track& tr, std::size_t s, std::size_t lo, std::size_t hi) {
  for (std::size_t d = 0; d <= hi - lo; ++d) {
    if (s >= lo + d && s - d <= hi && tr.clean[s - d]) return s - d;
    if (s + d <= hi && s + d >= lo && tr.clean[s + d]) return s + d;
  }
  return tr.p.size();
}

Fragment fragment_of(const Track& tr, std::size_t a, std::size_t b, double dt, const RealPatchOptions& o, std::size_t standing,
                     std::size_t walking) {
  Fragment f;
  f.radius_m = o.radius_m;
  for (std::size_t s = a; s <= b; ++s) {
    f.positions.push_back(tr.p[s]);
    f.headings.push_back(wrap_angle(tr.heading[s]));
    f.times.push_back(tr.t0 + static_cast<double>(s) * dt);
  }
  f.entry_class = tr.standing[a] ? standing : walking;
  f.exit_class = tr.standing[b] ? standing : walking;
  // Walking ends face along the path (as the built-in patches): the end's heading is its tangent's.
  const auto along = [&](std::size_t i, std::size_t j, double& h) {
    const Eigen::Vector2d d = f.positions[j] - f.positions[i];
    if (d.norm() > 1e-6) h = std::atan2(d.y(), d.x());
  };
  if (f.entry_class == walking) along(0, 1, f.headings.front());
  if (f.exit_class == walking) along(f.positions.size() - 2, f.positions.size() - 1, f.headings.back());
  return f;
}

}  // namespace

PatchLibrary patches_from_trajectories(const CrowdMotion& motion, const RealPatchOptions& o) {
  const auto positive = [](double v, const char* what) {
    if (!(v > 0) || !std::isfinite(v)) throw ConfigError(std::string("real patches: ") + what + " must be > 0");
  };
  positive(o.sample_rate_hz, "sample_rate");
  positive(o.max_gap_s, "max_gap");
  positive(o.radius_m, "radius");
  positive(o.standing_speed_mps, "standing_speed");
  positive(o.clean_acceleration_mps2, "clean_acceleration");
  positive(o.near_m, "near");
  positive(o.single_duration_s, "single_duration");
  positive(o.preference_per_character, "preference_per_character");
  const double dt = 1.0 / o.sample_rate_hz;
  const std::vector<Track> tracks = resample(motion, o);

  PatchLibrary lib;
  const std::size_t standing = lib.pose_class("standing"), walking = lib.pose_class("walking");

  // Interaction episodes between pairs of tracks.
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < tracks.size() && pairs < o.max_pair_patches; ++i) {
    for (std::size_t j = i + 1; j < tracks.size() && pairs < o.max_pair_patches; ++j) {
      const Track& A = tracks[i];
      const Track& B = tracks[j];
      if (A.agent == B.agent) continue;
      // Common samples: A's index s and B's index s + shift.
      const auto shift = static_cast<long>(std::lround((A.t0 - B.t0) / dt));
      const long lo = std::max<long>(0, -shift), hi = std::min<long>(static_cast<long>(A.p.size()), static_cast<long>(B.p.size()) - shift);
      long s = lo;
      while (s < hi) {
        if ((A.p[static_cast<std::size_t>(s)] - B.p[static_cast<std::size_t>(s + shift)]).norm() >= o.near_m) {
          ++s;
          continue;
        }
        long e = s;
        long closest = s;
        while (e + 1 < hi && (A.p[static_cast<std::size_t>(e + 1)] - B.p[static_cast<std::size_t>(e + 1 + shift)]).norm() < o.near_m) {
          ++e;
          if ((A.p[static_cast<std::size_t>(e)] - B.p[static_cast<std::size_t>(e + shift)]).norm() <
              (A.p[static_cast<std::size_t>(closest)] - B.p[static_cast<std::size_t>(closest + shift)]).norm()) {
            closest = e;
          }
        }
        const long contact_begin = s, contact_end = e;
        s = e + 1;
        if (static_cast<double>(contact_end - contact_begin) * dt < o.min_contact_s) continue;
        const auto margin = static_cast<long>(std::lround(o.margin_s / dt));
        const long a0 = std::max(lo, contact_begin - margin), a1 = std::min(hi - 1, contact_end + margin);
        // Each fragment from and to its nearest clean samples inside the common span.
        const auto ua = static_cast<std::size_t>(a0), ub = static_cast<std::size_t>(a1);
        const std::size_t fa0 = nearest_clean(A, ua, static_cast<std::size_t>(lo), static_cast<std::size_t>(contact_begin));
        const std::size_t fa1 = nearest_clean(A, ub, static_cast<std::size_t>(contact_end), static_cast<std::size_t>(hi - 1));
        const std::size_t fb0 = nearest_clean(B, static_cast<std::size_t>(a0 + shift), static_cast<std::size_t>(lo + shift),
                                              static_cast<std::size_t>(contact_begin + shift));
        const std::size_t fb1 = nearest_clean(B, static_cast<std::size_t>(a1 + shift), static_cast<std::size_t>(contact_end + shift),
                                              static_cast<std::size_t>(hi - 1 + shift));
        if (fa0 >= A.p.size() || fa1 >= A.p.size() || fb0 >= B.p.size() || fb1 >= B.p.size()) continue;
        if (fa1 < fa0 + 2 || fb1 < fb0 + 2) continue;
        // Interest: reaction (mean |Δv| per second) and synchronicity (heading as gaze, Eq. 5).
        double reaction = 0, sync = 0;
        for (long k = contact_begin; k <= contact_end; ++k) {
          const auto ka = static_cast<std::size_t>(k), kb = static_cast<std::size_t>(k + shift);
          if (k > contact_begin) {
            reaction += ((A.v[ka] - A.v[ka - 1]).norm() + (B.v[kb] - B.v[kb - 1]).norm()) / 2;
          }
          const Eigen::Vector2d ab = (B.p[kb] - A.p[ka]).normalized();
          sync += 0.5 * (std::cos(A.heading[ka]) * ab.x() + std::sin(A.heading[ka]) * ab.y() -
                         (std::cos(B.heading[kb]) * ab.x() + std::sin(B.heading[kb]) * ab.y()));
        }
        const double span = static_cast<double>(contact_end - contact_begin) * dt;
        reaction /= span;
        sync /= static_cast<double>(contact_end - contact_begin + 1);
        if (reaction < o.reaction_min_mps2 && sync < o.synchronicity_min) continue;

        PatchType t;
        t.name = o.prefix + "pair_" + std::to_string(pairs);
        t.label = "pair";
        t.fragments.push_back(fragment_of(A, fa0, fa1, dt, o, standing, walking));
        t.fragments.push_back(fragment_of(B, fb0, fb1, dt, o, standing, walking));
        for (long k : {contact_begin, closest, contact_end}) {
          const auto ka = static_cast<std::size_t>(k), kb = static_cast<std::size_t>(k + shift);
          if (ka < fa0 || ka > fa1 || kb < fb0 || kb > fb1) continue;
          const InterpersonalConstraint c{0, ka - fa0, 1, kb - fb0};
          if (std::none_of(t.constraints.begin(), t.constraints.end(), [&](const InterpersonalConstraint& x) {
                return x.sample_a == c.sample_a && x.sample_b == c.sample_b;
              })) {
            t.constraints.push_back(c);
          }
        }
        t.preference = 2 * o.preference_per_character;
        lib.types.push_back(std::move(t));
        ++pairs;
      }
    }
  }

  // Single-character pieces between clean samples, spread over the data.
  struct Piece {
    std::size_t track, a, b;
  };
  std::vector<Piece> pieces;
  const auto length = static_cast<std::size_t>(std::lround(o.single_duration_s / dt));
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    const Track& tr = tracks[i];
    std::size_t a = nearest_clean(tr, 1, 1, tr.p.size() - 2);
    while (a < tr.p.size() && a + length + 1 < tr.p.size()) {
      const std::size_t b = nearest_clean(tr, a + length, a + length / 2, std::min(tr.p.size() - 2, a + 2 * length));
      if (b >= tr.p.size()) break;
      pieces.push_back({i, a, b});
      a = b + 1 < tr.p.size() - 1 ? nearest_clean(tr, b + 1, b + 1, tr.p.size() - 2) : tr.p.size();
    }
  }
  const std::size_t keep = std::min(pieces.size(), o.max_single_patches);
  for (std::size_t k = 0; k < keep; ++k) {
    const Piece& pc = pieces[k * pieces.size() / keep];
    PatchType t;
    t.name = o.prefix + "single_" + std::to_string(k);
    t.label = "single";
    t.fragments.push_back(fragment_of(tracks[pc.track], pc.a, pc.b, dt, o, standing, walking));
    t.preference = o.preference_per_character;
    lib.types.push_back(std::move(t));
  }
  if (lib.types.empty()) {
    std::ostringstream m;
    m << "real patches: the trajectories give no patch (" << tracks.size() << " resampled spans, none long enough for "
      << o.single_duration_s << " s pieces and no pair closer than " << o.near_m << " m for " << o.min_contact_s << " s)";
    throw InputError(m.str());
  }
  normalise_frames(lib);
  lib.validate("real patches");
  return lib;
}

void merge_into(PatchLibrary& into, const PatchLibrary& more) {
  std::map<std::size_t, std::size_t> classes;
  for (std::size_t c = 0; c < more.pose_classes.size(); ++c) classes[c] = into.pose_class(more.pose_classes[c]);
  for (PatchType t : more.types) {
    if (std::any_of(into.types.begin(), into.types.end(), [&](const PatchType& x) { return x.name == t.name; })) {
      throw ConfigError("patch library: the type name '" + t.name + "' is used twice");
    }
    for (Fragment& f : t.fragments) {
      f.entry_class = classes[f.entry_class];
      f.exit_class = classes[f.exit_class];
    }
    into.types.push_back(std::move(t));
  }
}

}  // namespace throng::tiling
