#pragma once
// The VRML97 and X3D files of the shared corpus, for tests that run over all of them.
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>
#include <vector>

namespace lodforge::testing {

/// Every VRML97 (.wrl) and X3D classic (.x3dv) file under the corpus's vrml2/
/// and x3d/ folders, and with `xml` the X3D XML (.x3d) files too; sorted.
inline std::vector<std::string> vrml97_corpus_files(bool xml = false) {
  std::vector<std::string> out;
  for (const char* dir : {"/vrml2", "/x3d"}) {
    const std::string root = std::string(LODFORGE_SHARED_DATA) + dir;
    std::error_code ec;
    if (!std::filesystem::is_directory(root, ec)) continue;
    for (const auto& e : std::filesystem::recursive_directory_iterator(root)) {
      const auto ext = e.path().extension().string();
      if (e.is_regular_file() && (ext == ".wrl" || ext == ".x3dv" || (xml && ext == ".x3d")))
        out.push_back(e.path());
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// A corpus file's path below the corpus as a test name (letters, digits, _).
inline std::string corpus_test_name(const std::string& path) {
  std::string s = path.substr(std::string(LODFORGE_SHARED_DATA).size() + 1);
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return s;
}

}  // namespace lodforge::testing
