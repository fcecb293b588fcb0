#include "lodforge/core/output_path.h"

#include <fmt/format.h>
#include <sys/stat.h>

#include <map>
#include <vector>

#include "lodforge/core/error.h"

namespace lodforge {
namespace {

namespace fs = std::filesystem;

// As the kernel's own limit on a chain of links (Linux MAXSYMLINKS).
constexpr int kMaxLinks = 40;

// What a path that must not be replaced is, for messages; nullptr for a
// regular file or a path that does not exist (both may be written).
//
// | type                   | written?                                      |
// |------------------------|-----------------------------------------------|
// | regular                | yes: replaced, keeping its permission mode    |
// | not found              | yes: created                                  |
// | none (cannot be told)  | left to the writer, whose error names the cause |
// | anything else          | no                                            |
const char* refused_kind(fs::file_type type) {
  switch (type) {
    case fs::file_type::regular:
    case fs::file_type::not_found:
    case fs::file_type::none:
      return nullptr;
    case fs::file_type::directory:
      return "a directory";
    case fs::file_type::block:
      return "a block device";
    case fs::file_type::character:
      return "a character device";
    case fs::file_type::fifo:
      return "a FIFO";
    case fs::file_type::socket:
      return "a socket";
    default:
      return "not a regular file";
  }
}

// A key equal for two paths exactly when they name the same file: device and
// inode for a file that exists (links followed), else the absolute path with
// its existing part made canonical.
std::string file_key(const fs::path& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0)
    return fmt::format("#{}:{}", static_cast<unsigned long long>(st.st_dev),
                       static_cast<unsigned long long>(st.st_ino));
  std::error_code ec;
  const fs::path absolute = fs::absolute(path, ec);
  const fs::path canonical = fs::weakly_canonical(absolute, ec);
  return (ec ? absolute.lexically_normal() : canonical).string();
}

}  // namespace

fs::path resolve_output_path(const std::string& path) {
  fs::path p(path);
  std::error_code ec;
  fs::file_status status = fs::symlink_status(p, ec);
  for (int links = 0; status.type() == fs::file_type::symlink; ++links) {
    if (links == kMaxLinks)
      throw DataError(fmt::format("{}: too many levels of symbolic links", path));
    fs::path target = fs::read_symlink(p, ec);
    if (ec) throw DataError(fmt::format("{}: cannot read the link: {}", p.string(), ec.message()));
    p = target.is_absolute() ? target : p.parent_path() / target;
    status = fs::symlink_status(p, ec);
  }
  if (const char* kind = refused_kind(status.type())) {
    if (p == fs::path(path))
      throw DataError(
          fmt::format("{}: is {}, expected a regular file or a new path to write", path, kind));
    throw DataError(fmt::format("{}: links to {}, {}; expected a regular file or a new path", path,
                                p.string(), kind));
  }
  return p;
}

void check_output_paths(std::span<const OutputPath> outputs, std::span<const std::string> inputs) {
  std::map<std::string, const std::string*> input_keys;
  for (const auto& in : inputs)
    if (in != "-") input_keys.emplace(file_key(in), &in);
  std::map<std::string, const OutputPath*> seen;  // file key ("-": stdout) -> first output there
  for (const auto& out : outputs) {
    std::string key = "-";
    if (out.path != "-") {
      key = file_key(resolve_output_path(out.path));
      if (auto in = input_keys.find(key); in != input_keys.end())
        throw DataError(
            fmt::format("{}: {} would overwrite the input {}", out.path, out.what, *in->second));
    }
    auto [first, inserted] = seen.emplace(key, &out);
    if (!inserted)
      throw DataError(fmt::format("{}: {} and {} would both be written to it",
                                  key == "-" ? "standard output" : out.path, first->second->what,
                                  out.what));
  }
}

}  // namespace lodforge
