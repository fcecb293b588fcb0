#include "lodforge/core/file_io.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <optional>

#include "lodforge/core/error.h"
#include "lodforge/core/output_path.h"

namespace lodforge {

bool is_gzip(std::string_view data) {
  return data.size() >= 2 && static_cast<unsigned char>(data[0]) == 0x1f &&
         static_cast<unsigned char>(data[1]) == 0x8b;
}

std::size_t max_inflated_size(std::size_t compressed) {
  constexpr std::size_t kRatio = 64, kFloor = std::size_t{64} << 20;
  return compressed > SIZE_MAX / kRatio ? SIZE_MAX : std::max(kRatio * compressed, kFloor);
}

std::string read_head(const std::string& path, std::size_t n) {
  std::ifstream in(path, std::ios::binary);
  // A gzip header is at most a few hundred bytes unless it holds a long name
  // or comment; 64 KiB of deflate data hold far more than a header's worth.
  std::string raw(std::max<std::size_t>(n, std::size_t{1} << 16), '\0');
  in.read(raw.data(), std::streamsize(raw.size()));
  raw.resize(std::size_t(std::max<std::streamsize>(in.gcount(), 0)));
  if (!is_gzip(raw)) return raw.substr(0, n);
  z_stream zs{};
  if (inflateInit2(&zs, 15 + 32) != Z_OK) return {};
  std::string out(n, '\0');
  zs.next_in = reinterpret_cast<Bytef*>(raw.data());
  zs.avail_in = static_cast<uInt>(raw.size());
  zs.next_out = reinterpret_cast<Bytef*>(out.data());
  zs.avail_out = static_cast<uInt>(n);
  inflate(&zs, Z_SYNC_FLUSH);
  out.resize(n - zs.avail_out);
  inflateEnd(&zs);
  return out;
}

std::string gunzip(std::string_view data, const std::string& what, std::size_t max_size) {
  if (max_size == 0) max_size = max_inflated_size(data.size());
  z_stream zs{};
  if (inflateInit2(&zs, 15 + 32) != Z_OK) throw DataError(what + ": cannot start zlib");
  std::string out;
  out.resize(std::min(std::max<std::size_t>(data.size() * 4, 1 << 16), max_size + 1));
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  zs.avail_in = static_cast<uInt>(data.size());
  std::size_t produced = 0;
  int rc = Z_OK;
  while (true) {
    // avail_out is 32-bit: grow in pieces of at most 1 GiB.
    if (produced == out.size())
      out.resize(std::min({out.size() * 2, out.size() + (std::size_t{1} << 30), max_size + 1}));
    zs.next_out = reinterpret_cast<Bytef*>(out.data() + produced);
    zs.avail_out = static_cast<uInt>(std::min(out.size() - produced, std::size_t{1} << 30));
    rc = inflate(&zs, Z_NO_FLUSH);
    produced = static_cast<std::size_t>(reinterpret_cast<char*>(zs.next_out) - out.data());
    if (produced > max_size) {
      inflateEnd(&zs);
      throw DataError(fmt::format(
          "{}: the gzip data inflates to more than {} MiB ({} times its "
          "{} bytes); refused as a possible gzip bomb",
          what, max_size >> 20, max_size / std::max<std::size_t>(data.size(), 1), data.size()));
    }
    if (rc == Z_STREAM_END) {
      // Concatenated gzip members are legal; continue with the next one.
      if (zs.avail_in > 0 && is_gzip({reinterpret_cast<const char*>(zs.next_in), zs.avail_in})) {
        inflateReset(&zs);
        continue;
      }
      break;
    }
    if (rc != Z_OK && rc != Z_BUF_ERROR) break;
    if (rc == Z_BUF_ERROR && zs.avail_in == 0) break;
  }
  inflateEnd(&zs);
  if (rc != Z_STREAM_END)
    throw DataError(fmt::format("{}: corrupt or truncated gzip data ({})", what,
                                zs.msg ? zs.msg : "unexpected end of stream"));
  out.resize(produced);
  return out;
}

namespace {

// One gzip stream being written: bytes in, compressed pieces out to a sink.
// zlib's default level, the largest window, no name and no time stamp, so
// the same bytes give the same stream however they are fed.
class Deflater {
 public:
  Deflater() {
    // 15 + 16: the largest window, with a gzip header and trailer (zlib's deflateInit2).
    if (deflateInit2(&zs_, Z_DEFAULT_COMPRESSION, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) !=
        Z_OK)
      throw DataError("cannot start zlib");
  }
  ~Deflater() { deflateEnd(&zs_); }
  Deflater(const Deflater&) = delete;
  Deflater& operator=(const Deflater&) = delete;

