#include "progress.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

namespace tessera::cli {

ProgressBar::ProgressBar(bool enabled, double delay_s)
    : enabled_(enabled), delay_s_(delay_s), t0_(std::chrono::steady_clock::now()) {
  // TESSERA_PROGRESS_DELAY (seconds) replaces the delay: 0 draws from the start (how the tests
  // check where a bar may and may not appear without depending on how long an encode takes).
  if (const char* env = std::getenv("TESSERA_PROGRESS_DELAY"); env && *env) {
    char* end = nullptr;
    const double v = std::strtod(env, &end);
    if (end && *end == '\0' && v >= 0) delay_s_ = v;
  }
}

double ProgressBar::seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
}

void ProgressBar::update(double fraction, const std::string& count, double mpixels) {
  if (!enabled_) return;
  const double s = seconds();
  // The last state (fraction 1) is always drawn once the delay has passed, so a bar that was
  // shown ends full.
  if (s < delay_s_ || (last_draw_s_ >= 0 && s - last_draw_s_ < 0.1 && fraction < 1.0)) return;
  last_draw_s_ = s;
  fraction = std::clamp(fraction, 0.0, 1.0);
  constexpr int kWidth = 28;
  std::string bar(std::size_t(kWidth * fraction), '=');
  bar.resize(kWidth, ' ');
  const double rate = s > 0 ? mpixels / s : 0;
  const double eta = fraction > 0 ? s * (1.0 - fraction) / fraction : 0;
  const std::string shown = count.empty() ? std::to_string(int(fraction * 100.0)) + "%" : count;
  std::fprintf(stderr, "\r[%s] %s  %.1f MPixel/s  ETA %d:%02d ", bar.c_str(), shown.c_str(), rate,
               int(eta) / 60, int(eta) % 60);
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressBar::clear() {
  if (!drawn_) return;
  std::fprintf(stderr, "\r\033[K");
  std::fflush(stderr);
  drawn_ = false;
  last_draw_s_ = -1.0;
}

}  // namespace tessera::cli
