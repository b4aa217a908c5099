// The streamed crowd file of a windowed tiling (tiling_stream.h).
#include <throng/core/bytes.h>
#include <throng/core/errors.h>
#include <throng/io/crowd_file_parts.h>
#include <throng/io/hdf5_growing.h>
#include <throng/io/report_record.h>
#include <throng/io/tiling_data.h>
#include <throng/io/tiling_stream.h>
#include <throng/tiling/characters.h>
#include <throng/tiling/runner.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <set>

namespace throng {

using namespace tiling;
using h5::GrowingDataset;
using h5::Number;

namespace {

constexpr std::uint64_t slot_chunk = 32;   // slots per chunk of the per-frame datasets
constexpr std::uint64_t row_chunk = 1024;  // rows per chunk of the tiling's tables

}  // namespace

void TilingStreamRecord::save(std::vector<std::byte>& out) const {
  ByteWriter w(out);
  for (const std::uint64_t v : {frames, slots, agents, instances, path_rows, connections, pieces, windows, density_rows,
                                lost_dangling}) {
    w.put(v);
  }
  w.put(density_worst);
  w.put(static_cast<std::uint8_t>(density_met));
  w.put(static_cast<std::uint64_t>(active.size()));
  for (const auto& [agent, a] : active) {
    w.put(agent);
    w.put(a.slot);
    w.put(a.radius);
    w.put_vector(a.last_pieces);
  }
}

TilingStreamRecord TilingStreamRecord::load(const std::vector<std::byte>& in, std::size_t& at, const std::string& where) {
  ByteReader r(in, at, where + ": the resume record");
  TilingStreamRecord out;
  for (std::uint64_t* v : {&out.frames, &out.slots, &out.agents, &out.instances, &out.path_rows, &out.connections, &out.pieces,
                           &out.windows, &out.density_rows, &out.lost_dangling}) {
    *v = r.get<std::uint64_t>();
  }
  out.density_worst = r.get<double>();
  out.density_met = r.get<std::uint8_t>() != 0;
  const auto n = r.count(sizeof(std::int64_t) + sizeof(std::uint64_t) + sizeof(double) + sizeof(std::uint64_t));
  std::set<std::uint64_t> slots;
  for (std::size_t k = 0; k < n; ++k) {
    const auto agent = r.get<std::int64_t>();
    Active a;
    a.slot = r.get<std::uint64_t>();
    a.radius = r.get<double>();
    a.last_pieces = r.get_vector<std::array<std::int64_t, 5>>();
    // Every active agent names an agent of the record, in a slot of its own.
    if (agent < 0 || static_cast<std::uint64_t>(agent) >= out.agents || a.slot >= out.slots || !slots.insert(a.slot).second ||
        out.active.count(agent) != 0) {
      r.fail();
    }
    out.active.emplace(agent, std::move(a));
  }
  return out;
}

void describe(ReportWriter& w, const WindowedSummary& s) {
  const TilingStreamRecord& r = s.record;
  w.count("windows", r.windows);
  w.count("instances", r.instances);
  w.count("connections", r.connections);
  w.count("dangling", r.lost_dangling);
  w.count("agents", r.agents);
  w.count("frames", r.frames);
  w.count("slots", r.slots);
  w.count("patch_types", s.patch_types);
  if (s.density_asked) {
    w.number("density_worst", r.density_worst);
    w.number("density_tolerance", s.density_tolerance);
    w.flag("density_met", r.density_met);
  }
  w.seconds("seconds", s.seconds);
}

ResumablePaths resumable_paths(const std::filesystem::path& target) {
  const std::filesystem::path folder = target.parent_path();
  const std::string name = "." + target.filename().string() + ".partial";
  return {folder / name, folder / (name + ".state")};
}

// The datasets a stream grows, by their place in the file.
struct TilingStreamWriter::Impl {
  h5::File file;
  std::string name;
  TilingStreamSetup setup;
  TilingStreamRecord record;
  bool periodic_box = false;
  std::optional<GrowingDataset> step, time, position, orientation, action, species, id, edges;
  std::optional<GrowingDataset> agent_id, agent_radius, agent_species;
  std::optional<GrowingDataset> type, transform, keyframed, paths, connections, pieces, windows, density;