  // Compresses `bytes` (with `finish`, and ends the stream), handing each
  // compressed piece to `sink`; `what` names the output in errors.
  template <class Sink>
  void feed(std::string_view bytes, bool finish, Sink&& sink, std::string_view what) {
    // avail_in is 32-bit: pieces of at most 1 GiB.
    constexpr std::size_t kPiece = std::size_t{1} << 30;
    std::size_t at = 0;
    do {
      const std::string_view piece = bytes.substr(at, kPiece);
      at += piece.size();
      deflate_piece(piece, finish && at == bytes.size() ? Z_FINISH : Z_NO_FLUSH, sink, what);
    } while (at < bytes.size());
  }

 private:
  template <class Sink>
  void deflate_piece(std::string_view bytes, int flush, Sink& sink, std::string_view what) {
    zs_.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
    zs_.avail_in = static_cast<uInt>(bytes.size());
    constexpr std::size_t kOut = std::size_t{1} << 16;
    int rc = Z_OK;
    do {
      buffer_.resize(kOut);
      zs_.next_out = reinterpret_cast<Bytef*>(buffer_.data());
      zs_.avail_out = static_cast<uInt>(kOut);
      rc = deflate(&zs_, flush);
      if (rc == Z_STREAM_ERROR)
        throw DataError(what.empty() ? std::string("gzip compression failed")
                                     : fmt::format("{}: gzip compression failed", what));
      sink(std::string_view(buffer_.data(), kOut - zs_.avail_out));
    } while (zs_.avail_out == 0 || (flush == Z_FINISH && rc != Z_STREAM_END));
  }

  z_stream zs_{};
  std::string buffer_;
};

}  // namespace

std::string gzip(std::string_view data) {
  std::string out;
  Deflater().feed(data, true, [&](std::string_view piece) { out += piece; }, {});
  return out;
}

bool is_gzip_path(std::string_view path) {
  return path.size() >= 3 && path[path.size() - 3] == '.' &&
         std::tolower(static_cast<unsigned char>(path[path.size() - 2])) == 'g' &&
         std::tolower(static_cast<unsigned char>(path[path.size() - 1])) == 'z';
}

std::string read_file(const std::string& path) {
  std::string data;
  if (path == "-") {
    data.assign(std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>());
  } else {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
      throw DataError(fmt::format("{}: is a directory, expected a file", path));
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) throw DataError(fmt::format("{}: cannot open: {}", path, std::strerror(errno)));
    // Regular files are read in one go; pipes and devices in chunks.
    long size = std::fseek(f, 0, SEEK_END) == 0 ? std::ftell(f) : -1;
    if (size > 0 && std::fseek(f, 0, SEEK_SET) == 0) {
      data.resize(static_cast<std::size_t>(size));
      data.resize(std::fread(data.data(), 1, data.size(), f));
    } else {
      char chunk[1 << 16];
      std::size_t got;
      while ((got = std::fread(chunk, 1, sizeof chunk, f)) > 0) data.append(chunk, got);
    }
    bool failed = std::ferror(f);
    std::fclose(f);
    if (failed) throw DataError(fmt::format("{}: read error", path));
  }
  if (is_gzip(data)) return gunzip(data, path == "-" ? "<stdin>" : path);
  return data;
}

FileBytes::FileBytes(const std::string& path) {
  // Only a regular file is opened here: opening a FIFO would block or take
  // its data from the reader below.
  struct stat st {};
  const bool regular = path != "-" && ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
  const int fd = regular ? ::open(path.c_str(), O_RDONLY | O_CLOEXEC) : -1;
  if (fd >= 0 && ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0) {
    void* m = ::mmap(nullptr, static_cast<std::size_t>(st.st_size), PROT_READ, MAP_PRIVATE, fd, 0);
    if (m != MAP_FAILED) {
      map_ = m;
      map_size_ = static_cast<std::size_t>(st.st_size);
      ::madvise(map_, map_size_, MADV_SEQUENTIAL);
    }
  }
  if (fd >= 0) ::close(fd);
  if (map_) {
    view_ = std::string_view(static_cast<const char*>(map_), map_size_);
    if (!is_gzip(view_)) return;
    data_ = gunzip(view_, path);
    ::munmap(map_, map_size_);
    map_ = nullptr;
  } else {
    data_ = read_file(path);  // standard input, pipes, empty files, and every error message
  }
  view_ = data_;
}

FileBytes::~FileBytes() {
  if (map_) ::munmap(map_, map_size_);
}

