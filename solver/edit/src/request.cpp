#include "request.h"

#include <throng/core/errors.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cmath>
#include <sstream>

namespace throng::edit {
namespace {

using Index = Eigen::Index;

std::string clip_range(const Clip& clip) {
  return "[" + std::to_string(clip.first_frame) + ", " + std::to_string(clip.last_frame) + "]";
}

std::string point(const Eigen::Vector2d& p) {
  std::ostringstream out;
  out << "(" << p.x() << ", " << p.y() << ")";
  return out.str();
}

// The graph agent with `id`, or a ConfigError saying why it is not in the clip.
std::size_t agent(const Clip& clip, const std::vector<std::int64_t>& crowd_ids, std::int64_t id, const std::string& where) {
  const long j = clip.agent_of_id(id);
  if (j >= 0) return static_cast<std::size_t>(j);
  if (std::find(crowd_ids.begin(), crowd_ids.end(), id) == crowd_ids.end()) {
    throw ConfigError(where + ": no agent with id " + std::to_string(id) + " in the crowd");
  }
  const bool left_out = std::find(clip.left_out.begin(), clip.left_out.end(), id) != clip.left_out.end();
  throw ConfigError(where + ": agent " + std::to_string(id) +
                    (left_out ? " is absent at some frames of the clip " + clip_range(clip) +
                                    " and was left out: only agents present over the whole clip can be edited"
                              : " is not in the clip " + clip_range(clip) +
                                    " (not among clip.agents, or absent from all of it)"));
}

// The input frame a request's frame names (negative: back from the clip's last frame), not checked.
long named_frame(const Clip& clip, Frame frame) { return frame < 0 ? static_cast<long>(clip.last_frame) + 1 + frame : frame; }

bool in_clip(const Clip& clip, long frame) {
  return frame >= static_cast<long>(clip.first_frame) && frame <= static_cast<long>(clip.last_frame);
}

// The input frame a request's frame names, checked to be in the clip.
std::size_t absolute_frame(const Clip& clip, Frame frame, const std::string& where) {
  const long f = named_frame(clip, frame);
  if (!in_clip(clip, f)) {
    throw ConfigError(where + " " + std::to_string(frame) + (frame < 0 ? " (" + std::to_string(f) + ")" : std::string()) +
                      " is outside the clip " + clip_range(clip));
  }
  return static_cast<std::size_t>(f);
}

// The frame range [first, last] (negative: from the end) clamped to the clip; a ConfigError when it misses it.
std::pair<std::size_t, std::size_t> clamp_range(const Clip& clip, Frame first, Frame last, const std::string& where) {
  const long end = static_cast<long>(clip.last_frame);
  const long a = first < 0 ? end + 1 + first : first;
  const long b = last < 0 ? end + 1 + last : last;
  if (a > b) {
    throw ConfigError(where + ": first_frame " + std::to_string(first) + " is after last_frame " + std::to_string(last) +
                      " (in the clip " + clip_range(clip) + ")");
  }
  if (a > end || b < static_cast<long>(clip.first_frame)) {
    throw ConfigError(where + ": frames [" + std::to_string(first) + ", " + std::to_string(last) + "] are outside the clip " +
                      clip_range(clip));
  }
  return {static_cast<std::size_t>(std::max(a, static_cast<long>(clip.first_frame))), static_cast<std::size_t>(std::min(b, end))};
}

// Samples whose source frame lies in [first, last] (already clamped); a ConfigError when there is none.
std::vector<std::size_t> samples_in(const Clip& clip, std::size_t first, std::size_t last, const std::string& where) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < clip.sample_count(); ++i) {
    if (clip.frames[i] >= first && clip.frames[i] <= last) out.push_back(i);
  }
  if (out.empty()) {
    throw ConfigError(where + ": frames [" + std::to_string(first) + ", " + std::to_string(last) + "] hold no sample");
  }
  return out;
}

std::size_t sample_at(const Clip& clip, Frame given, const std::string& where) {
  const std::size_t frame = absolute_frame(clip, given, where);
  const long s = clip.sample_of_frame(frame);
  if (s < 0) {
    throw ConfigError(where + " " + std::to_string(given) +
                      " is not a sample of this edit's clip (an editor samples the frames of the request it was "
                      "built with; build a new one)");
  }
  return static_cast<std::size_t>(s);
}

// The two frames a velocity constraint differences: (f, f + 1), or (f − 1, f) at the clip's last frame.
std::pair<std::size_t, std::size_t> velocity_frames(const Clip& clip, std::size_t frame) {
  return frame < clip.last_frame ? std::pair{frame, frame + 1} : std::pair{frame - 1, frame};
}

