// `lodforge studio` as a user runs it: a child process on a free port,
// ended by Ctrl-C (SIGINT) or SIGTERM, after which it has exited cleanly and
// removed the folder of the scenes uploaded to it.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>
#include <httplib.h>

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <thread>

#include "apps/run_command.h"

namespace fs = std::filesystem;

namespace {

std::string read_all(const fs::path& p) {
  return lodforge::testing::read_text(p.string());
}

// Starts `lodforge studio scene --port 0` with stderr into `log`.
pid_t start_studio(const fs::path& scene, const fs::path& log) {
  const pid_t pid = fork();
  if (pid == 0) {
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 2);
    execl(LODFORGE_EXE, LODFORGE_EXE, "studio", scene.c_str(), "--port", "0", nullptr);
    _exit(127);
  }
  return pid;
}

// The port the studio announces on stderr; 0 if it does not within 30 s.
int announced_port(const fs::path& log) {
  const std::regex url(R"(http://127\.0\.0\.1:(\d+)/)");
  for (int i = 0; i < 300; ++i) {
    std::smatch m;
    const std::string text = read_all(log);
    if (std::regex_search(text, m, url)) return std::stoi(m[1]);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return 0;
}

// The child's wait status, or -1 if it has not ended within 30 s (then killed).
int wait_for(pid_t pid) {
  for (int i = 0; i < 300; ++i) {
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) return status;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  kill(pid, SIGKILL);
  waitpid(pid, nullptr, 0);
  return -1;
}

}  // namespace

TEST(StudioCommand, CtrlCOrTermEndsItAndRemovesTheUploadedScenes) {
  const fs::path dir =
      fs::temp_directory_path() / ("lodforge_StudioCommand_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy_file(std::string(LODFORGE_EXAMPLES) + "/scene.wrl", dir / "scene.wrl");
  for (const int signal : {SIGINT, SIGTERM}) {
    SCOPED_TRACE(signal == SIGINT ? "SIGINT" : "SIGTERM");
    const fs::path log = dir / ("studio" + std::to_string(signal) + ".log");
    const pid_t pid = start_studio(dir / "scene.wrl", log);
    ASSERT_GT(pid, 0);
    // A failed check leaves no server running.
    struct Reap {
      pid_t pid;
      ~Reap() {
        if (pid > 0 && kill(pid, SIGKILL) == 0) waitpid(pid, nullptr, 0);
      }
    } reap{pid};
    const int port = announced_port(log);
    ASSERT_GT(port, 0) << read_all(log);
    httplib::Client client("127.0.0.1", port);
    const auto r = client.Post(
        "/api/upload",
        nlohmann::json{{"name", "up.wrl"}, {"text", "#VRML V1.0 ascii\nCube { }\n"}}.dump(),
        "application/json");
    ASSERT_TRUE(r) << read_all(log);
    ASSERT_EQ(r->status, 200) << r->body;
    const fs::path uploaded = nlohmann::json::parse(r->body).at("path").get<std::string>();
    ASSERT_TRUE(fs::exists(uploaded));
    kill(pid, signal);
    const int status = wait_for(pid);
    reap.pid = 0;
    ASSERT_TRUE(WIFEXITED(status)) << "status " << status << "\n" << read_all(log);
    EXPECT_EQ(WEXITSTATUS(status), 0) << read_all(log);
    EXPECT_FALSE(fs::exists(uploaded.parent_path())) << uploaded.parent_path();
  }
  fs::remove_all(dir);
}
