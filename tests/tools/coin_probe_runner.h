#pragma once
// Runs the Coin3D oracle (tests/tools/coin_probe) on a file in a child
// process: Coin crashes on some broken inputs, and a crash must be a verdict,
// not the end of the test run. Needs LODFORGE_COIN_PROBE (the probe's path).
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

namespace lodforge::testing {

struct CoinResult {
  bool ran = false;     ///< the probe finished normally
  std::string failure;  ///< why it did not (signal, timeout, bad output)
  bool ok = false;      ///< Coin accepted the file
  /// Coin read the file, whether or not its traversal then crashed (Coin
  /// crashes drawing an IndexedFaceSet under an indexed binding without the
  /// index field, which VRML 1.0 allows).
  bool read = false;
  std::string error;  ///< Coin's read errors
  std::map<std::string, std::size_t> node_counts;
  std::size_t ifs_triangles = 0;
  std::map<std::string, std::size_t> primitive_counts;
  std::map<std::string, std::size_t> shape_triangles;  ///< per shape type
  /// Per shape type, triangles with three corners at three different points.
  std::map<std::string, std::size_t> distinct_triangles;

  bool accepted() const { return ran && ok; }
  /// Triangles of all shapes the traversal met.
  std::size_t triangles() const {
    std::size_t n = 0;
    for (const auto& [type, t] : shape_triangles) n += t;
    return n;
  }
  std::string why_rejected() const { return ran ? error : failure; }
};

/// Runs coin_probe on `path` in a child process, killing it after `timeout`.
/// With `lod_child` >= 0 every LOD draws that child (or its last) in the counts.
inline CoinResult run_coin_probe(const std::string& path,
                                 std::chrono::seconds timeout = std::chrono::seconds(120),
                                 int lod_child = -1) {
  CoinResult result;
#ifdef LODFORGE_COIN_PROBE
  int fds[2];
  if (pipe(fds) != 0) {
    result.failure = "pipe() failed";
    return result;
  }
  const std::string child = std::to_string(lod_child);  // (no allocation after fork)
  const pid_t pid = fork();
  if (pid < 0) {
    result.failure = "fork() failed";
    return result;
  }
  if (pid == 0) {
    dup2(fds[1], STDOUT_FILENO);
    const int null_fd = open("/dev/null", O_WRONLY);
    if (null_fd >= 0) dup2(null_fd, STDERR_FILENO);
    close(fds[0]);
    close(fds[1]);
    if (lod_child >= 0)
      execl(LODFORGE_COIN_PROBE, "coin_probe", path.c_str(), child.c_str(),
            static_cast<char*>(nullptr));
    else
      execl(LODFORGE_COIN_PROBE, "coin_probe", path.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  close(fds[1]);
  std::string out;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  bool timed_out = false;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      timed_out = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    if (poll(&p, 1, static_cast<int>(left.count())) <= 0) continue;
    char buf[65536];
    const ssize_t n = read(fds[0], buf, sizeof buf);
    if (n <= 0) break;
    out.append(buf, static_cast<std::size_t>(n));
  }
  close(fds[0]);
  if (timed_out) kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  result.read = out.starts_with("{\"read\":true}");
  if (timed_out) {
    result.failure = "Coin timed out";
  } else if (WIFSIGNALED(status)) {
    result.failure = "Coin crashed (signal " + std::to_string(WTERMSIG(status)) + ")";
  } else if (WEXITSTATUS(status) != 0) {
    result.failure = "coin_probe exited with " + std::to_string(WEXITSTATUS(status));
  } else {
    // The last line: the first only says whether Coin read the file.
    const std::size_t nl = out.find('\n');
    const std::string last = nl == std::string::npos ? out : out.substr(nl + 1);
    const nlohmann::json j = nlohmann::json::parse(last, nullptr, false);
    if (j.is_discarded()) {
      result.failure = "coin_probe printed no JSON: " + out;
      return result;
    }
    result.ran = true;
    result.ok = j.at("ok").get<bool>();
    result.error = j.at("error").get<std::string>();
    result.node_counts = j.at("node_counts").get<std::map<std::string, std::size_t>>();
    result.ifs_triangles = j.at("ifs_triangles").get<std::size_t>();
    result.primitive_counts = j.at("primitive_counts").get<std::map<std::string, std::size_t>>();
    result.shape_triangles = j.at("shape_triangles").get<std::map<std::string, std::size_t>>();
    result.distinct_triangles =
        j.at("distinct_triangles").get<std::map<std::string, std::size_t>>();
  }
#else
  (void)path;
  (void)timeout;
  (void)lod_child;
  result.failure = "coin_probe not built";
#endif
  return result;
}

}  // namespace lodforge::testing