// The three frames an acceleration constraint fits its parabola to: (f − 1, f, f + 1), or the three nearest
// inside the clip at its ends (f, f + 1, f + 2 at the first frame; f − 2, f − 1, f at the last).
std::array<std::size_t, 3> acceleration_frames(const Clip& clip, std::size_t frame, const std::string& where) {
  if (clip.last_frame < clip.first_frame + 2) {
    throw ConfigError(where + ": an acceleration needs three frames, and the clip " + clip_range(clip) + " has " +
                      std::to_string(clip.last_frame - clip.first_frame + 1));
  }
  const std::size_t middle = std::clamp(frame, clip.first_frame + 1, clip.last_frame - 1);
  return {middle - 1, middle, middle + 1};
}

// A Sum's agents (graph indices) and weights (1/n by default), checked: agents given and distinct, one finite
// weight per agent, not all zero, a finite value.
std::pair<std::vector<std::size_t>, std::vector<double>> sum_terms(const Clip& clip, const std::vector<std::int64_t>& crowd_ids,
                                                                   const Sum& c, const std::string& where) {
  if (c.agents.empty()) throw ConfigError(where + ".agents: no agent given: a sum needs at least one");
  std::vector<std::size_t> agents;
  for (std::size_t i = 0; i < c.agents.size(); ++i) {
    const std::string entry = where + ".agents[" + std::to_string(i) + "]";
    const std::size_t a = agent(clip, crowd_ids, c.agents[i], entry);
    if (std::find(agents.begin(), agents.end(), a) != agents.end()) {
      throw ConfigError(entry + ": agent " + std::to_string(c.agents[i]) + " is named twice");
    }
    agents.push_back(a);
  }
  std::vector<double> weights = c.weights;
  if (weights.empty()) weights.assign(agents.size(), 1.0 / static_cast<double>(agents.size()));
  if (weights.size() != agents.size()) {
    throw ConfigError(where + ".weights: " + std::to_string(weights.size()) + " weights for " + std::to_string(agents.size()) +
                      " agents (give one per agent, or none for 1/n each)");
  }
  for (std::size_t i = 0; i < weights.size(); ++i) {
    if (!std::isfinite(weights[i])) throw ConfigError(where + ".weights[" + std::to_string(i) + "] is not finite");
  }
  if (std::all_of(weights.begin(), weights.end(), [](double w) { return w == 0.0; })) {
    throw ConfigError(where + ".weights: every weight is 0, so the row says nothing");
  }
  if (c.value && !c.value->allFinite()) throw ConfigError(where + ".value " + point(*c.value) + " is not finite");
  return {agents, weights};
}

// A Row's terms as (graph agent, input frame, axis, coefficient), checked: terms given, agents in the clip,
// frames in it, axis 0 or 1, finite coefficients not all zero, no (agent, frame, axis) twice, a finite value.
struct ResolvedTerm {
  std::size_t agent = 0, frame = 0;
  int axis = 0;
  double coefficient = 0;
};

std::vector<ResolvedTerm> row_terms(const Clip& clip, const std::vector<std::int64_t>& crowd_ids, const Row& c,
                                    const std::string& where) {
  if (c.terms.empty()) throw ConfigError(where + ".terms: no term given: a row needs at least one");
  if (!std::isfinite(c.value)) throw ConfigError(where + ".value is not finite");
  std::vector<ResolvedTerm> out;
  for (std::size_t i = 0; i < c.terms.size(); ++i) {
    const RowTerm& t = c.terms[i];
    const std::string entry = where + ".terms[" + std::to_string(i) + "]";
    ResolvedTerm r;
    r.agent = agent(clip, crowd_ids, t.agent, entry + ".agent");
    r.frame = absolute_frame(clip, t.frame, entry + ".frame");
    if (t.axis != 0 && t.axis != 1) throw ConfigError(entry + ".axis " + std::to_string(t.axis) + ": expected x (0) or y (1)");
    r.axis = t.axis;
    if (!std::isfinite(t.coefficient)) throw ConfigError(entry + ".coefficient is not finite");
    r.coefficient = t.coefficient;
    for (std::size_t j = 0; j < out.size(); ++j) {
      if (out[j].agent == r.agent && out[j].frame == r.frame && out[j].axis == r.axis) {
        throw ConfigError(entry + ": the same coordinate as " + where + ".terms[" + std::to_string(j) + "] (agent " +
                          std::to_string(t.agent) + ", frame " + std::to_string(r.frame) + ", " + (r.axis == 0 ? "x" : "y") +
                          "): add their coefficients into one term");
      }
    }
    out.push_back(r);
  }
  if (std::all_of(out.begin(), out.end(), [](const ResolvedTerm& t) { return t.coefficient == 0.0; })) {
    throw ConfigError(where + ".terms: every coefficient is 0, so the row says nothing");
  }
  return out;
}

