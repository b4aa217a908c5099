#include <throng/tiling/patch.h>

#include <throng/core/errors.h>

#include "geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>

namespace throng::tiling {

std::size_t PatchType::character_count() const noexcept {
  return static_cast<std::size_t>(std::count_if(fragments.begin(), fragments.end(), [](const Fragment& f) { return f.is_character(); }));
}

std::size_t PatchType::sample_count() const noexcept {
  std::size_t n = 0;
  for (const Fragment& f : fragments) n += f.sample_count();
  return n;
}

double fastest_speed(const PatchLibrary& library) {
  double fastest = 0.0;
  for (const PatchType& type : library.types) {
    for (const Fragment& f : type.fragments) {
      for (std::size_t i = 0; i + 1 < f.sample_count(); ++i) {
        fastest = std::max(fastest, (f.positions[i + 1] - f.positions[i]).norm() / (f.times[i + 1] - f.times[i]));
      }
    }
  }
  return fastest;
}

double speed_limit(const PatchLibrary& library, double speed_ratio) {
  const double fastest = fastest_speed(library);
  return speed_ratio > 0 && fastest > 0 ? speed_ratio * fastest : std::numeric_limits<double>::infinity();
}

std::vector<std::pair<std::size_t, std::size_t>> contact_pairs(const PatchType& type) {
  std::vector<std::pair<std::size_t, std::size_t>> out;
  for (std::size_t a = 0; a < type.fragments.size(); ++a) {
    for (std::size_t b = a + 1; b < type.fragments.size(); ++b) {
      const Fragment& fa = type.fragments[a];
      const Fragment& fb = type.fragments[b];
      bool contact = false;
      for (std::size_t s = 0; s + 1 < fa.sample_count() && !contact; ++s) {
        const MovingDisc p{fa.positions[s], fa.positions[s + 1], fa.times[s], fa.times[s + 1], fa.radius_m};
        for (std::size_t u = 0; u + 1 < fb.sample_count() && !contact; ++u) {
          const MovingDisc q{fb.positions[u], fb.positions[u + 1], fb.times[u], fb.times[u + 1], fb.radius_m};
          contact = closest_approach(p, q) < fa.radius_m + fb.radius_m;
        }
      }
      if (contact) out.emplace_back(a, b);
    }
  }
  return out;
}

double PatchType::start_time() const noexcept {
  double t = std::numeric_limits<double>::infinity();
  for (const Fragment& f : fragments) {
    if (!f.times.empty()) t = std::min(t, f.times.front());
  }
  return t;
}

double PatchType::end_time() const noexcept {
  double t = -std::numeric_limits<double>::infinity();
  for (const Fragment& f : fragments) {
    if (!f.times.empty()) t = std::max(t, f.times.back());
  }
  return t;
}

std::size_t PatchLibrary::find(const std::string& name) const {
  for (std::size_t i = 0; i < types.size(); ++i) {
    if (types[i].name == name) return i;
  }
  std::ostringstream known;
  for (std::size_t i = 0; i < types.size(); ++i) known << (i ? ", " : "") << types[i].name;
  throw ConfigError("no patch type '" + name + "' in the library (known: " + known.str() + ")");
}

std::size_t PatchLibrary::pose_class(const std::string& name) {
  const auto it = std::find(pose_classes.begin(), pose_classes.end(), name);
  if (it != pose_classes.end()) return static_cast<std::size_t>(it - pose_classes.begin());
  pose_classes.push_back(name);
  return pose_classes.size() - 1;
}

void PatchLibrary::validate(const std::string& what) const {
  if (types.empty()) throw InputError(what + ": no patch types");
  std::set<std::string> names;
  for (std::size_t k = 0; k < types.size(); ++k) {
    const PatchType& type = types[k];
    const std::string where = what + ": patch type " + std::to_string(k) + " '" + type.name + "'";
    if (type.name.empty()) throw InputError(what + ": patch type " + std::to_string(k) + " has no name");
    if (!names.insert(type.name).second) throw InputError(where + ": the name is used twice");
    if (!(type.preference > 0) || !std::isfinite(type.preference)) {
      throw InputError(where + ": preference " + std::to_string(type.preference) + ", expected a finite value > 0");
    }
    if (type.fragments.empty()) throw InputError(where + ": no fragments");
    if (type.character_count() == 0) throw InputError(where + ": no character fragment (only props)");
    for (std::size_t f = 0; f < type.fragments.size(); ++f) {
      const Fragment& fr = type.fragments[f];
      const std::string fw = where + " fragment " + std::to_string(f);
      const std::size_t n = fr.times.size();
      if (n < 2) throw InputError(fw + ": " + std::to_string(n) + " samples, expected at least 2");
      if (fr.positions.size() != n || fr.headings.size() != n) {
        throw InputError(fw + ": " + std::to_string(fr.positions.size()) + " positions, " +
                         std::to_string(fr.headings.size()) + " headings and " + std::to_string(n) +
                         " times, expected equal counts");
      }
      if (!(fr.radius_m > 0) || !std::isfinite(fr.radius_m)) {
        throw InputError(fw + ": radius " + std::to_string(fr.radius_m) + ", expected a finite value > 0");
      }
      if (fr.entry_class >= pose_classes.size() || fr.exit_class >= pose_classes.size()) {
        throw InputError(fw + ": pose class index out of range (" + std::to_string(pose_classes.size()) + " classes)");
      }
      for (std::size_t s = 0; s < n; ++s) {
        if (!fr.positions[s].allFinite() || !std::isfinite(fr.headings[s]) || !std::isfinite(fr.times[s])) {
          throw InputError(fw + " sample " + std::to_string(s) + ": a value is not finite");
        }
        if (s > 0 && !(fr.times[s] > fr.times[s - 1])) {
          throw InputError(fw + " sample " + std::to_string(s) + ": time " + std::to_string(fr.times[s]) +
                           " does not follow " + std::to_string(fr.times[s - 1]) + " (times must increase strictly)");
        }
      }
    }
    for (std::size_t c = 0; c < type.constraints.size(); ++c) {
      const InterpersonalConstraint& ic = type.constraints[c];
      const auto bad = [&](std::size_t fragment, std::size_t sample) {
        return fragment >= type.fragments.size() || sample >= type.fragments[fragment].sample_count();
      };
      if (bad(ic.fragment_a, ic.sample_a) || bad(ic.fragment_b, ic.sample_b) || ic.fragment_a == ic.fragment_b) {
        throw InputError(where + " constraint " + std::to_string(c) +
                         ": names a missing fragment or sample, or ties a fragment to itself");
      }
    }
  }
}

void normalise_frames(PatchLibrary& library) {
  for (PatchType& type : library.types) {
    Eigen::Vector2d centroid(0, 0);
    std::size_t n = 0;
    Eigen::Vector2d travel(0, 0);
    Eigen::Vector2d facing(0, 0);
    for (const Fragment& f : type.fragments) {
      for (const Eigen::Vector2d& p : f.positions) centroid += p;
      n += f.positions.size();
      if (f.is_character() && !f.positions.empty()) {
        travel += f.positions.back() - f.positions.front();
        facing += Eigen::Vector2d(std::cos(f.headings.front()), std::sin(f.headings.front()));
      }
    }
    if (n == 0) continue;
    centroid /= static_cast<double>(n);
    const Eigen::Vector2d axis = travel.norm() > 1e-6 ? travel : facing;
    const double angle = axis.norm() > 1e-9 ? std::atan2(axis.y(), axis.x()) : 0.0;
    const double mid = 0.5 * (type.start_time() + type.end_time());
    for (Fragment& f : type.fragments) {
      for (Eigen::Vector2d& p : f.positions) p = rotate(p - centroid, -angle);
      for (double& h : f.headings) h = wrap_angle(h - angle);
      for (double& t : f.times) t -= mid;
    }
  }
}

}  // namespace throng::tiling
