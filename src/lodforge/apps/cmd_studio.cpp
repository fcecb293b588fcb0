// `lodforge studio SCENE... [--port N] [--host H] [--open]`: the local web
// page over the scenes (src/lodforge/studio/).
#include <fmt/core.h>
#include <pthread.h>
#include <signal.h>

#include <cstdlib>
#include <filesystem>
#include <thread>

#include "lodforge/apps/commands.h"
#include "lodforge/studio/studio_server.h"

namespace lodforge::apps {
namespace {

struct Settings {
  std::vector<std::string> scenes;
  std::string host = "127.0.0.1";
  int port = 8765;
  int threads = 0;
  bool open = false;
};

struct AssetFolders {
  std::string web, three, codemirror;
};

// The page, three.js and CodeMirror: installed beside the program
// (share/lodforge/studio), else the source tree's this program was built from.
AssetFolders asset_folders() {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  const fs::path installed = exe.parent_path().parent_path() / "share/lodforge/studio";
  if (!ec && fs::exists(installed / "web/index.html"))
    return {(installed / "web").string(), (installed / "three").string(),
            (installed / "codemirror").string()};
  return {LODFORGE_STUDIO_WEB, LODFORGE_STUDIO_THREE, LODFORGE_STUDIO_CODEMIRROR};
}

// Serves until Ctrl-C (SIGINT) or SIGTERM, which end the server as stop()
// does, so its destructor runs and removes the folder of uploaded scenes.
// The signals are blocked in every thread (the server's workers inherit the
// mask) and taken by one waiting thread.
void serve_until_signal(studio::StudioServer& server) {
  sigset_t ending;
  sigemptyset(&ending);
  sigaddset(&ending, SIGINT);
  sigaddset(&ending, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &ending, nullptr);
  std::thread waiter([&] {
    int signal = 0;
    sigwait(&ending, &signal);
    server.stop();
  });
  server.serve();
  // Ended otherwise: the waiter is woken by a signal of its own.
  pthread_kill(waiter.native_handle(), SIGTERM);
  waiter.join();
}

int run_studio(const Settings& s) {
  const AssetFolders assets = asset_folders();
  studio::StudioServer server(studio::StudioOptions{.scenes = s.scenes,
                                                    .host = s.host,
                                                    .port = s.port,
                                                    .web_root = assets.web,
                                                    .three_root = assets.three,
                                                    .codemirror_root = assets.codemirror,
                                                    .threads = s.threads});
  const int port = server.bind();
  const std::string url = fmt::format("http://{}:{}/", s.host, port);
  fmt::print(stderr, "lodforge studio: {} (Ctrl-C ends it)\n", url);
  if (s.open) {
    // The browser is the desktop's; its failure leaves the server running.
    const std::string command = fmt::format("xdg-open '{}' >/dev/null 2>&1 &", url);
    if (std::system(command.c_str()) != 0)
      fmt::print(stderr, "could not start a browser; open {} by hand\n", url);
  }
  serve_until_signal(server);
  return 0;
}

}  // namespace

void add_studio_command(CLI::App& app, Runner& run) {
  auto s = std::make_shared<Settings>();
  CLI::App* cmd = app.add_subcommand(
      "studio",
      "A local web page to load scenes, make LODs, read their statistics and watch the "
      "levels switch in a 3D view");
  cmd->add_option("SCENE", s->scenes,
                  "VRML 1.0 or Inventor files; the studio opens and writes files under their "
                  "folders only")
      ->required();
  cmd->add_option("--port", s->port, "Port to listen on (0: any free port)")
      ->capture_default_str()
      ->check(CLI::Range(0, 65535));
  cmd->add_option("--host", s->host, "Address to listen on (the default serves this machine only)")
      ->capture_default_str();
  cmd->add_option("--threads", s->threads, "Worker threads of a LOD run (0: all cores)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--open", s->open, "Open the page in the desktop's browser (xdg-open)");
  cmd->callback([s, &run] { run = [s] { return run_studio(*s); }; });
}

}  // namespace lodforge::apps
