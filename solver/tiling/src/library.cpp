// The built-in patch library (library.h). Every character path is drawn by a "turtle": a pose (position,
// heading) and a list of legs, each with a duration, a speed at its start and end (linear in between) and a turn
// (the heading changes linearly over the leg). A leg at speed 0 turns on the spot. The path is integrated
// finely and sampled at the library's rate; headings are the turtle's. Two-character and group patches are made
// of several turtles and tied by interpersonal constraints where the characters interact.
#include <throng/tiling/library.h>

#include <throng/core/errors.h>

#include "geometry.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <sstream>

namespace throng::tiling {
namespace {

constexpr double pi = std::numbers::pi;
constexpr double deg = pi / 180.0;

struct Leg {
  double duration_s;
  double speed0;
  double speed1;
  double turn_rad = 0.0;
};

// A character fragment drawn by the turtle from `position`, `heading` along `legs`, sampled at `rate` Hz
// (the last sample exactly at the end of the last leg; the sample count rounds the total duration).
Fragment draw(Eigen::Vector2d position, double heading, const std::vector<Leg>& legs, double rate, double radius,
              std::size_t entry_class, std::size_t exit_class) {
  double total = 0;
  for (const Leg& l : legs) total += l.duration_s;
  const auto intervals = static_cast<std::size_t>(std::max(1.0, std::round(total * rate)));
  const double dt = total / static_cast<double>(intervals);
  constexpr int substeps = 20;
  Fragment f;
  f.radius_m = radius;
  f.entry_class = entry_class;
  f.exit_class = exit_class;
  f.positions.push_back(position);
  f.headings.push_back(wrap_angle(heading));
  f.times.push_back(0.0);
  // Leg starts (time, heading); speed and heading at time t.
  std::vector<double> starts{0.0}, start_headings{heading};
  for (const Leg& l : legs) {
    starts.push_back(starts.back() + l.duration_s);
    start_headings.push_back(start_headings.back() + l.turn_rad);
  }
  const auto state = [&](double t) {
    std::size_t k = 0;
    while (k + 1 < legs.size() && t > starts[k + 1]) ++k;
    const Leg& l = legs[k];
    const double u = std::clamp((t - starts[k]) / l.duration_s, 0.0, 1.0);
    return std::pair<double, double>(l.speed0 + u * (l.speed1 - l.speed0), start_headings[k] + u * l.turn_rad);
  };
  for (std::size_t s = 1; s <= intervals; ++s) {
    for (int k = 0; k < substeps; ++k) {
      const auto [speed, h] = state((static_cast<double>(s) - 1 + (k + 0.5) / substeps) * dt);
      position += speed * dt / substeps * Eigen::Vector2d(std::cos(h), std::sin(h));
    }
    const double t = static_cast<double>(s) * dt;
    f.positions.push_back(position);
    f.headings.push_back(wrap_angle(state(t).second));
    f.times.push_back(t);
  }
  return f;
}

// The same fragment turned by `angle` about the origin (a second character facing the first).
Fragment turned(Fragment f, double angle) {
  for (Eigen::Vector2d& p : f.positions) p = rotate(p, angle);
  for (double& h : f.headings) h = wrap_angle(h + angle);
  return f;
}

// A prop standing still at `position` over [t0, t1] (samples every 1 / rate).
Fragment still_prop(const Eigen::Vector2d& position, double t0, double t1, double rate, double radius) {
  Fragment f;
  f.kind = FragmentKind::prop;
  f.radius_m = radius;
  const auto n = static_cast<std::size_t>(std::max(1.0, std::round((t1 - t0) * rate)));
  for (std::size_t s = 0; s <= n; ++s) {
    f.positions.push_back(position);
    f.headings.push_back(0.0);
    f.times.push_back(t0 + (t1 - t0) * static_cast<double>(s) / static_cast<double>(n));
  }
  return f;
}

// Sample index of fragment `f` nearest to time `t`.
std::size_t at_time(const Fragment& f, double t) {
  std::size_t best = 0;
  for (std::size_t s = 1; s < f.times.size(); ++s) {
    if (std::abs(f.times[s] - t) < std::abs(f.times[best] - t)) best = s;
  }
  return best;
}

// Ties fragments a and b at the samples nearest to each time in `times`.
void tie(PatchType& type, std::size_t a, std::size_t b, std::initializer_list<double> times) {
  for (double t : times) {
    type.constraints.push_back({a, at_time(type.fragments[a], t), b, at_time(type.fragments[b], t)});
  }
}

struct Builder {
  const BuiltinOptions& o;
  PatchLibrary& lib;
  std::size_t standing, walking, carrying, sitting;

