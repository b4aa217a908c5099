// The windowed tiler (windowed.h): the window loop, what becomes final after each window, what is carried, and
// the resumable state.
#include <throng/tiling/windowed.h>

#include <throng/core/errors.h>
#include <throng/core/parallel.h>
#include <throng/core/random.h>

#include "bytes.h"
#include "frame_stream.h"
#include "phases.h"
#include "viability.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <tuple>

namespace throng::tiling {
namespace {

constexpr double minus_infinity = -std::numeric_limits<double>::infinity();
// 02: samples carry heading and action; 03: walks carry the facing shown (the facing-rate limit)
constexpr char magic[8] = {'T', 'H', 'R', 'W', 'I', 'N', '0', '3'};

// An instance carried into the next window, with its id in the delivered tiling once it is final (−1 before).
struct Carried {
  LiveInstance live;
  std::int64_t delivered = -1;
};

double start_of(const std::vector<Path>& paths) {
  double t = std::numeric_limits<double>::infinity();
  for (const Path& p : paths) t = std::min(t, p.times.front());
  return t;
}

double end_of(const std::vector<Path>& paths) {
  double t = -std::numeric_limits<double>::infinity();
  for (const Path& p : paths) t = std::max(t, p.times.back());
  return t;
}

// FNV-1a over the values that make a run: a resumed run must be the same run.
class Fingerprint {
 public:
  template <class T>
  void add(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* p = reinterpret_cast<const unsigned char*>(&v);
    for (std::size_t i = 0; i < sizeof(T); ++i) hash_ = (hash_ ^ p[i]) * 1099511628211ull;
  }
  void add(const std::string& s) {
    add(s.size());
    for (char c : s) add(c);
  }
  [[nodiscard]] std::uint64_t value() const noexcept { return hash_; }

