// Windowed tiling: a long horizon tiled window by window (the paper's advancing horizon, §5.3 "Interactive
// Control", applied to the whole tiler), with each window's frames handed to the caller as soon as they are final.
//
// The horizon [t0, t1] of the region is cut into windows of `window_s` (the last may be shorter). Window k tiles
// [t_k, t_k+1 + L], L the look-ahead: its chains start from the instances carried over from window k − 1, phase 1
// draws middle times in [t_k, t_k+1 + L], phase 2 closes the ends that now dangle (the exits beyond the previous
// window's reach, free when it was tiled) and the density rounds hold the density per area in those bins. The
// region rule of window k is the region with t1 = t_k+1 + L: ends beyond it are left for later windows. What
// lies after t_k+1 is provisional: window k + 1 continues it and may change it as it changes the patches on its
// seam. (Without the look-ahead, the start of each window would be short of characters: a character in the
// middle of the region at t_k+1 came in from a side well before, when the window that could still add it no
// longer sampled that time.)
//
// Earlier windows are fixed except the patches that touch the seam: carried instances that end at or before t_k
// are `fixed` (never deformed, never removed), those that end after it may be removed, and deform when a new
// patch is stitched to them. Nothing may change before the window's freeze time b_k, the earliest start of a
// patch that may still change (at most t_k − the longest half patch): no new or re-deformed sample lies before
// it (the stitcher refuses it), so whatever ends before b_k is final. After window k:
//   - instances that end at or before t_k+1 (all of them after the last window) are final: they get their ids in
//     the delivered tiling (in order of start time, end time, type, placement), and are delivered with the
//     connections into their entries;
//   - the frames of every time window j with t_j+1 ≤ b_k+1 are final and delivered (all of them after the last
//     window): usually window k − 1's, one window behind the tiling;
//   - what window k + 1 needs is carried: every instance that ends at or after b_k+1. Links to instances left
//     behind are kept by their delivered ids. That, the frame stream's open characters and a few counters are the
//     whole resumable state (WindowedTiler::state()), a few hundred instances: memory does not grow with the
//     horizon.
//
// Frames: as lay_out (characters.h) would make them from the whole delivered tiling with repeat 1 and the same
// max_facing_rate (one agent per maximal present piece of a chain, frames t0 + f / frame_rate_hz, the last at
// t1), streamed: agent ids are given
// in the order lay_out gives them (first frame, then the chain's head fragment copy, then the piece) and stay the
// same across windows. One difference: an agent's radius is the largest of the fragments it has walked up to the
// end of the delivered window, not of its whole chain (a character who picks up a box later widens then).
//
// Repeatable: window k's chain c draws from Rng(derive_seed(derive_seed(seed, k), c)) and starts from the carried
// state alone, so the same inputs give the same bits for any thread count, and a run resumed from the state after
// window k gives the same bits as one that went on. Runs on the calling rank only (a batch spreads shots over
// ranks): no MPI.
//
// Restrictions (ConfigError, before any work): a region periodic in time (a loop is one tile: tile() it), the
// total cap Options::characters (meaningless over an open horizon: use Options::density), keyframes (not carried
// yet: tile() takes them), window_s shorter than twice the longest patch.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/core/progress.h>
#include <throng/tiling/characters.h>
#include <throng/tiling/density.h>
#include <throng/tiling/options.h>
#include <throng/tiling/patch.h>
#include <throng/tiling/tile.h>
#include <throng/tiling/tiling.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace throng::tiling {

struct WindowOptions {
  double window_s = 60.0;
  double frame_rate_hz = 10.0;  ///< delivered frames
  double max_facing_rate_rad_s = LayoutOptions{}.max_facing_rate_rad_s;  ///< as lay_out's (characters.h)
  /// Seconds beyond its end a window tiles provisionally (see the file comment); negative: half the region's
  /// larger side walked at DensityOptions::projection_speed_mps plus the longest patch, at most a window.
  double lookahead_s = -1.0;
};

/// The frames of one time window [t0, t1) (the last window includes t1).
struct FrameWindow {
  std::size_t index = 0;
  double t0 = 0;
  double t1 = 0;
  std::size_t first_frame = 0;  ///< index of frames.times[0] among all frames of the run
  /// The window's frames; its agents are those present in at least one of them, by id (ids stable across
  /// windows, 0, 1, ... in order of appearance).
  CrowdMotion frames;
  std::vector<std::vector<AgentPiece>> pieces;  ///< per agent: the fragment copies it walks in this window
  DensityWindow density;                        ///< measured on the final tiling (empty areas without a density)
};

/// What one tiled window did.
struct WindowReport {
  std::size_t index = 0;
  double t0 = 0;
  double t1 = 0;
  double freeze = 0;              ///< nothing before this time could change in this window
  std::vector<ChainReport> chains;
  std::size_t best_chain = 0;
  std::size_t dangling = 0;       ///< ends dangling in the kept chain at the end of the window
  std::size_t carried_in = 0;     ///< instances the window started from
  std::size_t instances = 0;      ///< instances of the kept chain (carried ones included)
  std::size_t carried_out = 0;    ///< instances carried to the next window
  double seconds = 0;             ///< wall time of the window
};

/// Everything a window makes final.
struct WindowOutput {
  WindowReport report;
  /// Instances that became final, with ids first_instance, first_instance + 1, ...; the connections into their
  /// entries (instances named by delivered ids: from an earlier delivery or this one).
  std::size_t first_instance = 0;
  std::vector<Instance> instances;
  std::vector<Connection> connections;
  /// Dangling ends that can no longer be connected (they lie before the next window's freeze time), over the
  /// run so far: 0 at the end means the delivered tiling is perfect.
  std::size_t lost_dangling = 0;
  std::vector<FrameWindow> frames;  ///< the time windows whose frames became final (usually one)
};

class WindowedTiler {
 public:
  /// Checks everything (ConfigError, InputError, NumericalError as tile() does, plus the restrictions above)
  /// and precomputes the patch systems; tiles nothing yet. The library and environment are copied.
  WindowedTiler(const PatchLibrary& library, const Environment& environment, const Options& options,
                const WindowOptions& window);
  /// The same, resumed from a state() taken after some window of a run with the same inputs. InputError for
  /// bytes that are not such a state or that were made with other inputs (a fingerprint of the library, region,
  /// obstacles, window, frame rate, density and seed).
  WindowedTiler(const PatchLibrary& library, const Environment& environment, const Options& options,
                const WindowOptions& window, const std::vector<std::byte>& state);
  ~WindowedTiler();
  WindowedTiler(const WindowedTiler&) = delete;
  WindowedTiler& operator=(const WindowedTiler&) = delete;

  [[nodiscard]] std::size_t windows() const noexcept;      ///< windows of the horizon
  [[nodiscard]] std::size_t next_window() const noexcept;  ///< the window next() tiles
  [[nodiscard]] bool done() const noexcept { return next_window() == windows(); }

  /// Tiles the next window and returns what became final. Progress covers this window. Throws std::logic_error
  /// when done().
  WindowOutput next(Progress& progress);

  /// The state to resume from after the last complete window (small: the carried instances, the open
  /// characters, counters), as bytes in host order (same-architecture, like the MPI layer).
  [[nodiscard]] std::vector<std::byte> state() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Runs every remaining window, calling `on_window` with each output as soon as it is final (and the tiler, whose
/// state() is then the state after that window). Returns the number of dangling ends left (0: perfect).
std::size_t tile_windows(WindowedTiler& tiler, const std::function<void(const WindowOutput&, const WindowedTiler&)>& on_window,
                         Progress& progress);

}  // namespace throng::tiling
