#pragma once
// Records what a library operation reports through its ProgressCallback
// (core/progress.h), from any thread.
#include <algorithm>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "lodforge/core/progress.h"

namespace lodforge::test {

class ProgressRecorder {
 public:
  ProgressCallback callback() {
    return [this](std::string_view stage, std::uint64_t done, std::uint64_t total) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (stages_.empty() || stages_.back() != stage) stages_.emplace_back(stage);
      Seen& s = seen_[std::string(stage)];
      s.done = std::max(s.done, done);
      s.total = total;
      s.beyond = s.beyond || done > total;
      ++s.calls;
    };
  }
  /// The stages in the order they began (a stage again after another: twice).
  const std::vector<std::string>& stages() const { return stages_; }
  /// Whether the stage reported all its units (and never more than its total).
  bool completed(const std::string& stage) const {
    auto it = seen_.find(stage);
    return it != seen_.end() && !it->second.beyond && it->second.done == it->second.total;
  }
  std::size_t calls(const std::string& stage) const {
    auto it = seen_.find(stage);
    return it == seen_.end() ? 0 : it->second.calls;
  }

 private:
  struct Seen {
    std::uint64_t done = 0, total = 0;
    std::size_t calls = 0;
    bool beyond = false;
  };
  std::mutex mutex_;
  std::vector<std::string> stages_;
  std::map<std::string, Seen> seen_;
};

}  // namespace lodforge::test