 private:
  std::uint64_t hash_ = 14695981039346656037ull;
};

std::uint64_t fingerprint_of(const PatchLibrary& library, const Environment& environment, const Options& options,
                             const WindowOptions& window) {
  Fingerprint f;
  for (const std::string& c : library.pose_classes) f.add(c);
  for (const PatchType& t : library.types) {
    f.add(t.name);
    f.add(t.preference);
    for (const Fragment& fr : t.fragments) {
      f.add(fr.radius_m);
      f.add(fr.entry_class);
      f.add(fr.exit_class);
      for (std::size_t s = 0; s < fr.sample_count(); ++s) {
        f.add(fr.positions[s].x());
        f.add(fr.positions[s].y());
        f.add(fr.headings[s]);
        f.add(fr.times[s]);
      }
    }
    f.add(t.constraints.size());
  }
  const Region& r = *environment.scene.region;
  for (const double v : {r.min.x(), r.min.y(), r.max.x(), r.max.y(), r.t0, r.t1}) f.add(v);
  for (const bool p : r.periodic) f.add(p);
  f.add(environment.scene.obstacles.size());
  for (const Obstacle& o : environment.scene.obstacles) f.add(bounds_over(o, r.t0, r.t1).min().x());
  f.add(environment.sources.size());
  f.add(environment.sinks.size());
  f.add(window.window_s);
  f.add(window.lookahead_s);
  f.add(window.frame_rate_hz);
  f.add(window.max_facing_rate_rad_s);
  f.add(options.density.per_m2);
  f.add(options.density.zones.size());
  f.add(options.density.tolerance);
  f.add(options.density.bin_s);
  f.add(options.chains);
  f.add(options.seed);
  return f.value();
}

// The look-ahead (windowed.h): as given, or (negative) half the region's larger side walked at the projection
// speed, plus the longest patch; at most a window.
double lookahead_of(const PatchLibrary& library, const Region& region, const Options& options, const WindowOptions& window) {
  if (window.lookahead_s >= 0) return window.lookahead_s;
  const double side = std::max(region.max.x() - region.min.x(), region.max.y() - region.min.y());
  return std::min(window.window_s, 0.5 * side / options.density.projection_speed_mps + 2 * max_half_duration_of(library));
}

void check(const PatchLibrary& library, const Environment& environment, const Options& options,
           const WindowOptions& window) {
  validate(options);
  library.validate();
  if (!environment.scene.region) throw ConfigError("windowed tiling: no region: give the space-time box to fill");
  const Region& r = *environment.scene.region;
  if (!(r.max.x() > r.min.x() && r.max.y() > r.min.y() && r.t1 > r.t0)) {
    throw ConfigError("windowed tiling: the region must have max > min on x and y and t1 > t0");
  }
  environment.scene.validate("windowed tiling scene");
  if (r.periodic[2]) {
    throw ConfigError("windowed tiling: the region is periodic in time: a loop is one tile, tile it whole (no window)");
  }
  if (options.characters > 0) {
    throw ConfigError("windowed tiling: `characters` caps the total over the whole run, which has no meaning over an "
                      "open horizon: give the density per area (density.per_m2) instead");
  }
  if (!(window.window_s > 0) || !std::isfinite(window.window_s)) {
    throw ConfigError("windowed tiling: window = " + std::to_string(window.window_s) + " s, expected a finite value > 0");
  }
  if (!(window.frame_rate_hz > 0) || !std::isfinite(window.frame_rate_hz)) {
    throw ConfigError("windowed tiling: frame rate " + std::to_string(window.frame_rate_hz) + " Hz, expected > 0");
  }
  const double longest = 2 * max_half_duration_of(library);
  if (window.window_s < 2 * longest) {
    std::ostringstream m;
    m << "windowed tiling: window = " << window.window_s << " s is shorter than twice the longest patch (" << longest
      << " s): a window must hold what its seam may still change";
    throw ConfigError(m.str());
  }
  for (const auto& [zones, what] : {std::pair(&environment.sources, "source"), std::pair(&environment.sinks, "sink")}) {
    for (std::size_t i = 0; i < zones->size(); ++i) {
      const Zone& z = (*zones)[i];
      if (!(z.radius_m > 0) || !z.center.allFinite() || !(z.t1 >= z.t0)) {
        throw ConfigError(std::string("windowed tiling: ") + what + " " + std::to_string(i) +
                          ": expected a finite centre, radius > 0 and t1 ≥ t0");
      }
    }
  }
  const Viability viability = find_usable_types(library);
  if (std::none_of(viability.usable.begin(), viability.usable.end(), [](bool u) { return u; })) {
    std::ostringstream m;
    m << "windowed tiling: no patch type can ever be placed inside the region without leaving an end that nothing can "
         "continue:";
    for (std::size_t k = 0; k < library.types.size(); ++k) m << (k ? ";" : "") << " '" << library.types[k].name << "': " << viability.why[k];
    throw NumericalError(m.str());
  }
  double bytes = 0;
  for (const PatchType& t : library.types) bytes += deformation_bytes(t);
  if (bytes > max_deformation_bytes) {
    std::ostringstream m;
    m << "windowed tiling: the patch deformation systems would take " << bytes / 1e9 << " GB, more than the "
      << max_deformation_bytes / 1e9 << " GB allowed: sample the patches more coarsely or use shorter ones";
    throw ConfigError(m.str());
  }
  if (!std::isfinite(window.lookahead_s)) throw ConfigError("windowed tiling: the look-ahead must be finite");
  // A window's grids span the window, its look-ahead and what its seam may still change.
  Region one = r;
  one.t1 = std::min(r.t1, r.t0 + window.window_s + lookahead_of(library, r, options, window) + longest);
  const double cells = index_cells(library, one, options);
  if (cells > max_index_cells) {
    std::ostringstream m;
    m << "windowed tiling: a window's space-time index would have " << cells << " cells, more than " << max_index_cells
      << ": raise index.cell or index.cell_time, or use shorter windows";
    throw ConfigError(m.str());
  }
}

// The ranking key of a window's chain (as tile(): dangling, density, preference, index).
std::tuple<std::size_t, double, double, std::size_t> score(const ChainReport& r) {
  return {r.dangling, r.density_distance, r.mean_preference_cost, r.chain};
}

}  // namespace

struct WindowedTiler::Impl {
  Impl(const PatchLibrary& lib, const Environment& env, const Options& opts, const WindowOptions& win)
      : library((check(lib, env, opts, win), lib)), environment(env), options(opts), window(win),
        stream(library, *environment.scene.region, window.frame_rate_hz,
               max_turn_per_frame(LayoutOptions{window.frame_rate_hz, {1, 1, 1}, window.max_facing_rate_rad_s})) {
    const Region& r = *environment.scene.region;
    for (double t = r.t0; t < r.t1 - 1e-9 * window.window_s; t = r.t0 + static_cast<double>(seams.size()) * window.window_s) {
      seams.push_back(t);
    }
    seams.push_back(r.t1);
    precompute = std::make_shared<const PatchPrecompute>(library, options.deformation);
    lookahead = lookahead_of(library, r, options, window);
    fingerprint = fingerprint_of(library, environment, options, window);
  }

  [[nodiscard]] std::size_t windows() const noexcept { return seams.size() - 1; }

