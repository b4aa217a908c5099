// The independent checker (check.h). Deliberately shares no code with the tiler beyond the public types and
// end_needs_no_partner (the definition of the region rule): its own geometry, its own deformation measures, its
// own pruning (sorted space-time boxes per fragment) and brute-force segment tests.
#include <throng/tiling/check.h>

#include <throng/core/errors.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <sstream>

namespace throng::tiling {
namespace {

double wrap(double a) {
  a = std::remainder(a, 2.0 * std::numbers::pi);
  return a <= -std::numbers::pi ? a + 2.0 * std::numbers::pi : a;
}

Eigen::Vector2d turn_by(const Eigen::Vector2d& p, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * p.x() - s * p.y(), s * p.x() + c * p.y()};
}

double signed_turn(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
}

// Smallest centre distance of two discs moving linearly over [ta, tb] and [ua, ub]; +inf without common time.
double approach(const Eigen::Vector2d& a0, const Eigen::Vector2d& a1, double ta, double tb, const Eigen::Vector2d& b0,
                const Eigen::Vector2d& b1, double ua, double ub) {
  const double lo = std::max(ta, ua), hi = std::min(tb, ub);
  if (lo > hi) return std::numeric_limits<double>::infinity();
  const auto at = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q, double t0, double t1, double t) {
    return Eigen::Vector2d(p + (t - t0) / (t1 - t0) * (q - p));
  };
  const Eigen::Vector2d d0 = at(a0, a1, ta, tb, lo) - at(b0, b1, ua, ub, lo);
  const Eigen::Vector2d d1 = at(a0, a1, ta, tb, hi) - at(b0, b1, ua, ub, hi);
  const Eigen::Vector2d w = d1 - d0;
  const double ww = w.squaredNorm();
  const double s = ww > 0 ? std::clamp(-d0.dot(w) / ww, 0.0, 1.0) : 0.0;
  return (d0 + s * w).norm();
}

std::string fragment_name(const PatchLibrary& library, const Tiling& tiling, std::size_t i, std::size_t f) {
  std::ostringstream m;
  m << "instance " << i << " ('" << library.types[tiling.instances[i].type].name << "') fragment " << f;
  return m.str();
}

class Checker {
 public:
  Checker(const PatchLibrary& library, const Tiling& tiling, const Environment& environment, const CheckOptions& options,
          std::size_t max_failures)
      : lib_(library), tiling_(tiling), env_(environment), o_(options), max_(max_failures) {
    if (env_.scene.region) {
      const Region& r = *env_.scene.region;
      period_ = {r.periodic[0] ? r.max.x() - r.min.x() : 0.0, r.periodic[1] ? r.max.y() - r.min.y() : 0.0,
                 r.periodic[2] ? r.t1 - r.t0 : 0.0};
    }
  }

  CheckReport run() {
    well_formed();
    report_.instances = tiling_.instances.size();
    report_.connections = tiling_.connections.size();
    ends_and_connections();
    deformation_and_keyframes();
    overlaps();
    obstacles();
    return std::move(report_);
  }

 private:
  void fail(FailureKind kind, const std::string& message) {
    ++report_.totals[static_cast<std::size_t>(kind)];
    if (report_.failures.size() < max_) report_.failures.push_back({kind, message});
  }

  void well_formed() const {
    for (std::size_t i = 0; i < tiling_.instances.size(); ++i) {
      const Instance& inst = tiling_.instances[i];
      if (inst.type >= lib_.types.size()) {
        throw InputError("tiling instance " + std::to_string(i) + ": patch type " + std::to_string(inst.type) +
                         " not in the library of " + std::to_string(lib_.types.size()));
      }
      const PatchType& type = lib_.types[inst.type];
      if (inst.paths.size() != type.fragments.size()) {
        throw InputError("tiling instance " + std::to_string(i) + ": " + std::to_string(inst.paths.size()) +
                         " paths, its type '" + type.name + "' has " + std::to_string(type.fragments.size()) + " fragments");
      }
      for (std::size_t f = 0; f < inst.paths.size(); ++f) {
        const Path& p = inst.paths[f];
        const std::size_t n = type.fragments[f].sample_count();
        if (p.positions.size() != n || p.headings.size() != n || p.times.size() != n) {
          throw InputError("tiling instance " + std::to_string(i) + " fragment " + std::to_string(f) +
                           ": path has " + std::to_string(p.times.size()) + " samples, the patch " + std::to_string(n));
        }
        for (std::size_t s = 0; s < n; ++s) {
          if (!p.positions[s].allFinite() || !std::isfinite(p.headings[s]) || !std::isfinite(p.times[s])) {
            throw InputError("tiling instance " + std::to_string(i) + " fragment " + std::to_string(f) + " sample " +
                             std::to_string(s) + ": a value is not finite");
          }
        }
      }
    }
    for (std::size_t c = 0; c < tiling_.connections.size(); ++c) {
      const Connection& k = tiling_.connections[c];
      for (const FragmentRef& r : {k.from, k.to}) {
        if (r.instance >= tiling_.instances.size() ||
            r.fragment >= lib_.types[tiling_.instances[r.instance].type].fragments.size()) {
          throw InputError("tiling connection " + std::to_string(c) + " names instance " + std::to_string(r.instance) +
                           " fragment " + std::to_string(r.fragment) + ", which does not exist");
        }
      }
    }
  }

