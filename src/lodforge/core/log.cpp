#include "lodforge/core/log.h"

#include <algorithm>
#include <array>
#include <utility>

namespace lodforge {
namespace {
constexpr std::array<std::string_view, 10> kCategoryNames = {
    "general",  "parse", "coord", "material", "normal",
    "texcoord", "face",  "line",  "join",     "triangulator"};
}  // namespace

std::string_view to_string(LogLevel level) {
  switch (level) {
    case LogLevel::kMessage:
      return "message";
    case LogLevel::kWarning:
      return "warning";
    case LogLevel::kError:
      return "error";
    case LogLevel::kInternal:
      return "internal";
  }
  return "?";
}

std::string_view to_string(LogCategory category) {
  return kCategoryNames[static_cast<std::size_t>(category)];
}

bool parse_category(std::string_view name, LogCategory& out) {
  auto it = std::find(kCategoryNames.begin(), kCategoryNames.end(), name);
  if (it == kCategoryNames.end()) return false;
  out = static_cast<LogCategory>(it - kCategoryNames.begin());
  return true;
}

void Log::add(LogLevel level, LogCategory category, std::string text) {
  entries_.push_back({level, category, std::move(text)});
  if (sink) sink(entries_.back());
}

void Log::merge(const Log& other) {
  for (const auto& d : other.entries()) add(d.level, d.category, d.text);
}

std::size_t Log::count(LogLevel level) const {
  return std::count_if(entries_.begin(), entries_.end(),
                       [level](const Diagnostic& d) { return d.level == level; });
}

}  // namespace lodforge
