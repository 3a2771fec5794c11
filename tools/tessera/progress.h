// The one-line progress bar of `tessera compress` on a terminal (stderr): a bar, a count
// ("3/10 files" or "42%"), MPixel/s and the time left, redrawn at most 10 times a second.
#pragma once

#include <chrono>
#include <string>

namespace tessera::cli {

class ProgressBar {
 public:
  /// `enabled`: draw at all (callers pass whether stderr is a terminal and the run is neither
  /// quiet nor printing JSON). Nothing is drawn before `delay_s` seconds have passed since
  /// construction, so short runs leave no trace; $TESSERA_PROGRESS_DELAY (seconds) overrides it.
  explicit ProgressBar(bool enabled, double delay_s = 0.0);
  ~ProgressBar() { clear(); }
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  /// Redraws with `fraction` (0 to 1) done, `count` as the count text ("" = the percentage) and
  /// `mpixels` megapixels done so far (for the rate); the time left is the elapsed time scaled
  /// by what is left. Skipped when disabled, too early, or within 0.1 s of the last drawing
  /// (except `fraction` 1, the last state).
  void update(double fraction, const std::string& count, double mpixels);
  /// Erases the line, if one was drawn (before printing anything else on stderr or stdout).
  void clear();
  /// Seconds since construction.
  double seconds() const;

 private:
  bool enabled_;
  double delay_s_;
  bool drawn_ = false;
  double last_draw_s_ = -1.0;
  std::chrono::steady_clock::time_point t0_;
};

}  // namespace tessera::cli