  [[nodiscard]] const Fragment& fragment(const FragmentRef& r) const {
    return lib_.types[tiling_.instances[r.instance].type].fragments[r.fragment];
  }
  [[nodiscard]] const Path& path(const FragmentRef& r) const { return tiling_.instances[r.instance].paths[r.fragment]; }

  void ends_and_connections() {
    std::map<FragmentRef, int> exits_used, entries_used;
    for (std::size_t c = 0; c < tiling_.connections.size(); ++c) {
      const Connection& k = tiling_.connections[c];
      ++exits_used[k.from];
      ++entries_used[k.to];
      const bool seam = k.image != std::array<int, 3>{0, 0, 0};
      const FailureKind kind = seam ? FailureKind::seam : FailureKind::connection;
      std::ostringstream where;
      where << "connection " << c << " (exit of " << fragment_name(lib_, tiling_, k.from.instance, k.from.fragment)
            << " → entry of " << fragment_name(lib_, tiling_, k.to.instance, k.to.fragment) << ", image " << k.image[0]
            << " " << k.image[1] << " " << k.image[2] << ")";
      const Fragment& a = fragment(k.from);
      const Fragment& b = fragment(k.to);
      if (!a.is_character() || !b.is_character()) {
        fail(kind, where.str() + ": joins a prop");
        continue;
      }
      if (k.from.instance == k.to.instance && k.from.fragment == k.to.fragment && k.image == std::array<int, 3>{0, 0, 0}) {
        fail(kind, where.str() + ": joins a fragment to itself");
      }
      bool bad_image = false;
      for (std::size_t ax = 0; ax < 3; ++ax) bad_image = bad_image || (k.image[ax] != 0 && !(period_[ax] > 0));
      if (bad_image) {
        fail(kind, where.str() + ": an image on an axis that is not periodic");
        continue;
      }
      if (a.exit_class != b.entry_class) {
        fail(kind, where.str() + ": pose classes differ ('" + lib_.pose_classes[a.exit_class] + "' → '" +
                       lib_.pose_classes[b.entry_class] + "')");
      }
      const Path& pa = path(k.from);
      const Path& pb = path(k.to);
      const Eigen::Vector2d shift(k.image[0] * period_[0], k.image[1] * period_[1]);
      const double tshift = k.image[2] * period_[2];
      const double d1 = (pa.positions.back() - (pb.positions.front() + shift)).norm();
      if (d1 > o_.distance_tolerance_m) {
        fail(kind, where.str() + ": Eq. 1 position gap " + std::to_string(d1) + " m");
      }
      const Eigen::Vector2d ta = pa.positions.back() - pa.positions[pa.positions.size() - 2];
      const Eigen::Vector2d tb = pb.positions[1] - pb.positions[0];
      const double d2 = (ta - tb).norm();
      if (d2 > o_.distance_tolerance_m) fail(kind, where.str() + ": Eq. 2 tangent gap " + std::to_string(d2) + " m");
      const double d3 = std::abs(pa.times.back() - (pb.times.front() + tshift));
      if (d3 > o_.time_tolerance_s) fail(kind, where.str() + ": Eq. 3 time gap " + std::to_string(d3) + " s");
      const double dh = std::abs(wrap(pa.headings.back() - pb.headings.front()));
      if (dh > o_.match.angle_rad * (1 + o_.limit_tolerance)) {
        fail(kind, where.str() + ": headings differ by " + std::to_string(dh * 180 / std::numbers::pi) + "°, limit " +
                       std::to_string(o_.match.angle_rad * 180 / std::numbers::pi) + "°");
      }
    }
    for (std::size_t i = 0; i < tiling_.instances.size(); ++i) {
      const PatchType& type = lib_.types[tiling_.instances[i].type];
      for (std::uint32_t f = 0; f < type.fragments.size(); ++f) {
        if (!type.fragments[f].is_character()) continue;
        const FragmentRef ref{static_cast<std::uint32_t>(i), f};
        const Path& p = path(ref);
        for (int side = 0; side < 2; ++side) {
          ++report_.character_ends;
          const auto& used = side == 1 ? exits_used : entries_used;
          const auto it = used.find(ref);
          const int n = it == used.end() ? 0 : it->second;
          const char* what = side == 1 ? "exit" : "entry";
          if (n > 1) {
            fail(FailureKind::connection,
                 "the " + std::string(what) + " of " + fragment_name(lib_, tiling_, i, f) + " is connected " + std::to_string(n) + " times");
          }
          if (n > 0) continue;
          const std::size_t s = side == 1 ? p.times.size() - 1 : 0;
          if (end_needs_no_partner(env_, p.positions[s], p.times[s], side == 1)) continue;
          std::ostringstream m;
          m << "the " << what << " of " << fragment_name(lib_, tiling_, i, f) << " at (" << p.positions[s].x() << ", "
            << p.positions[s].y() << ") m, " << p.times[s] << " s dangles";
          fail(FailureKind::dangling, m.str());
        }
      }
    }
  }

