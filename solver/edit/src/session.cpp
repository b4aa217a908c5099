#include "edit_result.h"
#include "request.h"

#include <throng/core/errors.h>
#include <throng/edit/local_edit.h>
#include <throng/edit/session.h>
#include <throng/graph/clip.h>

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <vector>

namespace throng::edit {

const char* use_name(EditorUse use) noexcept {
  switch (use) {
    case EditorUse::built: return "built";
    case EditorUse::refactorised: return "refactorised";
    case EditorUse::reused: return "reused";
  }
  return "built";
}

struct Session::State {
  State(const Crowd& in, const Job& j, int r) : input(in), job(j), ranks(r) {}

  const Crowd& input;
  Job job;
  int ranks = 1;
  Clip bounds;  // the clip without a request's frames: its regular samples (make_clip)
  // The kept editor (global or local, as job.options.local.parts says) and the sample frames it was built on.
  std::unique_ptr<Editor> global;
  std::unique_ptr<LocalEditor> local;
  std::vector<std::size_t> frames;
  EditorUse use = EditorUse::built;
  // The kept editor's result for the last request solved (null before the first and after a failed one).
  const Eigen::Matrix<double, Eigen::Dynamic, 2>* last = nullptr;

  [[nodiscard]] bool has_editor() const { return global || local; }
  [[nodiscard]] bool is_local() const { return job.options.local.parts > 0; }

  // The samples an editor built for `request` would have: the regular samples and the request's frames
  // (make_clip's rule), or a ConfigError naming the entry that does not fit (required_frames).
  [[nodiscard]] std::vector<std::size_t> samples_for(const Request& request) const {
    std::vector<std::size_t> out = required_frames(request, bounds, input.motion.ids);
    out.insert(out.end(), bounds.frames.begin(), bounds.frames.end());
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

  // What the kept editor has factorised so far: a deform that adds to it refactorised.
  [[nodiscard]] int factorised() const {
    if (global) return global->report().factorizations;
    if (local) return local->report().regions_built;
    return 0;
  }

  // Makes the kept editor fit `request` (see session.h) and deforms for it: the sample positions.
  const Eigen::Matrix<double, Eigen::Dynamic, 2>& solve(const Request& request) {
    last = nullptr;
    std::vector<std::size_t> wanted = samples_for(request);
    if (!has_editor() || wanted != frames) {
      // The new editor's graph first (a ConfigError there leaves the kept one), then the old one's memory is
      // given back before the new one factorises.
      std::unique_ptr<Editor> new_global;
      std::unique_ptr<LocalEditor> new_local;
      if (is_local()) {
        new_local = std::make_unique<LocalEditor>(input.motion, job.options, request);
      } else {
        new_global = std::make_unique<Editor>(input.motion, job.options, request);
      }
      global = std::move(new_global);
      local = std::move(new_local);
      frames = std::move(wanted);
      if (global) global->precompute();
      use = EditorUse::built;
    } else {
      use = EditorUse::reused;
    }
    const int before = factorised();
    const auto& samples = local ? local->deform(request) : global->deform(request);
    if (use == EditorUse::reused && factorised() > before) use = EditorUse::refactorised;
    last = &samples;
    return samples;
  }

  // The edited clip for `request`, as edit_group_motion gives it.
  Result deform(const Request& request) {
    const auto& samples = solve(request);
    Result result = local ? edit_result(*local, samples) : edit_result(*global, samples);
    result.report.max_output_residual = max_request_residual(input.motion, result.crowd, result.first_frame, request);
    return result;
  }

  // Runs `step`; after anything but a ConfigError (raised before the editor changes: the request's entries are
  // checked first) the kept editor is dropped, since a solver that failed half-way (a singular system,
  // contradictory constraints) may hold a half-applied request.
  template <class Step>
  auto guarded(Step&& step) -> decltype(step()) {
    try {
      return step();
    } catch (const ConfigError&) {
      throw;
    } catch (...) {
      global.reset();
      local.reset();
      frames.clear();
      last = nullptr;
      throw;
    }
  }
};

Session::Session(const Crowd& input, const Job& job, int ranks) : state_(std::make_unique<State>(input, job, ranks)) {
  validate(job.options);
  state_->bounds = make_clip(input.motion, job.options.clip);
}

Session::~Session() = default;

Run Session::edit(const Request& request) {
  State& s = *state_;
  Job job = s.job;
  job.request = request;
  Result result = s.guarded([&] { return s.deform(request); });
  return finish_edit(s.input, job, std::move(result), s.ranks);
}

Preview Session::preview(const Request& request) {
  State& s = *state_;
  s.guarded([&] { (void)s.solve(request); });
  return {samples(), s.local ? s.local->report() : s.global->report()};
}

Samples Session::samples() const {
  const State& s = *state_;
  if (s.last == nullptr) throw std::logic_error("Session::samples: no request solved (or the last one failed)");
  const Clip& clip = s.local ? s.local->graph().clip : s.global->graph().clip;
  Samples out{clip.frames, clip.ids, *s.last};
  if (out.positions.rows() > 0) {
    Eigen::Index row = 0;
    out.max_displacement_m = (out.positions - clip.positions).rowwise().norm().maxCoeff(&row);
    const std::size_t agents = clip.agent_count();
    out.max_displacement_frame = clip.frames[static_cast<std::size_t>(row) / agents];
    out.max_displacement_id = clip.ids[static_cast<std::size_t>(row) % agents];
  }
  return out;
}

EditorUse Session::prepare(const Request& request) {
  State& s = *state_;
  s.guarded([&] { (void)s.solve(request); });
  return s.use;
}

EditorUse Session::last_use() const noexcept { return state_->use; }

bool Session::bit_identical() const noexcept {
  const State& s = *state_;
  const Options& o = s.job.options;
  if (o.solver.backend != "eigen" || o.solver.method == "iterative") return false;
  if (o.solver.method == "direct" || s.is_local()) return true;
  return s.global == nullptr || s.global->report().method == "direct";  // auto: as the kept editor resolved it
}

const Job& Session::job() const noexcept { return state_->job; }

}  // namespace throng::edit
