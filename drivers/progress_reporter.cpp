#include "progress_reporter.h"

#include <algorithm>
#include <cstdio>

namespace throng::cli {

ProgressReporter::ProgressReporter(bool terminal) : terminal_(terminal) {}

ProgressReporter::~ProgressReporter() {
  if (terminal_ && drawn_) std::fputs("\n", stderr);
}

void ProgressReporter::update(double fraction, std::string_view stage) {
  fraction = std::clamp(fraction, 0.0, 1.0);
  const auto now = std::chrono::steady_clock::now();
  const bool new_stage = stage != last_stage_;
  const bool step = fraction - last_fraction_ >= 0.01 || (fraction == 1.0 && last_fraction_ < 1.0);
  const bool due = now - last_time_ >= std::chrono::milliseconds(250);
  if (!new_stage && !(step && due) && !(fraction == 1.0 && last_fraction_ < 1.0)) return;
  if (terminal_) {
    constexpr int width = 30;
    const int filled = static_cast<int>(fraction * width + 0.5);
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(width, '.');
    std::fprintf(stderr, "\r[%s] %5.1f%% %-40.40s", bar.c_str(), 100.0 * fraction, std::string(stage).c_str());
    drawn_ = true;
  } else {
    std::fprintf(stderr, "PROGRESS %.1f%% %s\n", 100.0 * fraction, std::string(stage).c_str());
  }
  std::fflush(stderr);
  last_fraction_ = fraction;
  last_stage_ = stage;
  last_time_ = now;
}

}  // namespace throng::cli