  Impl(h5::File f, std::string display, const TilingStreamSetup& s) : file(std::move(f)), name(std::move(display)), setup(s) {
    const Region& r = *setup.environment->scene.region;
    periodic_box = r.periodic[0] || r.periodic[1];
  }

  // Every growing dataset, with its name, type and rank, for creating and reopening alike.
  template <class F>
  void for_each(F&& f) {
    f(step, "particles/trajectory/position/step", Number::int64, std::vector<std::uint64_t>{0}, std::vector<std::uint64_t>{row_chunk}, 0.0);
    f(time, "particles/trajectory/position/time", Number::float64, std::vector<std::uint64_t>{0}, std::vector<std::uint64_t>{row_chunk}, 0.0);
    const std::uint64_t fc = std::max<std::uint64_t>(1, setup.frames_per_window);
    f(position, "particles/trajectory/position/value", Number::float64, std::vector<std::uint64_t>{0, 0, 3},
      std::vector<std::uint64_t>{fc, slot_chunk, 3}, absent);
    f(orientation, "particles/trajectory/orientation/value", Number::float64, std::vector<std::uint64_t>{0, 0, 4},
      std::vector<std::uint64_t>{fc, slot_chunk, 4}, absent);
    f(action, "particles/trajectory/action/value", Number::int32, std::vector<std::uint64_t>{0, 0},
      std::vector<std::uint64_t>{fc, slot_chunk}, -1.0);
    f(species, "particles/trajectory/species", Number::int32, std::vector<std::uint64_t>{0}, std::vector<std::uint64_t>{slot_chunk}, 0.0);
    f(id, "particles/trajectory/id/value", Number::int64, std::vector<std::uint64_t>{0, 0}, std::vector<std::uint64_t>{fc, slot_chunk}, -1.0);
    if (periodic_box) {
      f(edges, "particles/trajectory/box/edges/value", Number::float64, std::vector<std::uint64_t>{0, 3, 3},
        std::vector<std::uint64_t>{row_chunk, 3, 3}, 0.0);
    }
    f(agent_id, "parameters/throng/agents/id", Number::int64, std::vector<std::uint64_t>{0}, std::vector<std::uint64_t>{row_chunk}, -1.0);
    f(agent_radius, "parameters/throng/agents/radius", Number::float64, std::vector<std::uint64_t>{0}, std::vector<std::uint64_t>{row_chunk}, 0.0);
    f(agent_species, "parameters/throng/agents/species", Number::int32, std::vector<std::uint64_t>{0}, std::vector<std::uint64_t>{row_chunk}, 0.0);
    const std::string t = "parameters/throng/tiling/";
    f(type, t + "instances/type", Number::int64, std::vector<std::uint64_t>{0}, std::vector<std::uint64_t>{row_chunk}, 0.0);
    f(transform, t + "instances/transform", Number::float64, std::vector<std::uint64_t>{0, 4}, std::vector<std::uint64_t>{row_chunk, 4}, 0.0);
    f(keyframed, t + "instances/keyframed", Number::int32, std::vector<std::uint64_t>{0}, std::vector<std::uint64_t>{row_chunk}, 0.0);
    f(paths, t + "instances/paths", Number::float64, std::vector<std::uint64_t>{0, 4}, std::vector<std::uint64_t>{row_chunk * 8, 4}, 0.0);
    f(connections, t + "connections", Number::int64, std::vector<std::uint64_t>{0, 7}, std::vector<std::uint64_t>{row_chunk, 7}, 0.0);
    f(pieces, t + "agents/pieces", Number::int64, std::vector<std::uint64_t>{0, 6}, std::vector<std::uint64_t>{row_chunk, 6}, 0.0);
    f(windows, t + "windows", Number::float64, std::vector<std::uint64_t>{0, 7}, std::vector<std::uint64_t>{64, 7}, 0.0);
    f(density, t + "density", Number::float64, std::vector<std::uint64_t>{0, 7}, std::vector<std::uint64_t>{256, 7}, 0.0);
  }

  // The group holding `path`'s last component (created with its parents when `create`), and that component.
  std::pair<h5::Group, std::string> parent_of(const std::string& path, bool create) const {
    const auto cut = path.rfind('/');
    h5::Group g = file.root();
    std::size_t at = 0;
    while (at < cut) {
      const auto next = std::min(path.find('/', at), cut);
      const std::string part = path.substr(at, next - at);
      g = create && !g.has(part) ? g.create_group(part) : g.open_group(part);
      at = next + 1;
    }
    return {std::move(g), path.substr(cut + 1)};
  }

