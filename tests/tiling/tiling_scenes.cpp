#include "tiling_scenes.h"

#include <cmath>

namespace throng::tiling::test {

Instance placed(const PatchLibrary& library, std::size_t type, const Eigen::Vector2d& at, double angle, double time) {
  Instance inst;
  inst.type = type;
  inst.transform.translation = at;
  inst.transform.angle = angle;
  inst.transform.time_shift = time;
  const Fragment& f0 = library.types[type].fragments[0];
  inst.paths.resize(library.types[type].fragments.size());
  for (std::size_t f = 0; f < inst.paths.size(); ++f) {
    const Fragment& fr = library.types[type].fragments[f];
    for (std::size_t s = 0; s < fr.sample_count(); ++s) {
      inst.paths[f].positions.push_back(inst.transform.apply(fr.positions[s]));
      inst.paths[f].headings.push_back(std::remainder(fr.headings[s] + angle, 2 * std::numbers::pi));
      inst.paths[f].times.push_back(fr.times[s] + time);
    }
  }
  (void)f0;
  return inst;
}

Tiling walk_chain(const PatchLibrary& library, int n, double x0, double y, double t0) {
  const Fragment& f = library.types[0].fragments[0];
  const double length = (f.positions.back() - f.positions.front()).norm();
  const double duration = f.times.back() - f.times.front();
  Tiling t;
  for (int k = 0; k < n; ++k) {
    t.instances.push_back(placed(library, 0, {x0 + (k + 0.5) * length, y}, 0.0, t0 + (k + 0.5) * duration));
    if (k > 0) t.connections.push_back({{static_cast<std::uint32_t>(k - 1), 0}, {static_cast<std::uint32_t>(k), 0}, {0, 0, 0}});
  }
  return t;
}

void append(Tiling& into, const Tiling& more) {
  const auto base = static_cast<std::uint32_t>(into.instances.size());
  into.instances.insert(into.instances.end(), more.instances.begin(), more.instances.end());
  for (Connection c : more.connections) {
    c.from.instance += base;
    c.to.instance += base;
    into.connections.push_back(c);
  }
}

Environment box(double w, double h, double d, std::array<bool, 3> periodic) {
  Environment e;
  Region r;
  r.min = {0, 0};
  r.max = {w, h};
  r.t0 = 0;
  r.t1 = d;
  r.periodic = periodic;
  e.scene.region = r;
  return e;
}

Options quick_options(std::uint64_t seed, std::size_t chains) {
  Options o;
  o.seed = seed;
  o.chains = chains;
  o.annealing.max_failures = 300;
  o.search.max_steps = 20000;
  return o;
}

}  // namespace throng::tiling::test
