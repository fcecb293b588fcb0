#include "lodforge/core/progress.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <regex>
#include <string>
#include <thread>
#include <vector>

namespace lodforge {
namespace {

// A fake terminal: a temporary file Progress draws into, read back as text.
class FakeTerminal {
 public:
  FakeTerminal() : file_(std::tmpfile()) {}
  ~FakeTerminal() { std::fclose(file_); }
  /// Options drawing into this file, as on a terminal, without delay or
  /// interval unless a test asks for them (interval 0: each update draws,
  /// no redrawing thread, so the drawings are the updates').
  ProgressOptions options(double delay = 0, double interval = 0) const {
    return {.out = file_, .terminal = true, .delay = delay, .interval = interval, .columns = 60};
  }
  std::string text() const {
    std::fflush(file_);
    std::rewind(file_);
    std::string s;
    char buf[4096];
    for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, file_)) > 0;) s.append(buf, n);
    std::fseek(file_, 0, SEEK_END);
    return s;
  }

 private:
  std::FILE* file_;
};

// The percentages of each drawing, in order.
std::vector<int> percentages(const std::string& text) {
  std::vector<int> out;
  static const std::regex kPercent(R"(\] +(\d+) %)");
  for (std::sregex_iterator it(text.begin(), text.end(), kPercent), end; it != end; ++it)
    out.push_back(std::stoi((*it)[1]));
  return out;
}

TEST(Progress, DrawsABarRedrawnInPlaceAndClearsItAtTheEnd) {
  FakeTerminal term;
  {
    Progress p("scene.wrl", 4, term.options());
    for (std::uint64_t i = 1; i <= 4; ++i) p.update(i);
    EXPECT_TRUE(p.drawn());
  }
  const std::string text = term.text();
  EXPECT_NE(text.find("\rscene.wrl ["), std::string::npos) << text;
  EXPECT_NE(text.find("#####...."), std::string::npos) << text;
  EXPECT_NE(text.find(" 50 %"), std::string::npos) << text;
  EXPECT_EQ(text.find('\n'), std::string::npos) << "one line, redrawn with \\r";
  // Cleared at the end: what follows starts on a clean line.
  EXPECT_TRUE(text.ends_with("\r\033[K")) << text;
}

TEST(Progress, LineFitsTheWidth) {
  FakeTerminal term;
  {
    Progress p(std::string(200, 'x') + "/scene.wrl", 10, term.options());
    p.update(3);
  }
  const std::string text = term.text();
  const std::string line = text.substr(1, text.find("\033[K") - 1);
  EXPECT_LE(line.size(), 59u) << line;  // one column short of 60: never wraps
  EXPECT_TRUE(line.starts_with("...")) << line;
  EXPECT_NE(line.find("scene.wrl ["), std::string::npos) << line;
}

TEST(Progress, PercentagesAreMonotoneUnderThreads) {
  FakeTerminal term;
  constexpr std::uint64_t kTotal = 40000;
  {
    Progress p("work", kTotal, term.options());
    ProgressCallback cb = p.callback();
    ProgressCounter counter(cb, "items", kTotal, 100);
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
      threads.emplace_back([&] {
        for (int i = 0; i < 10000; ++i) counter.add(1);
      });
    for (auto& t : threads) t.join();
  }
  const std::string text = term.text();
  EXPECT_NE(text.find("\rwork: items ["), std::string::npos);
  std::vector<int> seen = percentages(text);
  ASSERT_GE(seen.size(), 2u);
  for (std::size_t i = 1; i < seen.size(); ++i) EXPECT_LE(seen[i - 1], seen[i]) << i;
  EXPECT_LE(seen.back(), 100);
}