std::vector<std::size_t> selected_agents(const Clip& clip, const std::vector<std::int64_t>& crowd_ids, const std::vector<std::int64_t>& ids,
                                         const std::string& where) {
  std::vector<std::size_t> out;
  if (ids.empty()) {
    for (std::size_t j = 0; j < clip.agent_count(); ++j) out.push_back(j);
  } else {
    for (std::int64_t id : ids) out.push_back(agent(clip, crowd_ids, id, where + ".agents"));
  }
  return out;
}

Eigen::Vector2d original(const Clip& clip, std::size_t sample, std::size_t agent_index) {
  return clip.positions.row(clip.vertex(sample, agent_index)).transpose();
}

// Whether a drag's offset, rotation and pivot are finite.
bool finite_motion(const Drag& d) { return d.offset.allFinite() && std::isfinite(d.rotation) && (!d.pivot || d.pivot->allFinite()); }

// A drag's rigid motion p ↦ pivot + R(θ) (p − pivot) + offset (exactly p + offset without rotation) and its
// coordinates (cos θ, sin θ, t), t = pivot − R(θ) pivot + offset: one definition for resolve() and redrag(), so
// both give the same bits. `centroid` is the default pivot.
struct DragMotion {
  DragMotion(const Drag& d, const Eigen::Vector2d& centroid)
      : drag(d),
        pivot(d.pivot.value_or(centroid)),
        turn(d.rotation),
        t(d.rotation == 0.0 ? d.offset : Eigen::Vector2d(pivot - turn * pivot + d.offset)) {}

  [[nodiscard]] std::array<double, 4> coordinates() const {
    const bool still = drag.rotation == 0.0;
    return {still ? 1.0 : std::cos(drag.rotation), still ? 0.0 : std::sin(drag.rotation), t.x(), t.y()};
  }
  [[nodiscard]] Eigen::Vector2d target(const Eigen::Vector2d& p) const {
    return drag.rotation == 0.0 ? Eigen::Vector2d(p + drag.offset) : Eigen::Vector2d(pivot + turn * (p - pivot) + drag.offset);
  }

  const Drag& drag;
  Eigen::Vector2d pivot;
  Eigen::Rotation2Dd turn;
  Eigen::Vector2d t;
};

// The same bits (a zero's sign and a NaN's payload count: redrag() promises resolve()'s bits).
bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }
bool same_bits(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return same_bits(a.x(), b.x()) && same_bits(a.y(), b.y()); }
bool same_bits(const std::optional<Eigen::Vector2d>& a, const std::optional<Eigen::Vector2d>& b) {
  return a.has_value() == b.has_value() && (!a || same_bits(*a, *b));
}
bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](double x, double y) { return same_bits(x, y); });
}
bool same_bits(const Pin& a, const Pin& b) { return a.agent == b.agent && a.frame == b.frame && same_bits(a.position, b.position); }
bool same_bits(const RelativePosition& a, const RelativePosition& b) {
  return a.agent == b.agent && a.other == b.other && a.first_frame == b.first_frame && a.last_frame == b.last_frame &&
         same_bits(a.offset, b.offset);
}
bool same_bits(const Velocity& a, const Velocity& b) { return a.agent == b.agent && a.frame == b.frame && same_bits(a.velocity, b.velocity); }
bool same_bits(const OnLine& a, const OnLine& b) {
  return a.agent == b.agent && a.first_frame == b.first_frame && a.last_frame == b.last_frame && same_bits(a.point, b.point) &&
         same_bits(a.direction, b.direction);
}
bool same_bits(const Acceleration& a, const Acceleration& b) {
  return a.agent == b.agent && a.frame == b.frame && same_bits(a.acceleration, b.acceleration);
}
bool same_bits(const Sum& a, const Sum& b) {
  return a.agents == b.agents && same_bits(a.weights, b.weights) && a.first_frame == b.first_frame && a.last_frame == b.last_frame &&
         same_bits(a.value, b.value);
}
bool same_bits(const RowTerm& a, const RowTerm& b) {
  return a.agent == b.agent && a.frame == b.frame && a.axis == b.axis && same_bits(a.coefficient, b.coefficient);
}
bool same_bits(const Row& a, const Row& b) {
  return a.terms.size() == b.terms.size() && same_bits(a.value, b.value) &&
         std::equal(a.terms.begin(), a.terms.end(), b.terms.begin(), [](const RowTerm& x, const RowTerm& y) { return same_bits(x, y); });
}
bool same_bits(const Constraint& a, const Constraint& b) {
  return a.index() == b.index() &&
         std::visit([&](const auto& x) { return same_bits(x, std::get<std::decay_t<decltype(x)>>(b)); }, a);
}
// Every entry the same, value for value and bit for bit.
template <typename T>
bool same_entries(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](const T& x, const T& y) { return same_bits(x, y); });
}

}  // namespace

