// Progress reporting from long-running solvers to whoever drives them (a terminal bar, PROGRESS lines, nothing).
#pragma once

#include <string_view>

namespace throng {

/// Receives progress from a solver. Called from the thread that called the solver, never from workers.
class Progress {
 public:
  virtual ~Progress() = default;
  /// `fraction` in [0, 1], non-decreasing within a stage; `stage` names what is being done.
  virtual void update(double fraction, std::string_view stage) = 0;
};

/// Reports nothing.
class NoProgress final : public Progress {
 public:
  void update(double, std::string_view) override {}
};

}  // namespace throng
