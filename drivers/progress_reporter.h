// Progress on stderr: a redrawn bar on a terminal; on a pipe, stable lines a farm manager can parse:
//   PROGRESS 37.5% stage name
// emitted when the stage changes or the fraction grows by ≥ 1 %, and at most 4 times a second otherwise.
#pragma once

#include <throng/core/progress.h>

#include <chrono>
#include <string>

namespace throng::cli {

class ProgressReporter final : public Progress {
 public:
  explicit ProgressReporter(bool terminal);
  ~ProgressReporter() override;
  void update(double fraction, std::string_view stage) override;

 private:
  bool terminal_;
  bool drawn_ = false;
  double last_fraction_ = -1;
  std::string last_stage_;
  std::chrono::steady_clock::time_point last_time_{};
};

}  // namespace throng::cli
