// A one-line progress bar on stderr for the CLI's long steps (issue 17): "map [#####.....] 42% 1.3 s",
// redrawn in place at most every 100 ms. It is drawn only when stderr is a terminal, so pipes,
// logs and --json output never see carriage returns; --progress forces it on, --quiet off.
#pragma once

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <mutex>
#include <string>

#include "command/args.h"

namespace mcon::cli {

// --quiet wins over --progress; neither: on when stderr is a terminal.
inline bool progress_wanted(bool quiet, bool progress) {
  if (quiet) return false;
  return progress || isatty(fileno(stderr)) == 1;
}
inline bool progress_wanted(const ArgParser& p) { return progress_wanted(p.flag("quiet"), p.flag("progress")); }

class ProgressBar {
 public:
  ProgressBar(std::string label, bool enabled) : label_(std::move(label)), enabled_(enabled) {}
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;
  ~ProgressBar() { finish(); }

  // Records `fraction` (in [0, 1]; out-of-range values are clamped) and redraws when due. Safe
  // from any thread: library builds report from worker threads. Never cancels.
  bool update(double fraction) {
    if (!enabled_) return true;
    const std::lock_guard<std::mutex> lock(mutex_);
    if (finished_) return true;
    const int percent = static_cast<int>(std::floor(100.0 * std::clamp(fraction, 0.0, 1.0)));
    const auto now = std::chrono::steady_clock::now();
    // Redraw when the percentage moved and 100 ms passed, and always on reaching 100 %.
    const bool due = percent > percent_ && (percent == 100 || !drawn_ || now - last_draw_ >= std::chrono::milliseconds(100));
    if (!due) return true;
    percent_ = percent;
    last_draw_ = now;
    draw(now);
    return true;
  }

  // The callback the SDK's options take: progress over [begin, end] of this bar.
  std::function<bool(double)> callback(double begin = 0.0, double end = 1.0) {
    return [this, begin, end](double f) { return update(begin + (end - begin) * f); };
  }

  // A log line (stderr) above the bar: the bar is cleared, the line printed, the bar redrawn, so
  // commands that log per case keep both. Without a bar it is a plain line.
  void println(const std::string& line) {
    const std::lock_guard<std::mutex> lock(mutex_);
    const bool bar = enabled_ && drawn_ && !finished_;
    std::fprintf(stderr, "%s%s\n", bar ? "\r\033[K" : "", line.c_str());
    if (bar) draw(std::chrono::steady_clock::now());
    std::fflush(stderr);
  }

  // Ends the line (once); later updates are ignored. An error message printed afterwards starts
  // on its own line.
  void finish() {
    if (!enabled_) return;
    const std::lock_guard<std::mutex> lock(mutex_);
    if (finished_) return;
    finished_ = true;
    if (drawn_) std::fputc('\n', stderr);
    std::fflush(stderr);
  }

 private:
  void draw(std::chrono::steady_clock::time_point now) {
    constexpr int kWidth = 24;
    const int filled = percent_ * kWidth / 100;
    const double seconds = std::chrono::duration<double>(now - start_).count();
    std::fprintf(stderr, "\r%s [%s%s] %3d%% %.1f s", label_.c_str(), std::string(static_cast<std::size_t>(filled), '#').c_str(),
                 std::string(static_cast<std::size_t>(kWidth - filled), '.').c_str(), percent_, seconds);
    std::fflush(stderr);
    drawn_ = true;
  }

  std::string label_;
  bool enabled_;
  std::mutex mutex_;
  bool drawn_ = false, finished_ = false;
  int percent_ = -1;
  const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point last_draw_{};
};

}  // namespace mcon::cli
