#pragma once
// The VRML 1.0 files the tests run over: the real corpus beside the
// repository (../shared/data/vrml1) and the repository's examples.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace lodforge::testing {

inline bool is_vrml_path(const std::filesystem::path& p) {
  std::string s = p.filename().string();
  auto ends = [&](std::string_view e) { return s.size() >= e.size() && s.ends_with(e); };
  return ends(".wrl") || ends(".wrl.gz") || ends(".WRL") || ends(".vrml");
}

/// Every VRML file under `dir` (recursive), sorted; empty if `dir` is missing.
inline std::vector<std::string> vrml_files_under(const std::string& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return out;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
    if (e.is_regular_file() && is_vrml_path(e.path())) out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

/// Every Open Inventor file (.iv, .iv.gz) under `dir` (recursive), sorted.
inline std::vector<std::string> inventor_files_under(const std::string& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return out;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    const std::string s = e.path().filename().string();
    if (e.is_regular_file() && (s.ends_with(".iv") || s.ends_with(".iv.gz")))
      out.push_back(e.path().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// The Inventor files of the shared corpus (../shared/data/inventor).
inline std::vector<std::string> all_inventor_test_files() {
  return inventor_files_under(std::string(LODFORGE_SHARED_DATA) + "/inventor");
}

/// Corpus files and examples together.
inline std::vector<std::string> all_vrml_test_files() {
  auto files = vrml_files_under(std::string(LODFORGE_SHARED_DATA) + "/vrml1");
  auto ex = vrml_files_under(LODFORGE_EXAMPLES);
  files.insert(files.end(), ex.begin(), ex.end());
  return files;
}

/// A name usable in a test name: the path's characters outside [A-Za-z0-9] as _.
inline std::string test_name_for(const std::string& path) {
  std::string shared = std::string(LODFORGE_SHARED_DATA) + "/vrml1/";
  std::string inventor = std::string(LODFORGE_SHARED_DATA) + "/inventor/";
  std::string s = path.starts_with(shared)     ? path.substr(shared.size())
                  : path.starts_with(inventor) ? path.substr(inventor.size())
                                               : std::filesystem::path(path).filename().string();
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return s;
}

}  // namespace lodforge::testing
