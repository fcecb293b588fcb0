// The progress bar of progress.h. Updates come from worker threads: the
// count is an atomic maximum, and the one thread that gets the lock draws
// (the others go on working), so a busy loop never waits on the terminal.
#include "lodforge/core/progress.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace lodforge {

ProgressCounter::ProgressCounter(const ProgressCallback& callback, std::string_view stage,
                                 std::uint64_t total, std::uint64_t step)
    : callback_(callback), stage_(stage), total_(total), step_(std::max<std::uint64_t>(step, 1)) {
  if (callback_) callback_(stage_, 0, total_);
}

void ProgressCounter::add(std::uint64_t n) {
  if (!callback_) return;
  const std::uint64_t before = done_.fetch_add(n, std::memory_order_relaxed), after = before + n;
  if (after / step_ != before / step_ || (before < total_ && after >= total_))
    callback_(stage_, after, total_);
}

ProgressOptions stderr_progress(bool quiet) {
  return {.out = stderr, .terminal = isatty(STDERR_FILENO) == 1, .quiet = quiet};
}

namespace {

// "3.2 s", "42 s", "3 min 12 s", "1 h 05 min".
std::string duration_text(double seconds) {
  if (seconds < 9.95) return fmt::format("{:.1f} s", seconds);
  const auto s = static_cast<long long>(std::lround(seconds));
  if (s < 60) return fmt::format("{} s", s);
  if (s < 3600) return fmt::format("{} min {:02} s", s / 60, s % 60);
  return fmt::format("{} h {:02} min", s / 3600, s % 3600 / 60);
}

int terminal_columns(std::FILE* out) {
  winsize ws{};
  if (ioctl(fileno(out), TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0) return ws.ws_col;
  return 80;
}

}  // namespace

Progress::Progress(std::string label, std::uint64_t total, const ProgressOptions& options)
    : label_(std::move(label)),
      options_(options),
      enabled_(options.out && options.terminal && !options.quiet),
      total_(total),
      start_(Clock::now()),
      stage_start_(start_) {
  if (enabled_ && options_.interval > 0) ticker_ = std::thread([this] { tick(); });
}

Progress::~Progress() {
  finish();
}

void Progress::raise(std::uint64_t done) {
  std::uint64_t seen = done_.load(std::memory_order_relaxed);
  while (done > seen && !done_.compare_exchange_weak(seen, done, std::memory_order_relaxed)) {
  }
}

void Progress::update(std::uint64_t done) {
  if (!enabled_) return;
  raise(done);
  std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
  if (lock) draw_if_due(false);
}

void Progress::update(std::string_view stage, std::uint64_t done, std::uint64_t total) {
  if (!enabled_) return;
  std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
  if (!lock) {
    // Another thread draws: a count of the current stage is kept for the
    // next drawing. (A new stage's first calls may be counted against the
    // stage before it, which only holds that bar up until a call gets the
    // lock and switches.)
    raise(done);
    return;
  }
  if (stage != stage_) {
    stage_ = stage;
    stage_start_ = Clock::now();
    done_.store(0, std::memory_order_relaxed);
    last_percent_ = -1;
    drawn_total_ = 0;  // the ticker draws the new name
  }
  total_.store(total, std::memory_order_relaxed);
  raise(done);
  draw_if_due(false);
}

ProgressCallback Progress::callback() {
  return [this](std::string_view stage, std::uint64_t done, std::uint64_t total) {
    update(stage, done, total);
  };
}

void Progress::clear() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (finished_) return;
  if (drawn_) {
    std::fputs("\r\033[K", options_.out);
    std::fflush(options_.out);
  }
  drawn_ = false;
  held_ = true;
  last_draw_ = Clock::now();
  // The counts so far count as shown, also when the bar was not drawn yet:
  // the ticker brings it back only for a later count, not over what the
  // caller prints next (the summary after the work, while nothing counts).
  drawn_done_ = done_.load(std::memory_order_relaxed);
  drawn_total_ = total_.load(std::memory_order_relaxed);
}

void Progress::finish() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (finished_) return;
    finished_ = true;
  }
  wake_.notify_all();
  if (ticker_.joinable()) ticker_.join();
  if (!drawn_) return;
  std::fputs("\r\033[K", options_.out);
  std::fflush(options_.out);
}

// The ticker: every interval, a drawing of what changed since the last one.
void Progress::tick() {
  const auto period =
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(options_.interval));
  std::unique_lock<std::mutex> lock(mutex_);
  while (!wake_.wait_for(lock, period, [this] { return finished_; })) draw_if_due(true);
}

void Progress::draw_if_due(bool only_changes) {
  if (finished_) return;
  const auto now = Clock::now();
  const auto seconds = [](Clock::duration d) { return std::chrono::duration<double>(d).count(); };
  if (seconds(now - start_) < options_.delay) return;
  if ((drawn_ || held_) && seconds(now - last_draw_) < options_.interval) return;
  if (only_changes && (drawn_ || held_) && done_.load(std::memory_order_relaxed) == drawn_done_ &&
      total_.load(std::memory_order_relaxed) == drawn_total_)
    return;
  draw(now);
}

// label: stage [##########..........]  52 % 3.2 s left
void Progress::draw(Clock::time_point now) {
  const std::uint64_t total = total_.load(std::memory_order_relaxed);
  if (total == 0) return;
  const std::uint64_t done = std::min(done_.load(std::memory_order_relaxed), total);
  drawn_done_ = done_.load(std::memory_order_relaxed);
  drawn_total_ = total;
  const double fraction = double(done) / double(total);
  // Never back (the count is monotone within a stage; this guards rounding).
  const int percent = std::max(last_percent_, static_cast<int>(std::floor(100 * fraction)));
  last_percent_ = percent;
  std::string tail = fmt::format(" {:3} %", percent);
  const double elapsed = std::chrono::duration<double>(now - stage_start_).count();
  if (done > 0 && done < total && elapsed > 0.2)
    tail += " " + duration_text(elapsed * double(total - done) / double(done)) + " left";
  std::string head = stage_.empty() ? label_ : label_.empty() ? stage_ : label_ + ": " + stage_;
  // Fit in one line short of the width: the bar shrinks to 10 cells, then
  // the head loses its beginning ("...ene.wrl: shapes").
  const int limit = (options_.columns > 0 ? options_.columns : terminal_columns(options_.out)) - 1;
  constexpr int kBarMax = 30, kBarMin = 10;
  const int fixed = static_cast<int>(tail.size()) + 3;  // " [" and "]"
  int bar = std::clamp(limit - fixed - static_cast<int>(head.size()), kBarMin, kBarMax);
  const int room = std::max(0, limit - fixed - bar);
  if (static_cast<int>(head.size()) > room)
    head = room > 3 ? "..." + head.substr(head.size() - static_cast<std::size_t>(room - 3))
                    : std::string();
  const int full = static_cast<int>(std::floor(fraction * bar));
  std::string line = "\r" + head + " [" + std::string(static_cast<std::size_t>(full), '#') +
                     std::string(static_cast<std::size_t>(bar - full), '.') + "]" + tail + "\033[K";
  std::fputs(line.c_str(), options_.out);
  std::fflush(options_.out);
  drawn_ = true;
  held_ = false;
  last_draw_ = now;
}

}  // namespace lodforge