  // The first frame at or after time t.
  [[nodiscard]] std::size_t first_frame_at(double t) const {
    const double t0 = environment.scene.region->t0;
    auto f = static_cast<std::size_t>(std::max(0.0, std::floor((t - t0) * window.frame_rate_hz)));
    while (f > 0 && stream.frame_time(f - 1) >= t) --f;
    while (f < stream.frame_count() && stream.frame_time(f) < t) ++f;
    return f;
  }

  WindowOutput next(Progress& progress);
  void save(std::vector<std::byte>& out) const;
  void load(const std::vector<std::byte>& in);

  PatchLibrary library;
  Environment environment;
  Options options;
  WindowOptions window;
  std::vector<double> seams;  // t_0 … t_K
  std::shared_ptr<const PatchPrecompute> precompute;
  double lookahead = 0;
  std::uint64_t fingerprint = 0;
  FrameStream stream;
  // The resumable state.
  std::size_t next_window = 0;
  double freeze = minus_infinity;
  std::uint64_t next_delivered = 0;
  std::size_t lost_dangling = 0;
  std::size_t next_frames = 0;  // the next time window whose frames to deliver
  std::vector<Carried> carry;
};

WindowOutput WindowedTiler::Impl::next(Progress& progress) {
  const auto started = std::chrono::steady_clock::now();
  const std::size_t k = next_window;
  const bool last = k + 1 == windows();
  const double t_begin = seams[k], t_end = seams[k + 1];
  const Region& horizon = *environment.scene.region;

  // The window's problem: the region rule ends at the end of the window's look-ahead; the grids start at the
  // freeze time.
  const double reach = std::min(horizon.t1, t_end + lookahead);
  Environment here = environment;
  here.scene.region->t1 = reach;
  const Problem problem(precompute, library, here, options, TimeWindow{t_begin, reach, freeze, horizon.t0, horizon.t1});
  std::vector<LiveInstance> start;
  start.reserve(carry.size());
  for (const Carried& c : carry) start.push_back(c.live);

  // The chains, in parallel; the best is kept.
  std::vector<WindowChain> chains(options.chains);
  const auto fractions = std::make_unique<std::atomic<double>[]>(options.chains);
  for (std::size_t c = 0; c < options.chains; ++c) fractions[c] = 0.0;
  const std::thread::id caller = std::this_thread::get_id();
  parallel_for(options.chains, 1, [&](std::size_t a, std::size_t b) {
    for (std::size_t c = a; c < b; ++c) {
      chains[c] = run_window_chain(problem, start, c, derive_seed(derive_seed(options.seed, k), c), [&, c](double f) {
        fractions[c] = f;
        if (std::this_thread::get_id() != caller) return;
        double sum = 0;
        for (std::size_t j = 0; j < options.chains; ++j) sum += fractions[j];
        progress.update(std::min(1.0, sum / static_cast<double>(options.chains)), "window " + std::to_string(k + 1));
      });
    }
  });
  std::size_t best = 0;
  for (std::size_t c = 1; c < chains.size(); ++c) {
    if (score(chains[c].report) < score(chains[best].report)) best = c;
  }
  const TilingState& state = *chains[best].state;

  WindowOutput out;
  WindowReport& report = out.report;
  report.index = k;
  report.t0 = t_begin;
  report.t1 = t_end;
  report.freeze = freeze;
  report.best_chain = best;
  report.dangling = state.dangling();
  report.carried_in = carry.size();
  report.instances = state.instances();
  for (const WindowChain& c : chains) report.chains.push_back(c.report);

  // What is final: every instance that ends by the window's end (all after the last window). Carried instances
  // keep their slots (fixed ones are never removed), so a carried slot still holds the instance it was given.
  std::vector<std::int64_t> delivered(state.slots(), -1);
  for (std::size_t i = 0; i < carry.size(); ++i) delivered[i] = carry[i].delivered;
  std::vector<std::uint32_t> alive, fresh;
  double next_freeze = t_end - precompute->max_half_duration_s;
  for (std::uint32_t id = 0; id < state.slots(); ++id) {
    const LiveInstance& inst = state.at(id);
    if (!inst.alive) continue;
    alive.push_back(id);
    const bool final = last || inst.fixed || end_of(inst.paths) <= t_end;
    if (!final) next_freeze = std::min(next_freeze, start_of(inst.paths));
    if (final && delivered[id] < 0) fresh.push_back(id);
  }
  next_freeze = std::max(next_freeze, freeze);
  // Delivered ids in order of start, end, type, placement (the slot last: ties of identical placements).
  std::sort(fresh.begin(), fresh.end(), [&](std::uint32_t a, std::uint32_t b) {
    const LiveInstance& x = state.at(a);
    const LiveInstance& y = state.at(b);
    return std::make_tuple(start_of(x.paths), end_of(x.paths), x.type, x.transform.translation.x(),
                           x.transform.translation.y(), x.transform.angle, a) <
           std::make_tuple(start_of(y.paths), end_of(y.paths), y.type, y.transform.translation.x(),
                           y.transform.translation.y(), y.transform.angle, b);
  });
  out.first_instance = next_delivered;
  for (std::uint32_t id : fresh) {
    delivered[id] = static_cast<std::int64_t>(next_delivered++);
    const LiveInstance& inst = state.at(id);
    out.instances.push_back(Instance{inst.type, inst.transform, inst.keyframed, inst.paths});
  }
  // The connections into the fresh instances' entries: their partners end where they start, so they are final
  // too (delivered now or before) and still held.
  for (std::uint32_t id : fresh) {
    const LiveInstance& inst = state.at(id);
    for (std::uint32_t f = 0; f < inst.ends.size(); ++f) {
      const EndLink& e = inst.ends[f][0];
      if (e.status != EndStatus::connected) continue;
      if (e.partner.instance == gone || delivered[e.partner.instance] < 0) {
        throw std::logic_error("windowed tiling: a final instance's predecessor is not final");
      }
      out.connections.push_back(Connection{{static_cast<std::uint32_t>(delivered[e.partner.instance]), e.partner.fragment},
                                           {static_cast<std::uint32_t>(delivered[id]), f},
                                           e.image});
    }
  }

  // What is carried: every instance that ends at or after the next freeze time; the others are left behind, with
  // their dangling ends, if any, lost for good.
  std::vector<std::uint32_t> position(state.slots(), gone);
  std::vector<Carried> next_carry;
  for (std::uint32_t id : alive) {
    const LiveInstance& inst = state.at(id);
    if (!last && end_of(inst.paths) >= next_freeze) {
      position[id] = static_cast<std::uint32_t>(next_carry.size());
      next_carry.push_back(Carried{inst, delivered[id]});
      next_carry.back().live.fixed = delivered[id] >= 0;
      continue;
    }
    for (const auto& sides : inst.ends) {
      for (const EndLink& e : sides) lost_dangling += e.status == EndStatus::dangling;
    }
  }
  for (Carried& c : next_carry) {
    for (auto& sides : c.live.ends) {
      for (EndLink& e : sides) {
        if (e.status == EndStatus::connected && e.partner.instance != gone) e.partner.instance = position[e.partner.instance];
      }
    }
  }
  carry = std::move(next_carry);
  report.carried_out = carry.size();
  out.lost_dangling = lost_dangling;
  freeze = next_freeze;
  ++next_window;

  // The frames that became final: every time window that ends by the next freeze time (all after the last).
  stream.deliver(out.first_instance, out.instances, out.connections);
  while (next_frames < windows() && (last || seams[next_frames + 1] <= next_freeze)) {
    FrameWindow fw;
    fw.index = next_frames;
    fw.t0 = seams[next_frames];
    fw.t1 = seams[next_frames + 1];
    fw.first_frame = stream.next_frame();
    const std::size_t end = next_frames + 1 == windows() ? stream.frame_count() : first_frame_at(fw.t1);
    if (options.density.enabled()) {
      Tiling held;
      for (const auto& [id, inst] : stream.held()) held.instances.push_back(inst);
      DensityOptions one = options.density;
      one.report_window_s = fw.t1 - fw.t0;
      one.bin_s = std::min(one.bin_s, one.report_window_s);
      const DensityReport d = measure_density(library, held, environment, one, fw.t0, fw.t1);
      if (!d.windows.empty()) fw.density = d.windows.front();
    }
    stream.emit(end, fw.frames, fw.pieces);
    out.frames.push_back(std::move(fw));
    ++next_frames;
  }
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  progress.update(1.0, "window " + std::to_string(k + 1));
  return out;
}

void WindowedTiler::Impl::save(std::vector<std::byte>& out) const {
  ByteWriter w(out);
  for (char c : magic) w.put(c);
  w.put(fingerprint);
  w.put<std::uint64_t>(next_window);
  w.put(freeze);
  w.put(next_delivered);
  w.put<std::uint64_t>(lost_dangling);
  w.put<std::uint64_t>(next_frames);
  w.put<std::uint64_t>(carry.size());
  for (const Carried& c : carry) {
    const LiveInstance& l = c.live;
    w.put(c.delivered);
    w.put(l.type);
    w.put(l.transform.translation.x());
    w.put(l.transform.translation.y());
    w.put(l.transform.angle);
    w.put(l.transform.time_shift);
    w.put<std::uint8_t>(l.keyframed ? 1 : 0);
    w.put<std::uint8_t>(l.fixed ? 1 : 0);
    w.put<std::uint64_t>(l.paths.size());
    for (const Path& p : l.paths) put_path(w, p);
    w.put_vector(l.ends);
  }
  stream.save(out);
}

void WindowedTiler::Impl::load(const std::vector<std::byte>& in) {
  std::size_t at = 0;
  ByteReader r(in, at, "windowed tiling state");
  for (char c : magic) {
    if (r.get<char>() != c) throw InputError("windowed tiling state: not a state of a windowed tiling run (no magic)");
  }
  if (r.get<std::uint64_t>() != fingerprint) {
    throw InputError("windowed tiling state: made by a run with another library, region, obstacles, window, frame "
                     "rate, facing rate, density, chain count or seed: resume with the job that made it");
  }
  next_window = r.get<std::uint64_t>();
  freeze = r.get<double>();
  next_delivered = r.get<std::uint64_t>();
  lost_dangling = r.get<std::uint64_t>();
  next_frames = r.get<std::uint64_t>();
  if (next_window > windows() || next_frames > windows()) r.fail();
  carry.assign(r.count(1), Carried{});
  for (Carried& c : carry) {
    LiveInstance& l = c.live;
    c.delivered = r.get<std::int64_t>();
    l.alive = true;
    l.type = r.get<std::uint32_t>();
    l.transform.translation.x() = r.get<double>();
    l.transform.translation.y() = r.get<double>();
    l.transform.angle = r.get<double>();
    l.transform.time_shift = r.get<double>();
    l.keyframed = r.get<std::uint8_t>() != 0;
    l.fixed = r.get<std::uint8_t>() != 0;
    if (l.type >= library.types.size()) r.fail();
    const PatchType& type = library.types[l.type];
    l.paths.resize(r.count(1));
    if (l.paths.size() != type.fragments.size()) r.fail();
    for (std::size_t f = 0; f < l.paths.size(); ++f) {
      l.paths[f] = get_path(r);
      const Path& p = l.paths[f];
      if (p.times.size() != type.fragments[f].sample_count() || p.positions.size() != p.times.size() ||
          p.headings.size() != p.times.size()) {
        r.fail();
      }
    }
    l.ends = r.get_vector<std::array<EndLink, 2>>();
    if (l.ends.size() != type.fragments.size()) r.fail();
  }
  for (const Carried& c : carry) {
    for (const auto& sides : c.live.ends) {
      for (const EndLink& e : sides) {
        if (e.status == EndStatus::connected && e.partner.instance != gone &&
            (e.partner.instance >= carry.size() || e.partner.fragment >= carry[e.partner.instance].live.ends.size())) {
          r.fail();
        }
      }
    }
  }
  stream.load(in, at);
  if (at != in.size()) r.fail();
}

WindowedTiler::WindowedTiler(const PatchLibrary& library, const Environment& environment, const Options& options,
                             const WindowOptions& window)
    : impl_(std::make_unique<Impl>(library, environment, options, window)) {}

WindowedTiler::WindowedTiler(const PatchLibrary& library, const Environment& environment, const Options& options,
                             const WindowOptions& window, const std::vector<std::byte>& state)
    : impl_(std::make_unique<Impl>(library, environment, options, window)) {
  impl_->load(state);
}

WindowedTiler::~WindowedTiler() = default;

std::size_t WindowedTiler::windows() const noexcept { return impl_->windows(); }
std::size_t WindowedTiler::next_window() const noexcept { return impl_->next_window; }

WindowOutput WindowedTiler::next(Progress& progress) {
  if (done()) throw std::logic_error("WindowedTiler::next: every window is tiled");
  return impl_->next(progress);
}

std::vector<std::byte> WindowedTiler::state() const {
  std::vector<std::byte> bytes;
  impl_->save(bytes);
  return bytes;
}

std::size_t tile_windows(WindowedTiler& tiler, const std::function<void(const WindowOutput&, const WindowedTiler&)>& on_window,
                         Progress& progress) {
  std::size_t lost = 0;
  while (!tiler.done()) {
    const WindowOutput out = tiler.next(progress);
    lost = out.lost_dangling;
    if (on_window) on_window(out, tiler);
  }
  return lost;
}

}  // namespace throng::tiling