  void create_all() {
    for_each([&](std::optional<GrowingDataset>& d, const std::string& path, Number n, const std::vector<std::uint64_t>& shape,
                 const std::vector<std::uint64_t>& chunk, double fill) {
      auto [group, leaf] = parent_of(path, true);
      d = GrowingDataset::create(group, leaf, n, shape, chunk, fill);
    });
  }

  // Reopens every dataset and cuts it back to the record (what an interrupted window wrote past it goes).
  void reopen_all() {
    for_each([&](std::optional<GrowingDataset>& d, const std::string& path, Number n, const std::vector<std::uint64_t>& shape,
                 const std::vector<std::uint64_t>&, double) {
      auto [group, leaf] = parent_of(path, false);
      d = GrowingDataset::open(group, leaf, n, shape.size());
    });
    const TilingStreamRecord& r = record;
    const auto cut = [&](GrowingDataset& d, std::vector<std::uint64_t> shape) {
      const std::vector<std::uint64_t> have = d.shape();
      for (std::size_t a = 0; a < shape.size(); ++a) {
        if (have[a] < shape[a]) throw InputError(d.where() + ": holds less than the resume record says (damaged partial file)");
      }
      d.resize(shape);
    };
    cut(*step, {r.frames});
    cut(*time, {r.frames});
    cut(*position, {r.frames, r.slots, 3});
    cut(*orientation, {r.frames, r.slots, 4});
    cut(*action, {r.frames, r.slots});
    cut(*id, {r.frames, r.slots});
    cut(*species, {r.slots});
    if (edges) cut(*edges, {r.frames, 3, 3});
    cut(*agent_id, {r.agents});
    cut(*agent_radius, {r.agents});
    cut(*agent_species, {r.agents});
    cut(*type, {r.instances});
    cut(*transform, {r.instances, 4});
    cut(*keyframed, {r.instances});
    cut(*paths, {r.path_rows, 4});
    cut(*connections, {r.connections, 7});
    cut(*pieces, {r.pieces, 6});
    cut(*windows, {r.windows, 7});
    cut(*density, {r.density_rows, 7});
  }

  void append_instances(const WindowOutput& out) {
    if (out.first_instance != record.instances) {
      throw std::logic_error(name + ": window " + std::to_string(out.report.index) + " delivers instance " +
                             std::to_string(out.first_instance) + " after " + std::to_string(record.instances));
    }
    const TilingRows rows = tiling_rows(out.instances, out.connections);
    type->append(rows.types.size(), rows.types.data());
    transform->append(rows.types.size(), rows.transforms.data());
    keyframed->append(rows.keyframed.size(), rows.keyframed.data());
    paths->append(rows.paths.size() / 4, rows.paths.data());
    connections->append(out.connections.size(), rows.connections.data());
    record.instances += rows.types.size();
    record.path_rows += rows.paths.size() / 4;
    record.connections += out.connections.size();
  }

