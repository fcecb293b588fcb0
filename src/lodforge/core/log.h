#pragma once
/// Messages from the library to whoever runs it. The library never prints:
/// it reports into a Log, and apps/ decides what to show (categories and
/// levels are selectable on the command line, as in the original tool).
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace lodforge {

enum class LogLevel { kMessage, kWarning, kError, kInternal };
enum class LogCategory {
  kGeneral,
  kParse,
  kCoord,
  kMaterial,
  kNormal,
  kTexCoord,
  kFace,
  kLine,
  kJoin,
  kTriangulator,
};

struct Diagnostic {
  LogLevel level = LogLevel::kMessage;
  LogCategory category = LogCategory::kGeneral;
  std::string text;
};

std::string_view to_string(LogLevel level);
std::string_view to_string(LogCategory category);
/// Parses a category name as used on the command line ("coord", "material", ...).
/// Returns false if the name is not a category.
bool parse_category(std::string_view name, LogCategory& out);

/// Collects diagnostics; optionally forwards each one to a sink as it arrives.
/// Thread-compatible, not thread-safe: give each worker its own Log and merge.
class Log {
 public:
  std::function<void(const Diagnostic&)> sink;

  void add(LogLevel level, LogCategory category, std::string text);
  void warn(LogCategory category, std::string text) {
    add(LogLevel::kWarning, category, std::move(text));
  }
  void info(LogCategory category, std::string text) {
    add(LogLevel::kMessage, category, std::move(text));
  }
  void merge(const Log& other);
  const std::vector<Diagnostic>& entries() const { return entries_; }
  std::size_t count(LogLevel level) const;

 private:
  std::vector<Diagnostic> entries_;
};

}  // namespace lodforge
