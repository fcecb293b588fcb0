// VRML 1.0 parse throughput and peak memory: lodforge's reader against
// Coin3D's SoDB::readAll on the same generated file, in the same run.
//
// The input is a ~50 MB number-dense IndexedFaceSet (a displaced grid: one
// Coordinate3 of ~560 000 points and ~1.1 million triangles), generated once,
// deterministically, into the temporary directory.
//
//   vrml1_parse_bench [benchmark flags]   times the readers (MB/s) and prints
//                                         the ratio lodforge / Coin, then the
//                                         peak memory of each reader
//   vrml1_parse_bench --peak-rss=READER FILE
//                                         internal: reads FILE with READER
//                                         (lodforge | lodforge-text | coin) in
//                                         this fresh process and prints its
//                                         peak RSS before and after, in kB
//
// Peak memory is measured in a child process started from scratch (exec, not
// just fork, so that the parent's own allocations are not counted), as the
// growth of the peak RSS (VmHWM) while reading, relative to the file size.
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include "lodforge/core/file_io.h"
#include "lodforge/io/vrml1/read_vrml1.h"

#ifdef LODFORGE_BENCH_COIN
#include <Inventor/SoDB.h>
#include <Inventor/SoInput.h>
#include <Inventor/errors/SoReadError.h>
#include <Inventor/nodes/SoSeparator.h>
#endif

namespace {

constexpr std::size_t kTargetBytes = 50u << 20;

/// Writes the benchmark file if it is missing (or of another generation).
std::string benchmark_file() {
  const auto path = std::filesystem::temp_directory_path() / "lodforge_vrml1_bench_50mb.wrl";
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && std::filesystem::file_size(path, ec) > kTargetBytes) {
    return path.string();
  }
  // A grid of n x n vertices costs about 90 bytes per vertex (a point and two
  // triangles); pick n for just over the target size.
  const int n = static_cast<int>(std::sqrt(static_cast<double>(kTargetBytes) / 88.0)) + 1;
  std::string text;
  text.reserve(kTargetBytes + (4u << 20));
  text += "#VRML V1.0 ascii\n# lodforge parse benchmark: a displaced grid\nSeparator {\n";
  text += "  Coordinate3 { point [\n";
  auto out = std::back_inserter(text);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double x = 0.01 * i - 0.005 * n;
      const double z = 0.01 * j - 0.005 * n;
      const double y =
          0.37 * std::sin(0.731 * x) * std::cos(0.529 * z) + 1e-4 * ((i * 7 + j * 13) % 97);
      fmt::format_to(out, "    {:.6g} {:.6g} {:.6g},\n", x, y, z);
    }
  }
  text += "  ] }\n  IndexedFaceSet { coordIndex [\n";
  for (int j = 0; j + 1 < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i;
      fmt::format_to(out, "    {}, {}, {}, -1, {}, {}, {}, -1,\n", a, a + n, a + 1, a + 1, a + n,
                     a + n + 1);
    }
  }
  text += "  ] }\n}\n";
  lodforge::write_file_atomic(path.string(), text);
  return path.string();
}

const std::string& file_path() {
  static const std::string path = benchmark_file();
  return path;
}

const std::string& file_text() {
  static const std::string text = lodforge::read_file(file_path());
  return text;
}

void BM_lodforge_read_text(benchmark::State& state) {
  const std::string& text = file_text();
  for (auto _ : state) {
    auto result = lodforge::vrml1::read_vrml1(text);
    benchmark::DoNotOptimize(result.scene.roots.data());
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * text.size()));
}

void BM_lodforge_read_file(benchmark::State& state) {
  const std::string& path = file_path();
  for (auto _ : state) {
    auto result = lodforge::vrml1::read_vrml1_file(path);
    benchmark::DoNotOptimize(result.scene.roots.data());
  }
  state.SetBytesProcessed(
      static_cast<std::int64_t>(state.iterations() * std::filesystem::file_size(path)));
}

#ifdef LODFORGE_BENCH_COIN
bool coin_read(const std::string& path) {
  SoInput input;
  if (!input.openFile(path.c_str())) return false;
  SoSeparator* root = SoDB::readAll(&input);
  if (root == nullptr) return false;
  root->ref();
  root->unref();
  return true;
}

void BM_coin_readAll(benchmark::State& state) {
  const std::string& path = file_path();
  SoDB::init();
  for (auto _ : state) {
    if (!coin_read(path)) state.SkipWithError("Coin could not read the benchmark file");
  }
  state.SetBytesProcessed(
      static_cast<std::int64_t>(state.iterations() * std::filesystem::file_size(path)));
}
#endif

BENCHMARK(BM_lodforge_read_text)->Unit(benchmark::kMillisecond)->Iterations(5);
BENCHMARK(BM_lodforge_read_file)->Unit(benchmark::kMillisecond)->Iterations(5);
#ifdef LODFORGE_BENCH_COIN
BENCHMARK(BM_coin_readAll)->Unit(benchmark::kMillisecond)->Iterations(3);
#endif