MappedFileRegion::MappedFileRegion(const std::string& path, std::uint64_t offset,
                                   std::uint64_t size) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw DataError(fmt::format("{}: cannot open: {}", path, std::strerror(errno)));
  struct stat st {};
  const bool regular = ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode);
  if (!regular || static_cast<std::uint64_t>(st.st_size) < offset ||
      static_cast<std::uint64_t>(st.st_size) - offset < size) {
    ::close(fd);
    throw DataError(regular ? fmt::format("{}: expected {} bytes from byte {}, the file has {}",
                                          path, size, offset, st.st_size)
                            : fmt::format("{}: not a regular file", path));
  }
  if (size == 0) {
    ::close(fd);
    return;
  }
  // mmap wants an offset on a page boundary: map from the page that holds it.
  const auto page = static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
  const std::uint64_t start = offset - offset % page;
  map_size_ = static_cast<std::size_t>(size + (offset - start));
  void* m = ::mmap(nullptr, map_size_, PROT_READ, MAP_PRIVATE, fd, static_cast<off_t>(start));
  const int err = errno;
  ::close(fd);
  if (m == MAP_FAILED)
    throw DataError(fmt::format("{}: cannot map {} bytes: {}", path, size, std::strerror(err)));
  map_ = m;
  view_ = std::string_view(static_cast<const char*>(map_) + (offset - start),
                           static_cast<std::size_t>(size));
}

MappedFileRegion::~MappedFileRegion() {
  if (map_) ::munmap(map_, map_size_);
}

struct AtomicFileWriter::Impl {
  std::string path;  // as given, for messages
  std::filesystem::path target;
  std::string temporary;
  int fd = -1;
  std::optional<Deflater> gzip;  // for a .gz name

  ~Impl() {
    if (fd >= 0) {
      ::close(fd);
      ::unlink(temporary.c_str());
    }
  }

  [[noreturn]] void fail(const char* what, int err) {
    throw DataError(fmt::format("{}: {}: {}", path, what, std::strerror(err)));
  }

  void put(std::string_view bytes) {
    if (path == "-") {
      errno = 0;
      std::cout.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
      if (!std::cout)
        throw DataError(fmt::format("cannot write to standard output: {}",
                                    errno ? std::strerror(errno) : "write error"));
      return;
    }
    for (std::size_t done = 0; done < bytes.size();) {
      const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
      if (n < 0) {
        if (errno == EINTR) continue;
        fail("write failed", errno);
      }
      done += static_cast<std::size_t>(n);
    }
  }
};

AtomicFileWriter::AtomicFileWriter(const std::string& path) : impl_(std::make_unique<Impl>()) {
  Impl& w = *impl_;
  w.path = path;
  if (path == "-") return;  // standard output, uncompressed
  if (is_gzip_path(path)) w.gzip.emplace();
  // A link's target is replaced, so the temporary file goes beside it.
  w.target = resolve_output_path(path);
  const std::filesystem::path dir = w.target.has_parent_path() ? w.target.parent_path() : ".";
  std::string name = ".";  // (built in steps: GCC 12 takes "." + s + "..." for an overlap)
  name += w.target.filename().string();
  name += ".tmpXXXXXX";
  w.temporary = (dir / name).string();
  w.fd = mkstemp(w.temporary.data());
  if (w.fd < 0) w.fail("cannot create", errno);
}

AtomicFileWriter::~AtomicFileWriter() = default;

void AtomicFileWriter::write(std::string_view bytes) {
  Impl& w = *impl_;
  if (w.gzip)
    w.gzip->feed(
        bytes, false, [&](std::string_view piece) { w.put(piece); }, w.path);
  else
    w.put(bytes);
}

void AtomicFileWriter::commit() {
  Impl& w = *impl_;
  if (w.gzip)
    w.gzip->feed(
        {}, true, [&](std::string_view piece) { w.put(piece); }, w.path);
  if (w.path == "-") {
    errno = 0;
    std::cout.flush();
    if (!std::cout)
      throw DataError(fmt::format("cannot write to standard output: {}",
                                  errno ? std::strerror(errno) : "write error"));
    return;
  }
  // mkstemp makes the file 0600: a replaced file keeps its own mode, a new
  // one gets the usual mode of a new file.
  struct stat old {};
  mode_t mode = 0;
  if (::stat(w.target.c_str(), &old) == 0 && S_ISREG(old.st_mode)) {
    mode = old.st_mode & 07777;
  } else {
    const mode_t mask = umask(0);
    umask(mask);
    mode = 0666 & ~mask;
  }
  int err = ::fchmod(w.fd, mode) == 0 ? 0 : errno;
  if (::close(w.fd) != 0 && err == 0) err = errno;
  w.fd = -1;
  if (err == 0 && std::rename(w.temporary.c_str(), w.target.c_str()) != 0) err = errno;
  if (err != 0) {
    ::unlink(w.temporary.c_str());
    throw DataError(fmt::format("{}: cannot write: {}", w.path, std::strerror(err)));
  }
}

void write_file_atomic(const std::string& path, std::string_view content) {
  AtomicFileWriter out(path);
  out.write(content);
  out.commit();
}

}  // namespace lodforge