  // The frames of one time window: agents into slots, then one block per dataset.
  void append_frames(const FrameWindow& w) {
    const CrowdMotion& m = w.frames;
    const std::size_t F = m.frame_count(), n = m.agent_count();
    if (w.first_frame != record.frames) {
      throw std::logic_error(name + ": frames " + std::to_string(w.first_frame) + " delivered after " + std::to_string(record.frames));
    }
    // Agents new to the file: ids continue 0, 1, ...; radii of the others may have grown.
    std::vector<std::int64_t> new_ids;
    std::vector<double> new_radii;
    for (std::size_t a = 0; a < n; ++a) {
      const std::int64_t agent = m.ids[a];
      if (agent == static_cast<std::int64_t>(record.agents + new_ids.size())) {
        new_ids.push_back(agent);
        new_radii.push_back(m.radii[a]);
      } else if (agent >= static_cast<std::int64_t>(record.agents)) {
        throw std::logic_error(name + ": agent " + std::to_string(agent) + " delivered out of order");
      } else if (const auto at = record.active.find(agent); at != record.active.end() && m.radii[a] > at->second.radius) {
        at->second.radius = m.radii[a];
        agent_radius->write({static_cast<std::uint64_t>(agent)}, {1}, &m.radii[a]);
      }
    }
    // Pieces: each agent's fragment copies of this window, less those the previous window already listed (a piece
    // spanning the windows' seam is listed by both).
    std::vector<std::int64_t> rows;
    std::vector<std::vector<std::array<std::int64_t, 5>>> listed(n);
    for (std::size_t a = 0; a < n; ++a) {
      const auto before = record.active.find(m.ids[a]);
      for (const AgentPiece& p : w.pieces[a]) {
        const std::array<std::int64_t, 5> key{p.fragment.instance, p.fragment.fragment, p.copy[0], p.copy[1], p.copy[2]};
        listed[a].push_back(key);
        if (before != record.active.end() &&
            std::find(before->second.last_pieces.begin(), before->second.last_pieces.end(), key) != before->second.last_pieces.end()) {
          continue;
        }
        rows.push_back(m.ids[a]);
        rows.insert(rows.end(), key.begin(), key.end());
      }
    }
    pieces->append(rows.size() / 6, rows.data());
    record.pieces += rows.size() / 6;

    // Slots, frame by frame: agents gone free theirs first, then newcomers take the lowest free ones.
    std::set<std::uint64_t> free;
    std::vector<bool> taken(record.slots, false);
    for (const auto& [agent, a] : record.active) taken[a.slot] = true;
    for (std::uint64_t s = 0; s < record.slots; ++s) {
      if (!taken[s]) free.insert(s);
    }
    std::vector<std::vector<std::uint64_t>> slot_of(F, std::vector<std::uint64_t>(n, UINT64_MAX));
    for (std::size_t f = 0; f < F; ++f) {
      for (auto it = record.active.begin(); it != record.active.end();) {
        const auto col = std::lower_bound(m.ids.begin(), m.ids.end(), it->first) - m.ids.begin();
        const bool here = static_cast<std::size_t>(col) < n && m.ids[static_cast<std::size_t>(col)] == it->first &&
                          m.present(f, static_cast<std::size_t>(col));
        if (here) {
          ++it;
          continue;
        }
        free.insert(it->second.slot);
        it = record.active.erase(it);
      }
      for (std::size_t a = 0; a < n; ++a) {
        if (!m.present(f, a)) continue;
        auto [it, added] = record.active.try_emplace(m.ids[a]);
        if (added) {
          if (free.empty()) free.insert(record.slots++);
          it->second.slot = *free.begin();
          free.erase(free.begin());
          it->second.radius = m.radii[a];
        }
        slot_of[f][a] = it->second.slot;
      }
    }
    for (std::size_t a = 0; a < n; ++a) {
      if (const auto it = record.active.find(m.ids[a]); it != record.active.end()) it->second.last_pieces = std::move(listed[a]);
    }
    const std::uint64_t S = record.slots, T = record.frames + F;
    std::vector<double> pos(F * S * 3, absent), ori(F * S * 4, absent);
    std::vector<std::int32_t> act(F * S, -1);
    std::vector<std::int64_t> ids(F * S, -1), steps(F);
    for (std::size_t f = 0; f < F; ++f) {
      steps[f] = static_cast<std::int64_t>(record.frames + f);
      for (std::size_t a = 0; a < n; ++a) {
        const std::uint64_t s = slot_of[f][a];
        if (s == UINT64_MAX) continue;
        const std::size_t e = f * S + s;
        std::copy_n(m.positions.data() + m.index(f, a), 3, pos.data() + 3 * e);
        if (!m.orientations.empty()) std::copy_n(m.orientations.data() + (f * n + a) * 4, 4, ori.data() + 4 * e);
        if (!m.actions.empty()) act[e] = m.action(f, a);
        ids[e] = m.ids[a];
      }
    }
    const std::uint64_t t0 = record.frames;
    position->resize({T, S, 3});
    position->write({t0, 0, 0}, {F, S, 3}, pos.data());
    orientation->resize({T, S, 4});
    orientation->write({t0, 0, 0}, {F, S, 4}, ori.data());
    action->resize({T, S});
    action->write({t0, 0}, {F, S}, act.data());
    species->resize({S});
    id->resize({T, S});
    id->write({t0, 0}, {F, S}, ids.data());
    step->append(F, steps.data());
    time->append(F, m.times.data());
    if (edges) {
      const Region& r = *setup.environment->scene.region;
      const std::array<double, 9> side = detail::box_edges_frame(r);
      std::vector<double> edge_rows;
      for (std::size_t f = 0; f < F; ++f) edge_rows.insert(edge_rows.end(), side.begin(), side.end());
      edges->append(F, edge_rows.data());
    }
    record.frames = T;
    const std::vector<std::int32_t> new_species(new_ids.size(), 0);
    agent_id->append(new_ids.size(), new_ids.data());
    agent_radius->append(new_radii.size(), new_radii.data());
    agent_species->append(new_species.size(), new_species.data());
    record.agents += new_ids.size();

    std::vector<double> measured;
    for (std::size_t k = 0; k < w.density.areas.size(); ++k) {
      const AreaDensity& d = w.density.areas[k];
      measured.insert(measured.end(), {w.density.t0, w.density.t1, static_cast<double>(k), d.target, d.mean, d.lowest, d.highest});
      if (d.target > 0) {
        record.density_worst = std::max(record.density_worst, std::abs(d.error()));
        record.density_met = record.density_met && std::abs(d.error()) <= setup.density_tolerance;
      }
    }
    density->append(measured.size() / 7, measured.data());
    record.density_rows += measured.size() / 7;
  }