TEST(Progress, StagesStartOverAndNameThemselves) {
  FakeTerminal term;
  {
    Progress p("mco build", 0, term.options());
    p.update("signs", 5, 10);
    p.update("tree", 1, 4);
  }
  const std::string text = term.text();
  EXPECT_NE(text.find("mco build: signs ["), std::string::npos) << text;
  EXPECT_NE(text.find("mco build: tree ["), std::string::npos) << text;
  EXPECT_EQ(percentages(text), (std::vector<int>{50, 25}));
}

TEST(Progress, NothingWhenNotATerminalOrQuiet) {
  FakeTerminal term;
  ProgressOptions pipe = term.options();
  pipe.terminal = false;
  ProgressOptions quiet = term.options();
  quiet.quiet = true;
  for (const ProgressOptions& o : {pipe, quiet}) {
    Progress p("scene.wrl", 2, o);
    p.update(1);
    p.update("stage", 2, 2);
    p.finish();
    EXPECT_FALSE(p.drawn());
  }
  EXPECT_EQ(term.text(), "");
}

TEST(Progress, NothingForWorkUnderTheDelay) {
  FakeTerminal term;
  {
    Progress p("scene.wrl", 100, term.options(/*delay=*/0.5, /*interval=*/0.1));
    for (std::uint64_t i = 1; i <= 100; ++i) p.update(i);
  }
  EXPECT_EQ(term.text(), "") << "no flicker on small inputs";
}

TEST(Progress, DrawsAtMostOncePerInterval) {
  FakeTerminal term;
  {
    Progress p("scene.wrl", 1000, term.options(/*delay=*/0, /*interval=*/60));
    for (std::uint64_t i = 1; i <= 1000; ++i) p.update(i);
  }
  EXPECT_EQ(percentages(term.text()).size(), 1u);
}

TEST(Progress, TheLastCountOfAStageIsRedrawn) {
  FakeTerminal term;
  {
    Progress p("mco build", 0, term.options(/*delay=*/0, /*interval=*/0.02));
    p.update("signs", 1, 10);  // drawn
    p.update("signs", 9, 10);  // within the interval: left to the redrawing thread
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  EXPECT_EQ(percentages(term.text()), (std::vector<int>{10, 90}));
}

TEST(Progress, AClearedBarStaysOffUntilTheCountMoves) {
  FakeTerminal term;
  Progress p("scene.wrl", 20, term.options(/*delay=*/0, /*interval=*/0.02));
  p.update(3);   // drawn
  p.update(10);  // within the interval: not drawn yet
  p.clear();     // the caller prints something
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_TRUE(term.text().ends_with("\r\033[K")) << "the redrawing thread drew over the caller";
  EXPECT_EQ(percentages(term.text()), (std::vector<int>{15}));
  p.update(15);  // a later count brings the bar back
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_EQ(percentages(term.text()), (std::vector<int>{15, 75}));
}

TEST(Progress, AClearBeforeTheFirstDrawingHoldsTheBarToo) {
  FakeTerminal term;
  Progress p("scene.wrl", 20, term.options(/*delay=*/0.05, /*interval=*/0.02));
  p.update(20);  // under the delay: not drawn
  p.clear();     // the work is done; the caller prints its summary
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_EQ(term.text(), "") << "the bar appeared after the work was done";
}

TEST(ProgressCounter, ReportsEveryStepAndTheEnd) {
  std::vector<std::uint64_t> calls;
  ProgressCallback cb = [&](std::string_view stage, std::uint64_t done, std::uint64_t total) {
    EXPECT_EQ(stage, "samples");
    EXPECT_EQ(total, 10u);
    calls.push_back(done);
  };
  ProgressCounter c(cb, "samples", 10, 4);
  for (int i = 0; i < 10; ++i) c.add(1);
  EXPECT_EQ(calls, (std::vector<std::uint64_t>{0, 4, 8, 10}));
  // An empty callback: nothing to call.
  ProgressCallback none;
  ProgressCounter quiet(none, "samples", 10);
  quiet.add(10);
}

}  // namespace
}  // namespace lodforge