std::vector<Eigen::Index> ResolvedRequest::pinned_unknowns() const {
  std::vector<Index> out;
  out.reserve(2 * handle_vertices.size());
  for (Index v : handle_vertices) {
    out.push_back(2 * v);
    out.push_back(2 * v + 1);
  }
  return out;
}

std::string describe(const Request& request, std::size_t k) {
  std::ostringstream out;
  out << "constraints[" << k << "] (";
  std::visit(
      [&](const auto& c) {
        using T = std::decay_t<decltype(c)>;
        if constexpr (std::is_same_v<T, RelativePosition>) {
          out << "position of agent " << c.agent << " relative to agent " << c.other;
        } else if constexpr (std::is_same_v<T, Velocity>) {
          out << "velocity of agent " << c.agent << " at frame " << c.frame;
        } else if constexpr (std::is_same_v<T, OnLine>) {
          out << "agent " << c.agent << " on a line";
        } else if constexpr (std::is_same_v<T, Acceleration>) {
          out << "acceleration of agent " << c.agent << " at frame " << c.frame;
        } else if constexpr (std::is_same_v<T, Sum>) {
          out << "sum over agent" << (c.agents.size() == 1 ? " " : "s ");
          for (std::size_t i = 0; i < c.agents.size() && i < 6; ++i) out << (i > 0 ? ", " : "") << c.agents[i];
          if (c.agents.size() > 6) out << ", ... (" << c.agents.size() << " agents)";
        } else {
          out << "row of " << c.terms.size() << " term" << (c.terms.size() == 1 ? "" : "s");
          if (!c.terms.empty()) out << " from agent " << c.terms.front().agent << " at frame " << c.terms.front().frame;
        }
      },
      request.constraints[k]);
  out << ")";
  return out.str();
}

std::vector<std::size_t> required_frames(const Request& request, const Clip& clip, const std::vector<std::int64_t>& crowd_ids) {
  std::vector<std::size_t> frames;
  for (std::size_t k = 0; k < request.pins.size(); ++k) {
    const Pin& p = request.pins[k];
    const std::string where = "pins[" + std::to_string(k) + "]";
    (void)agent(clip, crowd_ids, p.agent, where + ".agent");
    frames.push_back(absolute_frame(clip, p.frame, where + ".frame"));
  }
  for (std::size_t k = 0; k < request.drags.size(); ++k) {
    const Drag& d = request.drags[k];
    const std::string where = "drags[" + std::to_string(k) + "]";
    (void)selected_agents(clip, crowd_ids, d.selection.agents, where);
    const auto [first, last] = clamp_range(clip, d.selection.first_frame, d.selection.last_frame, where);
    for (std::size_t f = first; f <= last; ++f) frames.push_back(f);
  }
  for (std::size_t k = 0; k < request.constraints.size(); ++k) {
    const std::string where = "constraints[" + std::to_string(k) + "]";
    std::visit(
        [&](const auto& c) {
          using T = std::decay_t<decltype(c)>;
          if constexpr (std::is_same_v<T, Sum>) {
            (void)sum_terms(clip, crowd_ids, c, where);
            const auto [first, last] = clamp_range(clip, c.first_frame, c.last_frame, where);
            for (std::size_t f = first; f <= last; ++f) frames.push_back(f);
          } else if constexpr (std::is_same_v<T, Row>) {
            for (const ResolvedTerm& t : row_terms(clip, crowd_ids, c, where)) frames.push_back(t.frame);
          } else if constexpr (std::is_same_v<T, Acceleration>) {
            (void)agent(clip, crowd_ids, c.agent, where + ".agent");
            if (!c.acceleration.allFinite()) throw ConfigError(where + ".acceleration " + point(c.acceleration) + " is not finite");
            for (std::size_t f : acceleration_frames(clip, absolute_frame(clip, c.frame, where + ".frame"), where)) frames.push_back(f);
          } else if constexpr (std::is_same_v<T, Velocity>) {
            (void)agent(clip, crowd_ids, c.agent, where + ".agent");
            const auto [f0, f1] = velocity_frames(clip, absolute_frame(clip, c.frame, where + ".frame"));
            frames.push_back(f0);
            frames.push_back(f1);
          } else {
            (void)agent(clip, crowd_ids, c.agent, where + ".agent");
            if constexpr (std::is_same_v<T, RelativePosition>) {
              (void)agent(clip, crowd_ids, c.other, where + ".other");
              if (c.other == c.agent) throw ConfigError(where + ": agent and other are both " + std::to_string(c.agent));
            } else {
              if (!(c.direction.norm() > 0) || !c.direction.allFinite()) {
                throw ConfigError(where + ".direction " + point(c.direction) + ": expected a non-zero finite vector");
              }
            }
            const auto [first, last] = clamp_range(clip, c.first_frame, c.last_frame, where);
            for (std::size_t f = first; f <= last; ++f) frames.push_back(f);
          }
        },
        request.constraints[k]);
  }
  return frames;
}