  [[nodiscard]] double v() const { return o.walk_speed_mps; }
  [[nodiscard]] double D() const { return o.walk_duration_s; }
  [[nodiscard]] double r() const { return o.sample_rate_hz; }

  PatchType single(const std::string& name, const std::string& label, Fragment f) const {
    PatchType t;
    t.name = name;
    t.label = label;
    t.fragments.push_back(std::move(f));
    return t;
  }
  PatchType walk(const std::string& name, double speed, const std::string& label) const {
    return single(name, label, draw({0, 0}, 0, {{D(), speed, speed}}, r(), o.radius_m, walking, walking));
  }
  PatchType turn(const std::string& name, double angle) const {
    return single(name, "", draw({0, 0}, 0, {{D(), v(), v(), angle}}, r(), o.radius_m, walking, walking));
  }

  // A character carrying a box (or sitting on one) is this much wider, and carries the prop "box".
  [[nodiscard]] double carry_radius() const { return o.radius_m + 0.1; }

  PatchType make(const std::string& name) const {
    PatchType t = draw_type(name);
    for (Fragment& f : t.fragments) {
      if (f.is_character() && f.radius_m == carry_radius()) f.prop = "box";
    }
    return t;
  }

  PatchType draw_type(const std::string& name) const {
    const double R = o.radius_m;
    if (name == "walk") return walk(name, v(), "");
    if (name == "walk_slow") return walk(name, 0.7 * v(), "slow");
    if (name == "walk_fast") return walk(name, 1.4 * v(), "fast");
    if (name == "turn_left") return turn(name, 45 * deg);
    if (name == "turn_right") return turn(name, -45 * deg);
    if (name == "turn_left_90") return turn(name, 90 * deg);
    if (name == "turn_right_90") return turn(name, -90 * deg);
    if (name == "stop") {
      return single(name, "", draw({0, 0}, 0, {{0.75 * D(), v(), 0}, {0.25 * D(), 0, 0}}, r(), R, walking, standing));
    }
    if (name == "start") {
      return single(name, "", draw({0, 0}, 0, {{0.25 * D(), 0, 0}, {0.75 * D(), 0, v()}}, r(), R, standing, walking));
    }
    if (name == "wait") return single(name, "", draw({0, 0}, 0, {{o.wait_duration_s, 0, 0}}, r(), R, standing, standing));
    if (name == "turn_in_place") {
      return single(name, "", draw({0, 0}, 0, {{o.wait_duration_s, 0, 0, 90 * deg}}, r(), R, standing, standing));
    }
    if (name == "meet") {
      // Approach (decelerating), stand face to face 1 m apart and talk, walk off to the sides.
      const double brake = 1.5, talk = 1.0, leave = 1.5;
      const Fragment a = draw({-0.5 - 0.5 * v() * brake, 0}, 0,
                              {{brake, v(), 0}, {talk, 0, 0}, {leave, 0, v(), 90 * deg}, {0.5, v(), v()}}, r(), R, walking, walking);
      PatchType t;
      t.name = name;
      t.label = "friendly";
      t.fragments = {a, turned(a, pi)};
      tie(t, 0, 1, {brake, brake + talk});
      return t;
    }
    if (name == "pass") {
      // Walk past each other, each sidestepping to 0.6 m apart at the crossing (at the default 1.3 m/s and 2 s:
      // ±27° legs of 0.5 s step each 0.30 m aside; the centres pass 0.61 m apart, clear of the radii).
      PatchType t;
      t.name = name;
      t.fragments.push_back(draw({-0.5 * v() * D(), 0}, 0,
                                 {{0.25 * D(), v(), v(), 27 * deg}, {0.25 * D(), v(), v(), -27 * deg},
                                  {0.25 * D(), v(), v(), -27 * deg}, {0.25 * D(), v(), v(), 27 * deg}},
                                 r(), R, walking, walking));
      t.fragments.push_back(turned(t.fragments[0], pi));
      tie(t, 0, 1, {0.5 * D()});
      return t;
    }
    if (name == "handshake") {
      // Approach side by side offset, stand 0.9 m apart shaking hands, walk on past each other 0.7 m apart.
      const double brake = 1.5, shake = 1.5, go = 1.5;
      const double reach = 0.5 * v() * brake;
      const Fragment a = draw({-0.3 - reach, 0.35}, 0, {{brake, v(), 0}, {shake, 0, 0}, {go, 0, v()}}, r(), R, walking, walking);
      PatchType t;
      t.name = name;
      t.label = "friendly";
      t.fragments = {a, turned(a, pi)};
      tie(t, 0, 1, {brake, brake + 0.5 * shake, brake + shake});
      return t;
    }
    if (name == "bump") {
      // Shoulders bump at the crossing (the capsules brush: centres 2R + 2 cm apart); both are deflected and
      // slowed, then walk on.
      PatchType t;
      t.name = name;
      t.label = "hostile";
      t.fragments.push_back(draw({-0.5 * v() * D(), R + 0.01}, 0,
                                 {{0.5 * D(), v(), v()}, {0.2 * D(), v(), 0.6 * v(), 25 * deg}, {0.3 * D(), 0.6 * v(), v()}},
                                 r(), R, walking, walking));
      t.fragments.push_back(turned(t.fragments[0], pi));
      tie(t, 0, 1, {0.5 * D()});
      return t;
    }
    if (name == "bow_rows") {
      // Two rows of five walk in side by side, stop 1.2 m apart facing each other, bow, turn round and walk
      // back out the way they came.
      const double brake = 1.5, bow = 2.0, about = 0.8, leave = 1.5;
      PatchType t;
      t.name = name;
      t.label = "group";
      for (int i = 0; i < 5; ++i) {
        t.fragments.push_back(draw({-2.0 + i, 0.6 + 0.5 * v() * brake}, -0.5 * pi,
                                   {{brake, v(), 0}, {bow, 0, 0}, {about, 0, 0, pi}, {leave, 0, v()}}, r(), R, walking,
                                   walking));
      }
      for (int i = 0; i < 5; ++i) t.fragments.push_back(turned(t.fragments[static_cast<std::size_t>(i)], pi));
      for (std::size_t i = 0; i < 5; ++i) {
        tie(t, i, 9 - i, {brake, brake + bow});  // facing partners (the turned row runs the other way)
        if (i + 1 < 5) tie(t, i, i + 1, {brake + 0.5 * bow});
      }
      return t;
    }
    // The box patches: a character carrying a box is a wider capsule; a box standing on the ground is a prop.
    const double carry_r = carry_radius();
    if (name == "box_pickup") {
      PatchType t;
      t.name = name;
      t.label = "boxes";
      t.fragments.push_back(draw({0, 0}, 0, {{0.8, 0, 0}, {0.4, 0, 0, 180 * deg}, {0.8, 0, 0.7 * v()}}, r(), carry_r,
                                 standing, carrying));
      t.fragments.push_back(still_prop({0.7, 0}, 0, 1.0, r(), 0.3));  // the stack, until the box is taken
      return t;
    }
    if (name == "box_carry") {
      return single(name, "boxes", draw({0, 0}, 0, {{D(), 0.7 * v(), 0.7 * v()}}, r(), carry_r, carrying, carrying));
    }
    if (name == "box_pass") {
      // The carrier stops, hands the box to the walker facing it, who turns round and carries it away; the
      // carrier walks on past.
      const double brake = 1.2, hand = 0.8, go = 1.5;
      PatchType t;
      t.name = name;
      t.label = "boxes";
      t.fragments.push_back(draw({-0.45 - 0.5 * 0.7 * v() * brake, 0.25}, 0,
                                 {{brake, 0.7 * v(), 0}, {hand, 0, 0}, {go, 0, v(), 60 * deg}, {0.5, v(), v()}}, r(), carry_r, carrying,
                                 walking));
      t.fragments.push_back(turned(draw({-0.45 - 0.5 * v() * brake, 0.25}, 0,
                                        {{brake, v(), 0}, {hand, 0, 0, 180 * deg}, {go, 0, 0.7 * v()}}, r(), carry_r,
                                        walking, carrying),
                                   pi));
      tie(t, 0, 1, {brake, brake + hand});
      return t;
    }
    if (name == "box_sit") {
      return single(name, "boxes",
                    draw({0, 0}, 0, {{1.0, 0.7 * v(), 0}, {1.0, 0, 0, 180 * deg}}, r(), carry_r, carrying, sitting));
    }
    if (name == "sit") return single(name, "boxes", draw({0, 0}, 0, {{o.wait_duration_s, 0, 0}}, r(), carry_r, sitting, sitting));
    if (name == "box_stand") {
      PatchType t = single(name, "boxes", draw({0, 0}, 0, {{0.6, 0, 0}, {1.4, 0, 0.6 * v()}}, r(), R, sitting, standing));
      t.fragments[0].exit_class = walking;
      t.fragments.push_back(still_prop({-0.55, 0}, 1.0, 2.0, r(), 0.25));  // the box left behind, once stood up
      return t;
    }
    std::ostringstream m;
    m << "no built-in patch '" << name << "' (known:";
    for (const std::string& n : builtin_patch_names()) m << ' ' << n;
    m << ")";
    throw ConfigError(m.str());
  }
};

}  // namespace

std::vector<std::string> builtin_patch_names() {
  return {"walk",      "walk_slow", "walk_fast", "turn_left",  "turn_right", "turn_left_90", "turn_right_90",
          "stop",      "start",     "wait",      "turn_in_place", "meet",    "pass",         "handshake",
          "bump",      "bow_rows",  "box_pickup", "box_carry", "box_pass",   "box_sit",      "sit",
          "box_stand"};
}

std::vector<std::string> builtin_patch_group(const std::string& group) {
  static const std::map<std::string, std::vector<std::string>> groups = {
      {"locomotion",
       {"walk", "walk_slow", "walk_fast", "turn_left", "turn_right", "turn_left_90", "turn_right_90", "stop", "start",
        "wait", "turn_in_place"}},
      {"interaction", {"meet", "pass", "handshake", "bump"}},
      {"group", {"bow_rows"}},
      {"boxes", {"box_pickup", "box_carry", "box_pass", "box_sit", "sit", "box_stand"}},
  };
  if (group == "all") return builtin_patch_names();
  const auto it = groups.find(group);
  if (it == groups.end()) {
    throw ConfigError("no built-in patch group '" + group + "' (known: locomotion, interaction, group, boxes, all)");
  }
  return it->second;
}

PatchLibrary builtin_library(const std::vector<std::string>& names, const BuiltinOptions& options) {
  const auto positive = [](double v, const char* what) {
    if (!(v > 0) || !std::isfinite(v)) {
      throw ConfigError(std::string("built-in library: ") + what + " = " + std::to_string(v) + ", expected > 0");
    }
  };
  positive(options.sample_rate_hz, "sample_rate");
  positive(options.radius_m, "radius");
  positive(options.walk_speed_mps, "walk_speed");
  positive(options.walk_duration_s, "walk_duration");
  positive(options.wait_duration_s, "wait_duration");
  positive(options.preference_per_character, "preference_per_character");
  if (names.empty()) throw ConfigError("built-in library: no patch names");
  PatchLibrary lib;
  Builder b{options, lib, lib.pose_class("standing"), lib.pose_class("walking"), 0, 0};
  bool boxes = false;
  for (const std::string& n : names) boxes = boxes || n.rfind("box", 0) == 0 || n == "sit";
  if (boxes) {
    b.carrying = lib.pose_class("carrying");
    b.sitting = lib.pose_class("sitting");
  }
  for (const std::string& n : names) {
    if (std::any_of(lib.types.begin(), lib.types.end(), [&](const PatchType& t) { return t.name == n; })) continue;
    PatchType t = b.make(n);
    t.preference = options.preference_per_character * static_cast<double>(t.character_count());
    lib.types.push_back(std::move(t));
  }
  normalise_frames(lib);
  lib.validate("built-in library");
  return lib;
}

}  // namespace throng::tiling
