#pragma once
// Castle Model Viewer (Debian `view3dscene`) as a judge of VRML / X3D files,
// run as a child process.
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "apps/run_command.h"

namespace lodforge::testing {

inline bool have_view3dscene() {
  return std::system("command -v view3dscene >/dev/null 2>&1") == 0;
}

/// Castle Model Viewer loads `path` (--write: load and write back, no
/// window; with `draw`, it draws it instead under xvfb-run --screenshot,
/// which also reports what only drawing finds, such as an index out of
/// range); returns its log's errors and warnings about the scene, one per
/// line, without their positions and with the file's folder as DIR. Its log
/// goes to $HOME/.config/view3dscene, so each run gets a HOME of its own.
inline std::set<std::string> castle_errors(const std::string& path,
                                           const std::filesystem::path& home, bool draw = false) {
  std::filesystem::remove_all(home);
  std::filesystem::create_directories(home);
  const std::string cmd = "HOME=" + home.string() + " timeout 120 " +
                          (draw ? "xvfb-run -a view3dscene '" + path + "' --screenshot 0 " +
                                      (home / "shot.png").string()
                                : "view3dscene '" + path + "' --write") +
                          " >/dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  const std::string log = read_text((home / ".config/view3dscene/view3dscene.log").string());
  std::set<std::string> found;
  std::istringstream lines(log);
  const std::regex position("line [0-9]+ column [0-9]+");
  const std::string folder = std::filesystem::path(path).parent_path().string();
  for (std::string line; std::getline(lines, line);) {
    if (line.find("X3D") == std::string::npos && line.find("Error") == std::string::npos) continue;
    if (line.find("to load from disk") != std::string::npos) continue;  // a timing
    line = std::regex_replace(line, position, "POSITION");
    for (std::size_t at; (at = line.find(folder)) != std::string::npos;)
      line.replace(at, folder.size(), "DIR");
    found.insert(line);
  }
  if (status != 0) found.insert("view3dscene exit status " + std::to_string(status));
  return found;
}

/// Castle Model Viewer's own conversion of `path` to the X3D XML encoding,
/// written to `out`; true if it wrote one.
inline bool castle_to_xml(const std::string& path, const std::string& out,
                          const std::filesystem::path& home) {
  std::filesystem::remove_all(home);
  std::filesystem::create_directories(home);
  const std::string cmd = "HOME=" + home.string() + " timeout 120 view3dscene '" + path +
                          "' --write --write-encoding xml > '" + out + "' 2>/dev/null";
  return std::system(cmd.c_str()) == 0 && std::filesystem::file_size(out) > 0;
}

}  // namespace lodforge::testing
