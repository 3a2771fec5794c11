// engine_args.h — the example engines' command line: switches (`--json`), options with a value
// (`--size WxH`) and positional words, every problem one message naming the word ("unknown
// argument --x", "--size needs a value", what an option's own check says). Each example lists
// its flags with CommandLine; the two AA engines and the two Ptex engines add the flags they
// share through aa_report.h and ptex_report.h. Header-only, like engine_context.h.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace engine {

class CommandLine {
 public:
  /// `name` alone sets `*on`.
  void flag(std::string name, bool* on) { flags_.emplace_back(std::move(name), on); }

  /// `name VALUE` calls `set(VALUE)`, which returns "" or the problem.
  void option(std::string name, std::function<std::string(const std::string&)> set) {
    options_.emplace_back(std::move(name), std::move(set));
  }

  /// Reads argv[1 ..]; words that do not start with '-' go to `positional` (unknown arguments
  /// when it is null). "" or the first problem.
  std::string parse(int argc, char** argv, std::vector<std::string>* positional = nullptr) const {
    for (int i = 1; i < argc; ++i) {
      const std::string k = argv[i];
      if (bool* on = find_flag(k)) {
        *on = true;
      } else if (const auto* set = find_option(k)) {
        if (i + 1 >= argc) return k + " needs a value";
        if (std::string why = (*set)(argv[++i]); !why.empty()) return why;
      } else if (positional != nullptr && (k.empty() || k[0] != '-')) {
        positional->push_back(k);
      } else {
        return "unknown argument " + k;
      }
    }
    return "";
  }

 private:
  bool* find_flag(const std::string& k) const {
    for (const auto& [name, on] : flags_) {
      if (name == k) return on;
    }
    return nullptr;
  }
  const std::function<std::string(const std::string&)>* find_option(const std::string& k) const {
    for (const auto& [name, set] : options_) {
      if (name == k) return &set;
    }
    return nullptr;
  }

  std::vector<std::pair<std::string, bool*>> flags_;
  std::vector<std::pair<std::string, std::function<std::string(const std::string&)>>> options_;
};

/// An option's integer in [lo, hi] into `to` ("FLAG V: expected LO..HI" otherwise).
inline std::function<std::string(const std::string&)> count_option(const char* flag, int lo, int hi,
                                                                   int& to) {
  return [flag, lo, hi, &to](const std::string& v) -> std::string {
    to = std::atoi(v.c_str());
    return to < lo || to > hi ? std::string(flag) + " " + v + ": expected " + std::to_string(lo) +
                                    ".." + std::to_string(hi)
                              : "";
  };
}

/// The frame-loop flags both Vulkan engines take: --frame-loop N, --frames-in-flight F,
/// --views V, --window.
struct FrameLoopArgs {
  int frame_loop = 0;  ///< Frames of the frame loop; 0: the engine's single-frame mode.
  int frames_in_flight = 2, views = 2;
  bool window = false;  ///< Present view 0 of the frame loop in a GLFW window.
};
/// --frames-in-flight takes `min_in_flight`..`max_in_flight`.
inline void add_frame_loop_flags(CommandLine& cl, FrameLoopArgs& a, int min_in_flight,
                                 int max_in_flight) {
  cl.option("--frame-loop", count_option("--frame-loop", 1, 100000, a.frame_loop));
  cl.option("--frames-in-flight",
            count_option("--frames-in-flight", min_in_flight, max_in_flight, a.frames_in_flight));
  cl.option("--views", count_option("--views", 1, 16, a.views));
  cl.flag("--window", &a.window);
}

/// `WxH` into `w`, `h`; false unless two positive integers.
inline bool parse_size(const std::string& v, int& w, int& h) {
  return std::sscanf(v.c_str(), "%dx%d", &w, &h) == 2 && w > 0 && h > 0;
}

}  // namespace engine