ResolvedRequest resolve(const Request& request, const Clip& clip, const std::vector<std::int64_t>& crowd_ids) {
  // Handles: vertex → target and who set it; disagreement is a contradiction. Each vertex is parametrised by
  // the handle that placed it first: `column` is that handle's first coordinate, `rigid` says whether it is a
  // drag (4 coordinates, original position p) or a pin (2 coordinates).
  struct Parametrisation {
    Index column = 0;
    bool rigid = false;
    Eigen::Vector2d p{0, 0};
  };
  // Every placement in request order (a flat list sorted once below: a request that holds the whole crowd's
  // first and last frames places 2 × agents handles on every drag, and a map per placement cost more than the
  // drag's own solve of a cached local region).
  struct Placement {
    Index v = 0;
    Eigen::Vector2d target{0, 0};
    std::size_t who = 0;    // index into `sources`
    std::size_t order = 0;  // its place in request order
    Parametrisation q;
    long drag = -1;  // k when drags[k] placed it
  };
  // Who placed a handle: pins[k] or drags[k], as text only in a message (a request that pins 20,000 vertices
  // would otherwise build 60,000 strings on every drag).
  struct Source {
    const char* list = "";
    std::size_t index = 0;
    [[nodiscard]] std::string text() const { return std::string(list) + "[" + std::to_string(index) + "]"; }
    [[nodiscard]] bool operator==(const Source& o) const { return list == o.list && index == o.index; }
  };
  std::vector<Placement> placements;
  std::vector<Source> sources;
  std::vector<double> coordinates;
  Parametrisation current;
  auto place = [&](std::size_t sample, std::size_t agent_index, const Eigen::Vector2d& target, const Source& who) {
    if (!target.allFinite()) throw ConfigError(who.text() + ": target position " + point(target) + " is not finite");
    if (sources.empty() || !(sources.back() == who)) sources.push_back(who);
    Parametrisation mine = current;
    mine.p = original(clip, sample, agent_index);
    placements.push_back({clip.vertex(sample, agent_index), target, sources.size() - 1, placements.size(), mine});
  };
  // Agent ids to clip columns: by bisection when the ids increase (a request that pins every agent would
  // otherwise scan the ids once per pin, 10^8 comparisons at 10,000 agents), else Clip::agent_of_id's scan.
  const bool ids_increase = std::is_sorted(clip.ids.begin(), clip.ids.end());
  auto column_of = [&](std::int64_t id) -> long {
    if (!ids_increase) return clip.agent_of_id(id);
    const auto it = std::lower_bound(clip.ids.begin(), clip.ids.end(), id);
    return it != clip.ids.end() && *it == id ? static_cast<long>(it - clip.ids.begin()) : -1;
  };
  for (std::size_t k = 0; k < request.pins.size(); ++k) {
    const Pin& p = request.pins[k];
    const Source who{"pins", k};
    // A known agent at a sample of the clip without any text; agent() and sample_at() say what is wrong otherwise.
    const long known = column_of(p.agent);
    const std::size_t j = known >= 0 ? static_cast<std::size_t>(known) : agent(clip, crowd_ids, p.agent, who.text() + ".agent");
    const long frame = named_frame(clip, p.frame);
    const long sample = in_clip(clip, frame) ? clip.sample_of_frame(static_cast<std::size_t>(frame)) : -1;
    const std::size_t s = sample >= 0 ? static_cast<std::size_t>(sample) : sample_at(clip, p.frame, who.text() + ".frame");
    const Eigen::Vector2d at = p.position.value_or(original(clip, s, j));
    current = {static_cast<Index>(coordinates.size()), false, {0, 0}};
    coordinates.insert(coordinates.end(), {at.x(), at.y()});
    place(s, j, at, who);
  }
  std::vector<ResolvedRequest::DragPlacement> drag_placements(request.drags.size());
  for (std::size_t k = 0; k < request.drags.size(); ++k) {
    const Drag& d = request.drags[k];
    const std::string where = "drags[" + std::to_string(k) + "]";
    if (!finite_motion(d)) throw ConfigError(where + ": offset, rotation and pivot must be finite");
    const auto agents = selected_agents(clip, crowd_ids, d.selection.agents, where);
    const auto [first, last] = clamp_range(clip, d.selection.first_frame, d.selection.last_frame, where);
    const auto samples = samples_in(clip, first, last, where);
    Eigen::Vector2d& centroid = drag_placements[k].centroid;
    for (std::size_t s : samples)
      for (std::size_t j : agents) centroid += original(clip, s, j);
    centroid /= static_cast<double>(samples.size() * agents.size());
    const DragMotion motion(d, centroid);
    current = {static_cast<Index>(coordinates.size()), true, {0, 0}};
    drag_placements[k].column = current.column;
    const std::array<double, 4> c = motion.coordinates();
    coordinates.insert(coordinates.end(), c.begin(), c.end());
    for (std::size_t s : samples) {
      for (std::size_t j : agents) {
        place(s, j, motion.target(original(clip, s, j)), Source{"drags", k});
        placements.back().drag = static_cast<long>(k);
      }
    }
  }

  // One handle per vertex, its first placement's (the sort is stable); a later one elsewhere is a contradiction:
  // the earliest such placement in request order is reported, with the one it contradicts.
  std::stable_sort(placements.begin(), placements.end(), [](const Placement& a, const Placement& b) { return a.v < b.v; });
  std::vector<std::size_t> firsts;  // index of each vertex's first placement, vertices increasing
  const Placement* clash = nullptr;
  const Placement* clashed = nullptr;
  for (std::size_t i = 0; i < placements.size(); ++i) {
    const Placement& p = placements[i];
    if (firsts.empty() || placements[firsts.back()].v != p.v) {
      firsts.push_back(i);
      continue;
    }
    const Placement& first = placements[firsts.back()];
    for (long k : {first.drag, p.drag}) {
      if (k >= 0) drag_placements[static_cast<std::size_t>(k)].alone = false;
    }
    const bool differs = (first.target - p.target).cwiseAbs().maxCoeff() > 1e-9 * (1.0 + p.target.cwiseAbs().maxCoeff());
    if (differs && (clash == nullptr || p.order < clash->order)) {
      clash = &p;
      clashed = &first;
    }
  }
  if (clash != nullptr) {
    const auto agents = static_cast<Index>(clip.agent_count());
    const auto sample = static_cast<std::size_t>(clash->v / agents);
    const auto agent_index = static_cast<std::size_t>(clash->v % agents);
    throw NumericalError("contradictory handles: " + sources[clashed->who].text() + " and " + sources[clash->who].text() +
                         " both place agent " + std::to_string(clip.ids[agent_index]) + " at frame " +
                         std::to_string(clip.frames[sample]) + ", at " + point(clashed->target) + " and " + point(clash->target));
  }

  ResolvedRequest out;
  out.handle_targets.resize(static_cast<Index>(firsts.size()), 2);
  out.handle_vertices.reserve(firsts.size());
  std::vector<Eigen::Triplet<double>> basis;
  basis.reserve(6 * firsts.size());
  for (std::size_t i : firsts) {
    const Placement& placement = placements[i];
    const auto k = static_cast<Index>(out.handle_vertices.size());
    out.handle_targets.row(k) = placement.target.transpose();
    out.handle_vertices.push_back(placement.v);
    if (placement.drag >= 0) drag_placements[static_cast<std::size_t>(placement.drag)].rows.push_back(k);
    const Parametrisation& q = placement.q;
    if (q.rigid) {  // x = p_x cos − p_y sin + t_x,  y = p_y cos + p_x sin + t_y
      basis.emplace_back(2 * k, q.column, q.p.x());
      basis.emplace_back(2 * k, q.column + 1, -q.p.y());
      basis.emplace_back(2 * k, q.column + 2, 1.0);
      basis.emplace_back(2 * k + 1, q.column, q.p.y());
      basis.emplace_back(2 * k + 1, q.column + 1, q.p.x());
      basis.emplace_back(2 * k + 1, q.column + 3, 1.0);
    } else {
      basis.emplace_back(2 * k, q.column, 1.0);
      basis.emplace_back(2 * k + 1, q.column + 1, 1.0);
    }
  }
  out.handle_basis.resize(2 * static_cast<Index>(firsts.size()), static_cast<Index>(coordinates.size()));
  out.handle_basis.setFromTriplets(basis.begin(), basis.end());
  out.handle_basis.makeCompressed();
  out.handle_coordinates = Eigen::Map<const Eigen::VectorXd>(coordinates.data(), static_cast<Index>(coordinates.size()));
  out.drags = std::move(drag_placements);

  // General constraints: one or two rows per sample they cover (a Row: one row).
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<double> d;
  auto row = [&](std::size_t source, std::initializer_list<std::pair<Index, double>> terms, double value) {
    const auto r = static_cast<Index>(d.size());
    for (const auto& [unknown, coefficient] : terms) entries.emplace_back(r, unknown, coefficient);
    d.push_back(value);
    out.row_source.push_back(source);
  };
  // Kinds on one agent: relative position, velocity, on a line, acceleration.
  auto add_agent_rows = [&](std::size_t k, const auto& c, const std::string& where) {
    using T = std::decay_t<decltype(c)>;
    const std::size_t a = agent(clip, crowd_ids, c.agent, where + ".agent");
    if constexpr (std::is_same_v<T, Acceleration>) {
      if (!c.acceleration.allFinite()) throw ConfigError(where + ".acceleration " + point(c.acceleration) + " is not finite");
      const auto f = acceleration_frames(clip, absolute_frame(clip, c.frame, where + ".frame"), where);
      std::array<Index, 3> v{};
      std::array<double, 3> t{};
      for (std::size_t i = 0; i < 3; ++i) {
        const std::size_t sample = sample_at(clip, static_cast<Frame>(f[i]), where + ".frame");
        v[i] = clip.vertex(sample, a);
        t[i] = clip.times[sample];
      }
      // (h1 p0 − (h0 + h1) p1 + h0 p2) / h̄ = a h0 h1, h̄ = (h0 + h1)/2: the three-point second difference
      // times h0 h1, in metres (p0 − 2 p1 + p2 = a Δt² at equal spacing).
      const double h0 = t[1] - t[0], h1 = t[2] - t[1], mean = 0.5 * (h0 + h1);
      for (int axis = 0; axis < 2; ++axis) {
        row(k, {{2 * v[0] + axis, h1 / mean}, {2 * v[1] + axis, -(h0 + h1) / mean}, {2 * v[2] + axis, h0 / mean}},
            c.acceleration[axis] * h0 * h1);
      }
    } else if constexpr (std::is_same_v<T, Velocity>) {
      if (!c.velocity.allFinite()) throw ConfigError(where + ".velocity is not finite");
      const auto [f0, f1] = velocity_frames(clip, absolute_frame(clip, c.frame, where + ".frame"));
      const std::size_t s0 = sample_at(clip, static_cast<Frame>(f0), where + ".frame");
      const std::size_t s1 = sample_at(clip, static_cast<Frame>(f1), where + ".frame");
      const double dt = clip.times[s1] - clip.times[s0];
      const Index v0 = clip.vertex(s0, a), v1 = clip.vertex(s1, a);
      for (int axis = 0; axis < 2; ++axis) row(k, {{2 * v1 + axis, 1.0}, {2 * v0 + axis, -1.0}}, c.velocity[axis] * dt);
    } else {
      const auto [first, last] = clamp_range(clip, c.first_frame, c.last_frame, where);
      const auto samples = samples_in(clip, first, last, where);
      if constexpr (std::is_same_v<T, RelativePosition>) {
        const std::size_t b = agent(clip, crowd_ids, c.other, where + ".other");
        if (c.offset && !c.offset->allFinite()) throw ConfigError(where + ".offset is not finite");
        for (std::size_t s : samples) {
          const Eigen::Vector2d offset = c.offset.value_or(original(clip, s, a) - original(clip, s, b));
          const Index va = clip.vertex(s, a), vb = clip.vertex(s, b);
          for (int axis = 0; axis < 2; ++axis) row(k, {{2 * va + axis, 1.0}, {2 * vb + axis, -1.0}}, offset[axis]);
        }
      } else {
        if (!c.point.allFinite() || !c.direction.allFinite() || !(c.direction.norm() > 0)) {
          throw ConfigError(where + ": point and direction must be finite, direction non-zero");
        }
        const Eigen::Vector2d normal = Eigen::Vector2d(-c.direction.y(), c.direction.x()).normalized();
        for (std::size_t s : samples) {
          const Index v = clip.vertex(s, a);
          row(k, {{2 * v, normal.x()}, {2 * v + 1, normal.y()}}, normal.dot(c.point));
        }
      }
    }
  };
  // Σ_k w_k p(agent_k) = value, both axes, at every sample of the range.
  auto add_sum_rows = [&](std::size_t k, const Sum& c, const std::string& where) {
    const auto [agents, weights] = sum_terms(clip, crowd_ids, c, where);
    const auto [first, last] = clamp_range(clip, c.first_frame, c.last_frame, where);
    for (std::size_t s : samples_in(clip, first, last, where)) {
      Eigen::Vector2d value = Eigen::Vector2d::Zero();
      if (c.value) {
        value = *c.value;
      } else {
        for (std::size_t i = 0; i < agents.size(); ++i) value += weights[i] * original(clip, s, agents[i]);
      }
      for (int axis = 0; axis < 2; ++axis) {
        const auto r = static_cast<Index>(d.size());
        for (std::size_t i = 0; i < agents.size(); ++i) {
          if (weights[i] != 0.0) entries.emplace_back(r, 2 * clip.vertex(s, agents[i]) + axis, weights[i]);
        }
        d.push_back(value[axis]);
        out.row_source.push_back(k);
      }
    }
  };
  // Σ_j c_j p(agent_j, frame_j)[axis_j] = value: one row (zero coefficients left out).
  auto add_user_row = [&](std::size_t k, const Row& c, const std::string& where) {
    const auto r = static_cast<Index>(d.size());
    const std::vector<ResolvedTerm> terms = row_terms(clip, crowd_ids, c, where);
    for (std::size_t i = 0; i < terms.size(); ++i) {
      const std::size_t sample = sample_at(clip, static_cast<Frame>(terms[i].frame), where + ".terms[" + std::to_string(i) + "].frame");
      if (terms[i].coefficient != 0.0) entries.emplace_back(r, 2 * clip.vertex(sample, terms[i].agent) + terms[i].axis, terms[i].coefficient);
    }
    d.push_back(c.value);
    out.row_source.push_back(k);
  };
  for (std::size_t k = 0; k < request.constraints.size(); ++k) {
    const std::string where = "constraints[" + std::to_string(k) + "]";
    std::visit(
        [&](const auto& c) {
          using T = std::decay_t<decltype(c)>;
          if constexpr (std::is_same_v<T, Sum>) {
            add_sum_rows(k, c, where);
          } else if constexpr (std::is_same_v<T, Row>) {
            add_user_row(k, c, where);
          } else {
            add_agent_rows(k, c, where);
          }
        },
        request.constraints[k]);
  }
  out.C.resize(static_cast<Index>(d.size()), 2 * static_cast<Index>(clip.positions.rows()));
  // (Without entries the empty matrix is already right: setFromTriplets would still sort through a copy with a
  // column per unknown of the crowd, a cost every drag of a cached local region would pay.)
  if (!entries.empty()) out.C.setFromTriplets(entries.begin(), entries.end());
  out.d = Eigen::Map<const Eigen::VectorXd>(d.data(), static_cast<Index>(d.size()));
  return out;
}

