// progress.h — the encoder's progress reports (`EncodeOptions::progress`).
//
// `encode` owns one `ProgressSink` (the caller's hook and the last fraction reported) and hands
// the passes `Progress` ranges of it: a pass that loops reports how far it got within its range
// (`at`), and a caller splits its range into parts by the passes' estimated costs
// (`ProgressSteps`). Every report is made between parallel sections, on the thread that called
// `encode`, and only reads the encoder's state, so the output is the same with or without a hook.
#pragma once

#include <algorithm>
#include <functional>

namespace tessera::pvrtc::detail {

/// The caller's hook and the last fraction reported: reports never go backwards or repeat (the
/// first one may be 0), and none is made without a hook.
class ProgressSink {
 public:
  explicit ProgressSink(const std::function<void(double)>& fn) : fn_(fn) {}
  bool active() const { return static_cast<bool>(fn_); }
  void report(double fraction) {
    if (!fn_) return;
    fraction = std::clamp(fraction, 0.0, 1.0);
    if (started_ && fraction <= last_) return;
    started_ = true;
    last_ = fraction;
    fn_(fraction);
  }

 private:
  const std::function<void(double)>& fn_;
  double last_ = 0;
  bool started_ = false;
};

/// A range [lo, hi] of one encode's progress; default-constructed, it reports nothing.
class Progress {
 public:
  Progress() = default;
  Progress(ProgressSink* sink, double lo, double hi) : sink_(sink), lo_(lo), hi_(hi) {}

  bool active() const { return sink_ != nullptr && sink_->active(); }
  /// Reports that `fraction` (clamped to [0, 1]) of this range is done.
  void at(double fraction) const {
    if (sink_) sink_->report(lo_ + (hi_ - lo_) * std::clamp(fraction, 0.0, 1.0));
  }
  /// The part [a, b] (fractions of this range).
  Progress part(double a, double b) const {
    return {sink_, lo_ + (hi_ - lo_) * a, lo_ + (hi_ - lo_) * b};
  }

 private:
  ProgressSink* sink_ = nullptr;
  double lo_ = 0, hi_ = 0;
};

/// Splits a range into consecutive parts by weight: `next(w)` is the next w / `total` of it
/// (and first reports the end of the part before, so a pass that stopped early jumps ahead).
class ProgressSteps {
 public:
  ProgressSteps(const Progress& whole, double total) : whole_(whole), total_(total) {}
  Progress next(double weight) {
    const double a = total_ > 0 ? done_ / total_ : 1.0;
    done_ += weight;
    const double b = total_ > 0 ? std::min(done_ / total_, 1.0) : 1.0;
    whole_.at(a);
    return whole_.part(a, b);
  }

 private:
  Progress whole_;
  double total_ = 0;
  double done_ = 0;
};

/// The fraction of an exact search to convergence that is done after a round that searched
/// `searched` blocks, the round before having searched `previous` (0 before the first round):
/// later rounds revisit only blocks next to changed ones, and their counts fall about
/// geometrically, so the work left is estimated as that series' tail.
inline double convergence_fraction(double done_blocks, double searched, double previous) {
  const double q = previous > 0 ? std::clamp(searched / previous, 0.0, 0.9) : 0.7;
  const double left = searched * q / (1.0 - q);
  return done_blocks + left > 0 ? done_blocks / (done_blocks + left) : 1.0;
}

}  // namespace tessera::pvrtc::detail
