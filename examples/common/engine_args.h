// engine_args.h — the example engines' command line: switches (`--json`), options with a value
// (`--size WxH`) and positional words, every problem one message naming the word ("unknown
// argument --x", "--size needs a value", what an option's own check says). Each example lists
// its flags with CommandLine; the two AA engines and the two Ptex engines add the flags they
// share through aa_report.h and ptex_report.h. Header-only, like engine_context.h.
#pragma once

#include <cstdio>
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

/// `WxH` into `w`, `h`; false unless two positive integers.
inline bool parse_size(const std::string& v, int& w, int& h) {
  return std::sscanf(v.c_str(), "%dx%d", &w, &h) == 2 && w > 0 && h > 0;
}

}  // namespace engine