bool redrag(ResolvedRequest& resolved, const Request& before, const Request& request, const Clip& clip) {
  if (request.drags.size() != before.drags.size() || resolved.drags.size() != request.drags.size() ||
      !same_entries(request.pins, before.pins) || !same_entries(request.constraints, before.constraints)) {
    return false;
  }
  std::vector<std::size_t> changed;
  for (std::size_t k = 0; k < request.drags.size(); ++k) {
    const Drag& was = before.drags[k];
    const Drag& is = request.drags[k];
    if (is.selection.agents != was.selection.agents || is.selection.first_frame != was.selection.first_frame ||
        is.selection.last_frame != was.selection.last_frame) {
      return false;
    }
    if (same_bits(is.offset, was.offset) && same_bits(is.rotation, was.rotation) && same_bits(is.pivot, was.pivot)) continue;
    if (!resolved.drags[k].alone) return false;  // a target shared with another entry: resolve() checks them
    changed.push_back(k);
  }
  // Every new value first, then written. Anything not finite is resolve()'s to report (it names the first
  // offending entry in request order): refused, nothing changed.
  std::vector<Eigen::Vector2d> targets;
  std::vector<std::array<double, 4>> coordinates;
  for (std::size_t k : changed) {
    const Drag& d = request.drags[k];
    if (!finite_motion(d)) return false;
    const DragMotion motion(d, resolved.drags[k].centroid);
    coordinates.push_back(motion.coordinates());
    for (Index row : resolved.drags[k].rows) {
      const Eigen::Vector2d p = clip.positions.row(resolved.handle_vertices[static_cast<std::size_t>(row)]).transpose();
      targets.push_back(motion.target(p));
      if (!targets.back().allFinite()) return false;
    }
  }
  std::size_t next = 0;
  for (std::size_t c = 0; c < changed.size(); ++c) {
    const auto& placement = resolved.drags[changed[c]];
    for (Index i = 0; i < 4; ++i) resolved.handle_coordinates[placement.column + i] = coordinates[c][static_cast<std::size_t>(i)];
    for (Index row : placement.rows) resolved.handle_targets.row(row) = targets[next++].transpose();
  }
  return true;
}

}  // namespace throng::edit