  // Everything fixed for the run, and the growing datasets, empty.
  void create() {
    const h5::Group root = file.root();
    const Environment& env = *setup.environment;
    const h5::Group parameters = detail::write_crowd_header(root, setup.provenance, laid_scene(env, LayoutOptions{}));
    create_all();
    const h5::Group trajectory = root.open_group("particles/trajectory");
    trajectory.open_group("position").set_attribute_on("time", "unit", "s");
    for (const char* element : {"orientation", "action", "id"}) {
      const h5::Group g = trajectory.open_group(element);
      g.link("step", "/particles/trajectory/position/step");
      g.link("time", "/particles/trajectory/position/time");
    }
    detail::write_orientation_attributes(trajectory.open_group("orientation"));
    detail::write_action_attributes(trajectory.open_group("action"), patch_actions(*setup.library).table);
    const h5::Group box = trajectory.has_group("box") ? trajectory.open_group("box") : trajectory.create_group("box");
    detail::write_box_attributes(box, env.scene);
    if (edges) {
      const h5::Group e = box.open_group("edges");
      e.link("step", "/particles/trajectory/position/step");
      e.link("time", "/particles/trajectory/position/time");
    }
    const h5::Group tiling = parameters.open_group("tiling");
    tiling::write_library(tiling, *setup.library);
    tiling::write_tile_settings(tiling, env, LayoutOptions{}, setup.check);
    file.flush();
  }

  void append(const WindowOutput& out) {
    append_instances(out);
    for (const FrameWindow& w : out.frames) append_frames(w);
    const WindowReport& r = out.report;
    const std::array<double, 7> row{r.t0, r.t1, r.freeze, static_cast<double>(r.carried_in), static_cast<double>(r.instances),
                                    static_cast<double>(r.carried_out), static_cast<double>(r.dangling)};
    windows->append(1, row.data());
    ++record.windows;
    record.lost_dangling = out.lost_dangling;
    file.flush();
  }
};

TilingStreamWriter::TilingStreamWriter(const std::filesystem::path& path, const std::string& display_name,
                                       const TilingStreamSetup& setup)
    : impl_(std::make_unique<Impl>(h5::File::create(path, display_name), display_name, setup)) {
  impl_->create();
}

TilingStreamWriter::TilingStreamWriter(const std::filesystem::path& path, const std::string& display_name,
                                       const TilingStreamSetup& setup, const TilingStreamRecord& record)
    : impl_(std::make_unique<Impl>(h5::File::open_for_update(path, display_name), display_name, setup)) {
  impl_->record = record;
  impl_->reopen_all();
  impl_->file.flush();
}

TilingStreamWriter::~TilingStreamWriter() = default;

void TilingStreamWriter::append(const WindowOutput& out) { impl_->append(out); }

const TilingStreamRecord& TilingStreamWriter::record() const noexcept { return impl_->record; }

void TilingStreamWriter::finish(const WindowedSummary& summary) {
  const h5::Group tiling = impl_->file.root().open_group("parameters/throng/tiling");
  ReportRecord fields(tiling);
  describe(fields, summary);
  impl_->file.close();
}

}  // namespace throng