/// Console output plus the throughput of each benchmark, for the ratio.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  RatioReporter() : ConsoleReporter(isatty(STDOUT_FILENO) != 0 ? OO_Defaults : OO_Tabular) {}
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      const auto it = run.counters.find("bytes_per_second");
      if (it != run.counters.end()) bytes_per_second[run.run_name.function_name] = it->second.value;
    }
  }
  std::map<std::string, double> bytes_per_second;
};

/// Peak resident set size of this process in kB: VmHWM of /proc/self/status.
/// Not getrusage's ru_maxrss: that survives execve, so a child exec'd from the
/// benchmark would start with its parent's peak.
long max_rss_kb() {
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (f == nullptr) return -1;
  char line[256];
  long kb = -1;
  while (std::fgets(line, sizeof line, f) != nullptr) {
    if (std::sscanf(line, "VmHWM: %ld kB", &kb) == 1) break;
  }
  std::fclose(f);
  return kb;
}

/// The child's side of the memory measurement.
int measure_peak_rss(std::string_view reader, const std::string& path) {
  const long before = max_rss_kb();
  bool ok = true;
  if (reader == "lodforge") {
    auto result = lodforge::vrml1::read_vrml1_file(path);
    ok = !result.scene.roots.empty();
  } else if (reader == "lodforge-text") {
    // The text in memory is the caller's; only the parse is measured.
    const std::string text = lodforge::read_file(path);
    const long loaded = max_rss_kb();
    auto result = lodforge::vrml1::read_vrml1(text);
    ok = !result.scene.roots.empty();
    std::printf("%ld %ld\n", loaded, max_rss_kb());
    return ok ? 0 : 1;
#ifdef LODFORGE_BENCH_COIN
  } else if (reader == "coin") {
    SoDB::init();
    const long initialised = max_rss_kb();
    SoInput input;
    ok = input.openFile(path.c_str());
    SoSeparator* root = ok ? SoDB::readAll(&input) : nullptr;
    ok = root != nullptr;
    std::printf("%ld %ld\n", initialised, max_rss_kb());
    return ok ? 0 : 1;
#endif
  } else {
    std::fprintf(stderr, "unknown reader %.*s\n", static_cast<int>(reader.size()), reader.data());
    return 2;
  }
  std::printf("%ld %ld\n", before, max_rss_kb());
  return ok ? 0 : 1;
}

/// Runs this program as `--peak-rss=READER FILE` and returns the growth of its
/// peak RSS in bytes, or -1.
double peak_rss_growth(const char* self, const std::string& reader, const std::string& path) {
  int fds[2];
  if (pipe(fds) != 0) return -1;
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(fds[1], STDOUT_FILENO);
    close(fds[0]);
    close(fds[1]);
    const std::string flag = "--peak-rss=" + reader;
    execl(self, self, flag.c_str(), path.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  close(fds[1]);
  char buf[256] = {};
  const ssize_t n = read(fds[0], buf, sizeof buf - 1);
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  long before = 0;
  long after = 0;
  if (n <= 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0 ||
      std::sscanf(buf, "%ld %ld", &before, &after) != 2) {
    return -1;
  }
  std::printf("peak RSS %-14s %8.1f MB before reading, %8.1f MB after\n", reader.c_str(),
              before / 1024.0, after / 1024.0);
  return static_cast<double>(after - before) * 1024.0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 3 && std::strncmp(argv[1], "--peak-rss=", 11) == 0) {
    return measure_peak_rss(argv[1] + 11, argv[2]);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  const std::string& path = file_path();
  const double size = static_cast<double>(std::filesystem::file_size(path));
  std::printf("input: %s, %.1f MB\n", path.c_str(), size / 1e6);

  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();

  const auto& bps = reporter.bytes_per_second;
  for (const auto& [name, value] : bps)
    std::printf("%-24s %8.1f MB/s\n", name.c_str(), value / 1e6);
  if (bps.contains("BM_coin_readAll")) {
    for (const char* ours : {"BM_lodforge_read_text", "BM_lodforge_read_file"}) {
      if (bps.contains(ours)) {
        std::printf("%s / Coin = %.2fx (target >= 4x)\n", ours,
                    bps.at(ours) / bps.at("BM_coin_readAll"));
      }
    }
  }

  // Peak memory, each reader in a fresh process.
  std::vector<std::string> readers = {"lodforge", "lodforge-text"};
#ifdef LODFORGE_BENCH_COIN
  readers.push_back("coin");
#endif
  for (const std::string& reader : readers) {
    const double growth = peak_rss_growth("/proc/self/exe", reader, path);
    if (growth < 0) {
      std::printf("peak memory %-14s failed\n", reader.c_str());
    } else {
      std::printf("peak memory %-14s %8.1f MB = %.2fx the file size (target <= 2x)\n",
                  reader.c_str(), growth / 1e6, growth / size);
    }
  }
  return 0;
}