  void deformation_and_keyframes() {
    const DeformationLimits& L = o_.limits;
    const double slack = 1 + o_.limit_tolerance;
    // The speed limit: speed_ratio times the library's fastest segment (measured here, not by the tiler's code).
    double fastest = 0;
    for (const PatchType& type : lib_.types) {
      for (const Fragment& fr : type.fragments) {
        for (std::size_t s = 0; s + 1 < fr.sample_count(); ++s) {
          fastest = std::max(fastest, (fr.positions[s + 1] - fr.positions[s]).norm() / (fr.times[s + 1] - fr.times[s]));
        }
      }
    }
    const double top_speed =
        L.speed_ratio > 0 && fastest > 0 ? L.speed_ratio * fastest * slack : std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < tiling_.instances.size(); ++i) {
      const Instance& inst = tiling_.instances[i];
      const PatchType& type = lib_.types[inst.type];
      for (std::size_t f = 0; f < type.fragments.size(); ++f) {
        const Fragment& fr = type.fragments[f];
        const Path& p = inst.paths[f];
        const std::size_t n = fr.sample_count();
        const std::string who = fragment_name(lib_, tiling_, i, f);
        for (std::size_t s = 0; s + 1 < n; ++s) {
          const double frames = (fr.times[s + 1] - fr.times[s]) / L.frame_period_s;
          const double dt = p.times[s + 1] - p.times[s];
          if (!(dt > 0)) {
            fail(FailureKind::deformation, who + " sample " + std::to_string(s + 1) + ": time does not increase");
            continue;
          }
          const double shift = std::abs(dt - (fr.times[s + 1] - fr.times[s]));
          if (shift > L.time_shift_s * frames * slack + o_.time_tolerance_s) {
            fail(FailureKind::deformation, who + " segment " + std::to_string(s) + ": time shift " + std::to_string(shift) +
                                               " s, limit " + std::to_string(L.time_shift_s * frames) + " s");
          }
          const double stretch = std::abs((p.positions[s + 1] - p.positions[s]).norm() - (fr.positions[s + 1] - fr.positions[s]).norm());
          if (stretch > L.stretch_m * frames * slack + o_.distance_tolerance_m) {
            fail(FailureKind::deformation, who + " segment " + std::to_string(s) + ": stretch " + std::to_string(stretch) +
                                               " m, limit " + std::to_string(L.stretch_m * frames) + " m");
          }
          const double speed = (p.positions[s + 1] - p.positions[s]).norm() / dt;
          if (speed > top_speed + o_.distance_tolerance_m / dt) {
            fail(FailureKind::deformation, who + " segment " + std::to_string(s) + ": speed " + std::to_string(speed) +
                                               " m/s, limit " + std::to_string(top_speed) + " m/s (limits.speed_ratio)");
          }
        }
        for (std::size_t s = 1; s + 1 < n; ++s) {
          const Eigen::Vector2d a = fr.positions[s] - fr.positions[s - 1], b = fr.positions[s + 1] - fr.positions[s];
          const Eigen::Vector2d a2 = p.positions[s] - p.positions[s - 1], b2 = p.positions[s + 1] - p.positions[s];
          const double m = L.bend_min_segment_m;
          if (a.norm() <= m || b.norm() <= m || a2.norm() <= m || b2.norm() <= m) continue;
          const double frames = 0.5 * (fr.times[s + 1] - fr.times[s - 1]) / L.frame_period_s;
          const double bend = std::abs(wrap(signed_turn(a2, b2) - signed_turn(a, b)));
          if (bend > L.bend_rad * frames * slack) {
            fail(FailureKind::deformation, who + " sample " + std::to_string(s) + ": bend " +
                                               std::to_string(bend * 180 / std::numbers::pi) + "°, limit " +
                                               std::to_string(L.bend_rad * frames * 180 / std::numbers::pi) + "°");
          }
        }
        if (inst.keyframed) {
          double worst = 0, worst_t = 0;
          for (std::size_t s = 0; s < n; ++s) {
            worst = std::max(worst, (p.positions[s] - (turn_by(fr.positions[s], inst.transform.angle) + inst.transform.translation)).norm());
            worst_t = std::max(worst_t, std::abs(p.times[s] - (fr.times[s] + inst.transform.time_shift)));
          }
          if (worst > o_.distance_tolerance_m || worst_t > o_.time_tolerance_s) {
            fail(FailureKind::keyframe, who + ": a keyframed instance moved by " + std::to_string(worst) + " m, " +
                                            std::to_string(worst_t) + " s from where it was placed");
          }
        }
      }
      for (std::size_t c = 0; c < type.constraints.size(); ++c) {
        const InterpersonalConstraint& ic = type.constraints[c];
        const Fragment& fa = type.fragments[ic.fragment_a];
        const Fragment& fb = type.fragments[ic.fragment_b];
        const Eigen::Vector2d want = turn_by(fb.positions[ic.sample_b] - fa.positions[ic.sample_a], inst.transform.angle);
        const Eigen::Vector2d got = inst.paths[ic.fragment_b].positions[ic.sample_b] - inst.paths[ic.fragment_a].positions[ic.sample_a];
        const double dt_want = fb.times[ic.sample_b] - fa.times[ic.sample_a];
        const double dt_got = inst.paths[ic.fragment_b].times[ic.sample_b] - inst.paths[ic.fragment_a].times[ic.sample_a];
        const double dp = (want - got).norm(), dtt = std::abs(dt_want - dt_got);
        if (dp > o_.distance_tolerance_m || dtt > o_.time_tolerance_s) {
          fail(FailureKind::interpersonal, "instance " + std::to_string(i) + " ('" + type.name + "') constraint " +
                                               std::to_string(c) + ": off by " + std::to_string(dp) + " m, " +
                                               std::to_string(dtt) + " s");
        }
      }
    }
  }

  struct Box {
    std::size_t instance, fragment;
    double lo[3], hi[3];  // x, y, t grown by the radius in space
  };

  // Fragment pairs (a < b) each type brings into contact itself (patch.h contact_pairs), computed here with the
  // checker's own geometry from the library: the only pairs of an instance allowed closer than their radii.
  [[nodiscard]] std::vector<std::set<std::pair<std::size_t, std::size_t>>> declared_contacts() const {
    std::vector<std::set<std::pair<std::size_t, std::size_t>>> out(lib_.types.size());
    for (std::size_t k = 0; k < lib_.types.size(); ++k) {
      const PatchType& t = lib_.types[k];
      for (std::size_t a = 0; a < t.fragments.size(); ++a) {
        for (std::size_t b = a + 1; b < t.fragments.size(); ++b) {
          const Fragment& fa = t.fragments[a];
          const Fragment& fb = t.fragments[b];
          double d = std::numeric_limits<double>::infinity();
          for (std::size_t s = 0; s + 1 < fa.sample_count(); ++s) {
            for (std::size_t u = 0; u + 1 < fb.sample_count(); ++u) {
              d = std::min(d, approach(fa.positions[s], fa.positions[s + 1], fa.times[s], fa.times[s + 1], fb.positions[u],
                                       fb.positions[u + 1], fb.times[u], fb.times[u + 1]));
            }
          }
          if (d < fa.radius_m + fb.radius_m) out[k].insert({a, b});
        }
      }
    }
    return out;
  }

  void overlaps() {
    const auto contacts = declared_contacts();
    std::set<std::pair<FragmentRef, FragmentRef>> joined;
    for (const Connection& k : tiling_.connections) {
      joined.insert({k.from, k.to});
      joined.insert({k.to, k.from});
    }
    std::vector<Box> boxes;
    for (std::size_t i = 0; i < tiling_.instances.size(); ++i) {
      const Instance& inst = tiling_.instances[i];
      for (std::size_t f = 0; f < inst.paths.size(); ++f) {
        const Path& p = inst.paths[f];
        const double r = lib_.types[inst.type].fragments[f].radius_m;
        Box b{i, f, {1e300, 1e300, p.times.front()}, {-1e300, -1e300, p.times.back()}};
        for (const Eigen::Vector2d& q : p.positions) {
          for (int a = 0; a < 2; ++a) {
            b.lo[a] = std::min(b.lo[a], q[a] - r);
            b.hi[a] = std::max(b.hi[a], q[a] + r);
          }
        }
        boxes.push_back(b);
      }
    }
    std::sort(boxes.begin(), boxes.end(), [](const Box& a, const Box& b) { return a.lo[2] < b.lo[2]; });
    // Periodic images to try per axis: none off-period; -1, 0, 1 on a periodic axis (the boxes are smaller
    // than a period, so a nearer image cannot be missed).
    std::vector<std::array<int, 3>> images;
    for (int x = -1; x <= 1; ++x) {
      for (int y = -1; y <= 1; ++y) {
        for (int t = -1; t <= 1; ++t) {
          if ((x && !(period_[0] > 0)) || (y && !(period_[1] > 0)) || (t && !(period_[2] > 0))) continue;
          images.push_back({x, y, t});
        }
      }
    }
    std::set<std::pair<FragmentRef, FragmentRef>> reported;
    for (const std::array<int, 3>& im : images) {
      const double sx = im[0] * period_[0], sy = im[1] * period_[1], st = im[2] * period_[2];
      // Sweep over time: box b shifted by the image against box a.
      std::size_t first = 0;
      for (std::size_t ia = 0; ia < boxes.size(); ++ia) {
        const Box& a = boxes[ia];
        while (first < boxes.size() && boxes[first].lo[2] + st < a.lo[2] - max_duration()) ++first;
        for (std::size_t ib = first; ib < boxes.size(); ++ib) {
          const Box& b = boxes[ib];
          if (b.lo[2] + st > a.hi[2]) break;
          if (b.instance == a.instance) {
            // Two fragments of one instance: tested unless the patch declares them in contact.
            if (b.fragment == a.fragment || im != std::array<int, 3>{0, 0, 0}) continue;
            const auto pair = std::minmax(a.fragment, b.fragment);
            if (contacts[tiling_.instances[a.instance].type].contains({pair.first, pair.second})) continue;
          }
          if (b.hi[2] + st < a.lo[2] || b.lo[0] + sx > a.hi[0] || b.hi[0] + sx < a.lo[0] || b.lo[1] + sy > a.hi[1] ||
              b.hi[1] + sy < a.lo[1]) {
            continue;
          }
          const FragmentRef fa{static_cast<std::uint32_t>(a.instance), static_cast<std::uint32_t>(a.fragment)};
          const FragmentRef fb{static_cast<std::uint32_t>(b.instance), static_cast<std::uint32_t>(b.fragment)};
          if (joined.contains({fa, fb})) continue;
          const auto key = fa < fb ? std::pair(fa, fb) : std::pair(fb, fa);
          if (reported.contains(key)) continue;
          ++report_.pairs_tested;
          const double d = closest(fa, fb, Eigen::Vector2d(sx, sy), st);
          const double reach = fragment(fa).radius_m + fragment(fb).radius_m;
          if (d < reach - o_.distance_tolerance_m) {
            reported.insert(key);
            fail(FailureKind::overlap, fragment_name(lib_, tiling_, fa.instance, fa.fragment) + " and " +
                                           fragment_name(lib_, tiling_, fb.instance, fb.fragment) + " come " +
                                           std::to_string(d) + " m apart, closer than their radii " + std::to_string(reach) + " m");
          }
        }
      }
    }
  }

  double max_duration() {
    if (max_duration_ < 0) {
      max_duration_ = 0;
      for (const Instance& inst : tiling_.instances) {
        for (const Path& p : inst.paths) max_duration_ = std::max(max_duration_, p.times.back() - p.times.front());
      }
    }
    return max_duration_;
  }

  // Closest approach over all segment pairs of a and b (b shifted by `shift`, `tshift`).
  [[nodiscard]] double closest(const FragmentRef& a, const FragmentRef& b, const Eigen::Vector2d& shift, double tshift) const {
    const Path& p = path(a);
    const Path& q = path(b);
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t s = 0; s + 1 < p.times.size(); ++s) {
      for (std::size_t u = 0; u + 1 < q.times.size(); ++u) {
        if (q.times[u] + tshift > p.times[s + 1] || q.times[u + 1] + tshift < p.times[s]) continue;
        best = std::min(best, approach(p.positions[s], p.positions[s + 1], p.times[s], p.times[s + 1], q.positions[u] + shift,
                                       q.positions[u + 1] + shift, q.times[u] + tshift, q.times[u + 1] + tshift));
      }
    }
    return best;
  }

  void obstacles() {
    const auto& obs = env_.scene.obstacles;
    if (obs.empty()) return;
    const Region* region = env_.scene.region ? &*env_.scene.region : nullptr;
    for (std::size_t i = 0; i < tiling_.instances.size(); ++i) {
      const Instance& inst = tiling_.instances[i];
      for (std::size_t f = 0; f < inst.paths.size(); ++f) {
        const Path& p = inst.paths[f];
        const double r = lib_.types[inst.type].fragments[f].radius_m;
        const auto test = [&](const Eigen::Vector2d& q, double t) {
          if (region && period_[2] > 0) t = region->t0 + std::fmod(std::fmod(t - region->t0, period_[2]) + period_[2], period_[2]);
          for (int x = -1; x <= 1; ++x) {
            for (int y = -1; y <= 1; ++y) {
              if ((x && !(period_[0] > 0)) || (y && !(period_[1] > 0))) continue;
              const Eigen::Vector2d at = q + Eigen::Vector2d(x * period_[0], y * period_[1]);
              for (std::size_t k = 0; k < obs.size(); ++k) {
                const double d = distance_to(obs[k], at, t).signed_distance;
                if (d < r - o_.distance_tolerance_m) return std::pair<std::size_t, double>(k, d);
              }
            }
          }
          return std::pair<std::size_t, double>(obs.size(), 0.0);
        };
        bool found = false;
        for (std::size_t s = 0; s + 1 < p.times.size() && !found; ++s) {
          const Eigen::Vector2d a = p.positions[s], b = p.positions[s + 1];
          const double ta = p.times[s], tb = p.times[s + 1];
          const int n = static_cast<int>(std::max({1.0, std::ceil((b - a).norm() / o_.obstacle_step_m), std::ceil((tb - ta) / o_.obstacle_step_s)}));
          for (int j = 0; j <= n && !found; ++j) {
            const double u = static_cast<double>(j) / n;
            const auto [k, d] = test(a + u * (b - a), ta + u * (tb - ta));
            if (k < obs.size()) {
              found = true;
              std::ostringstream m;
              m << fragment_name(lib_, tiling_, i, f) << " enters obstacle " << k << " near sample " << s << " at "
                << ta + u * (tb - ta) << " s (" << d << " m from its boundary, radius " << r << " m)";
              fail(FailureKind::obstacle, m.str());
            }
          }
        }
      }
    }
  }

  const PatchLibrary& lib_;
  const Tiling& tiling_;
  const Environment& env_;
  const CheckOptions& o_;
  std::size_t max_;
  std::array<double, 3> period_{0, 0, 0};
  double max_duration_ = -1;
  CheckReport report_;
};

}  // namespace

const char* to_string(FailureKind kind) noexcept {
  switch (kind) {
    case FailureKind::dangling: return "dangling";
    case FailureKind::connection: return "connection";
    case FailureKind::seam: return "seam";
    case FailureKind::overlap: return "overlap";
    case FailureKind::obstacle: return "obstacle";
    case FailureKind::deformation: return "deformation";
    case FailureKind::interpersonal: return "interpersonal";
    case FailureKind::keyframe: return "keyframe";
  }
  return "unknown";
}

std::size_t CheckReport::total() const noexcept {
  std::size_t n = 0;
  for (std::size_t t : totals) n += t;
  return n;
}

CheckReport check_tiling(const PatchLibrary& library, const Tiling& tiling, const Environment& environment,
                         const CheckOptions& options, std::size_t max_failures) {
  return Checker(library, tiling, environment, options, max_failures).run();
}

}  // namespace throng::tiling
