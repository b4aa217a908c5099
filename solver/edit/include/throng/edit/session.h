// An editing session: one input crowd and one job's options, then many requests (pins, drags, constraints), each
// answered as `throng edit` would answer it alone, with the editor (its graph and factorisations) kept from one
// request to the next: `throng edit --session` (docs/commands/edit.md, "Session"), a DCC plugin's drag loop.
//
// Reuse. The editor's samples are decided by the request it was built for (edit.h: every frame a request names
// becomes a sample), so a request is answered by
//   reused        the kept editor: the same samples and the same handled vertices, so back-substitutions only
//                 (a new grouping of the handles into pins and drags, or new constraint rows, adds pin-basis or
//                 Schur columns on the kept factorisation, never a refactorisation);
//   refactorised  the kept editor with its systems factorised again: the same samples, other handled vertices
//                 (a local edit: a region not in its cache);
//   built         a new editor: the first request, or one whose frames make another set of samples (or the one
//                 after a request the solver refused: an editor that failed half-way is not trusted).
// Bit identity. Every answer is the Run that run() (runner.h) gives for the job with that request alone, bit for
// bit (positions, velocities, facing, the report's numbers; not its wall times): an editor built for a request
// with the same samples and handles holds the same graph and the same factorisation, and the direct method's
// solves depend only on them (linalg least_squares.h: "the same calls give the same bits"). Two methods keep
// state between solves and so are not bit-identical across a session: the iterative method starts step 2 from
// the previous drags' solutions (iterative_steps.h), and the petsc backend starts its Krylov solves from the
// previous solution; their answers are within solver.position_tolerance (iterative) or solver.relative_tolerance
// (petsc) of a one-shot edit. Session::bit_identical() says which.
// Previews. preview() is edit() stopped after the solve: the same editor, the same reuse rules and the same solve,
// so its sample positions are the ones edit() resamples for the same request, bit for bit (samples() after an
// edit() gives them); it skips what edit() does after the solve on the whole crowd (resampling every frame,
// putting the clip back, the guard, the residual at the written frames), which costs as much as the solve or more.
#pragma once

#include <throng/core/crowd.h>
#include <throng/edit/runner.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace throng::edit {

/// What answering one request did with the editor (see above).
enum class EditorUse { built, refactorised, reused };

/// "built", "refactorised", "reused": the session protocol's words.
[[nodiscard]] const char* use_name(EditorUse use) noexcept;

/// The edited samples of an answer: what a plugin draws while the user drags.
struct Samples {
  std::vector<std::size_t> frames;  ///< #samples source frames, increasing (the editor's clip)
  std::vector<std::int64_t> ids;    ///< #agents agent ids, in the clip's order
  /// #samples·#agents by 2 (metres): row i·#agents + j is agent ids[j] at frames[i] (Clip::vertex)
  Eigen::Matrix<double, Eigen::Dynamic, 2> positions;
  /// The largest distance of an edited sample from the input's position there (metres), and where.
  double max_displacement_m = 0;
  std::size_t max_displacement_frame = 0;
  std::int64_t max_displacement_id = 0;
};

/// A preview answer: the solve's samples and the editor's report (sizes, solve timings, the residual of the
/// general constraints at the samples: max_constraint_residual; max_output_residual is not measured).
struct Preview {
  Samples samples;
  Report report;
};

class Session {
 public:
  /// `input` must outlive the session. The job's options, clip_only and guard hold for every request; its
  /// request is not edited (each edit() brings its own). Throws ConfigError for options out of range.
  Session(const Crowd& input, const Job& job, int ranks = 1);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  /// The job with `request` edited, as run() would give it (see "Bit identity"), reusing the editor where the
  /// request allows. Throws as run() does (ConfigError for a request that does not fit the crowd, naming
  /// pins[k], drags[k] or constraints[k]; NumericalError for a singular system or contradictory constraints);
  /// after a NumericalError the next request builds a new editor, after a ConfigError the editor is kept.
  [[nodiscard]] Run edit(const Request& request);

  /// The request solved as edit() solves it (the same editor use, see "Reuse"; the same errors and the same
  /// recovery after them), without what follows the solve: the sample positions edit() would resample, bit for bit
  /// (see "Previews"), and the editor's report.
  [[nodiscard]] Preview preview(const Request& request);

  /// The samples of the last request solved (by edit(), preview() or prepare()), copied from the kept editor.
  /// Throws std::logic_error when none was solved since the session started or the last request failed.
  [[nodiscard]] Samples samples() const;

  /// Makes the kept editor ready for requests with the samples and handles of `request` (built, factorised and
  /// solved once, as edit() would, but without the answer's resampling, putting back and guard), so that the next
  /// edit() of a drag of the same handles is `reused`: a plugin calls it when the user picks the handles, before
  /// the first drag. Returns what it did with the editor. Throws as edit() does.
  EditorUse prepare(const Request& request);

  /// What the last edit() or prepare() did with the editor (built before the first).
  [[nodiscard]] EditorUse last_use() const noexcept;
  /// Whether answers equal one-shot edits bit for bit: the direct method on the eigen backend (see above).
  [[nodiscard]] bool bit_identical() const noexcept;
  /// The options every request is edited with.
  [[nodiscard]] const Job& job() const noexcept;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// The second half of run(): puts the edited clip `result` (edit_group_motion's, for `input`.motion and
/// job.request) into the written crowd (the whole crowd or the clip alone), warns as run() does, guards it and
/// measures the request on the written frames. run() is edit_group_motion followed by this; Session calls it
/// with its kept editor's result. `ranks` is what the report says.
[[nodiscard]] Run finish_edit(const Crowd& input, const Job& job, Result result, int ranks);

}  // namespace throng::edit
