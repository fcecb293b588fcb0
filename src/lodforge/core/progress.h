#pragma once
/// Progress of long work. The library reports it through a ProgressCallback
/// (an option of the long operations: LodOptions, McBuildOptions,
/// CompareOptions, MeasuredSimplifyOptions) and never draws; the command
/// connects the callback to a Progress, which draws a bar on a terminal:
///
///     scene.wrl: shapes [##########..........]  52 % 3.2 s left
///
/// redrawn in place, at most every `interval`, nothing at all for work that
/// ends within `delay`, and cleared at the end so what follows starts on a
/// clean line.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>

namespace lodforge {

/// `done` of `total` units of the named stage ("shapes", "signs", "A to B")
/// are done. A stage's calls may come from several threads at once; a new
/// stage is reported only after the previous stage's calls have returned.
/// Implementations must be cheap: they are called every few thousand units.
using ProgressCallback =
    std::function<void(std::string_view stage, std::uint64_t done, std::uint64_t total)>;

/// Counts the units of one stage done by worker threads and reports them to
/// a callback about every `step` units (and once at 0 when made, which
/// announces the stage). An empty callback makes add() a no-op.
class ProgressCounter {
 public:
  ProgressCounter(const ProgressCallback& callback, std::string_view stage, std::uint64_t total,
                  std::uint64_t step = 4096);
  /// Adds `n` done units; thread-safe.
  void add(std::uint64_t n);

 private:
  const ProgressCallback& callback_;
  std::string_view stage_;
  std::uint64_t total_, step_;
  std::atomic<std::uint64_t> done_{0};
};

struct ProgressOptions {
  std::FILE* out = nullptr;  ///< where to draw; nullptr: nowhere
  /// Whether `out` is a terminal: a bar is drawn only there (the command sets
  /// it from isatty, a test forces it).
  bool terminal = false;
  bool quiet = false;  ///< the user asked for quiet: draw nothing
  double delay = 0.5;  ///< seconds: work that ends sooner draws nothing
  /// Seconds between two drawings at least; 0: every update draws (and no
  /// thread redraws).
  double interval = 0.1;
  /// Width of the line in columns; 0: the terminal's (80 when unknown). The
  /// line stays one column short of it, so it never wraps.
  int columns = 0;
};

/// Options for a bar on standard error: terminal when stderr is one.
ProgressOptions stderr_progress(bool quiet);

/// A progress bar for one piece of work (optionally in stages). update() is
/// thread-safe and cheap: an atomic maximum, and a drawing only when the lock
/// is free and `interval` has passed. While enabled (and `interval` > 0), a
/// thread of its own redraws what changed since the last drawing every
/// `interval` (the last count of a stage, the first bar of work that
/// reports late). The
/// destructor clears the line.
class Progress {
 public:
  /// `label` starts the line; `total` units (0: unknown until a stage gives it).
  Progress(std::string label, std::uint64_t total, const ProgressOptions& options);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// `done` units of the current stage are done (a smaller value than one
  /// seen before is ignored, so threads may report out of order).
  void update(std::uint64_t done);
  /// The same within the named stage of `total` units: a new name starts
  /// the bar over from 0 and is shown after the label.
  void update(std::string_view stage, std::uint64_t done, std::uint64_t total);
  /// A callback that updates this bar (for the library's options).
  ProgressCallback callback();
  /// Clears the line if a bar is drawn, so that the caller can print a line
  /// of its own; the bar is drawn again by an update after `interval`.
  void clear();
  /// Clears the line if a bar was drawn; later updates draw nothing.
  void finish();
  /// Whether anything was drawn.
  bool drawn() const { return drawn_; }

 private:
  using Clock = std::chrono::steady_clock;
  void raise(std::uint64_t done);
  void draw_if_due(bool only_changes);  // with mutex_ held
  void draw(Clock::time_point now);
  void tick();

  std::string label_, stage_;
  ProgressOptions options_;
  bool enabled_;
  std::mutex mutex_;  // guards everything below but the atomics
  std::atomic<std::uint64_t> done_{0};
  std::atomic<std::uint64_t> total_;
  Clock::time_point start_, stage_start_, last_draw_;
  std::atomic<bool> drawn_{false};
  bool finished_ = false;
  bool held_ = false;  // cleared by clear(): no drawing for an interval, none by the ticker until
                       // the count moves
  int last_percent_ = -1;
  std::uint64_t drawn_done_ = 0, drawn_total_ = 0;  // what the last drawing showed
  std::condition_variable wake_;
  std::thread ticker_;
};

}  // namespace lodforge
