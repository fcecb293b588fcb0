#pragma once
// Files an output must never replace, made in a test's own folder: a private
// device node (never the machine's /dev), a FIFO, a socket, a directory.
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace lodforge::test {

enum class Special { kNullDevice, kFullDevice, kFifo, kSocket, kDirectory };

/// The kinds an output path is checked against (the full device serves
/// standard-output tests).
inline const std::vector<Special> kRefusedKinds = {Special::kNullDevice, Special::kFifo,
                                                   Special::kSocket, Special::kDirectory};

/// What the error message calls it.
inline const char* kind_text(Special kind) {
  switch (kind) {
    case Special::kNullDevice:
    case Special::kFullDevice:
      return "a character device";
    case Special::kFifo:
      return "a FIFO";
    case Special::kSocket:
      return "a socket";
    case Special::kDirectory:
      return "a directory";
  }
  return "";
}

inline std::filesystem::file_type file_type_of(Special kind) {
  using std::filesystem::file_type;
  switch (kind) {
    case Special::kNullDevice:
    case Special::kFullDevice:
      return file_type::character;
    case Special::kFifo:
      return file_type::fifo;
    case Special::kSocket:
      return file_type::socket;
    case Special::kDirectory:
      return file_type::directory;
  }
  return file_type::none;
}

/// Makes `kind` at `path`; false where it cannot be made (mknod needs
/// privileges, which the test runs have as root).
inline bool make_special(const std::string& path, Special kind) {
  switch (kind) {
    case Special::kNullDevice:  // char 1,3 as /dev/null
      return ::mknod(path.c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0;
    case Special::kFullDevice:  // char 1,7 as /dev/full: every write fails with ENOSPC
      return ::mknod(path.c_str(), S_IFCHR | 0666, makedev(1, 7)) == 0;
    case Special::kFifo:
      return ::mkfifo(path.c_str(), 0666) == 0;
    case Special::kSocket: {
      sockaddr_un address{};
      address.sun_family = AF_UNIX;
      if (path.size() >= sizeof address.sun_path) return false;
      std::memcpy(address.sun_path, path.c_str(), path.size() + 1);
      const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
      if (fd < 0) return false;
      // The socket file stays after the descriptor is closed.
      const bool bound = ::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0;
      ::close(fd);
      return bound;
    }
    case Special::kDirectory:
      return std::filesystem::create_directory(path);
  }
  return false;
}

/// The type of `path` itself (a link is not followed).
inline std::filesystem::file_type type_at(const std::string& path) {
  std::error_code ec;
  return std::filesystem::symlink_status(path, ec).type();
}

}  // namespace lodforge::test
