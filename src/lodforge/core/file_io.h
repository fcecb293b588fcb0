#pragma once
/// Reading whole files (gzip-compressed ones transparently) and writing files
/// atomically: output goes to a temporary file beside the target, which is
/// renamed into place only when complete, so a failure never leaves a
/// half-written file. A target whose name ends in ".gz" is written
/// gzip-compressed, so every writer of the toolkit writes gzip for such names.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

namespace lodforge {

/// Reads a whole file, or standard input for "-". Data that starts with the
/// gzip magic bytes is decompressed (at most max_inflated_size of it). Throws
/// DataError if it cannot be read or the compressed stream is corrupt.
std::string read_file(const std::string& path);

/// A whole file's bytes for reading, as read_file gives them, without the
/// copy where it can: an uncompressed regular file is mapped into memory
/// read-only; standard input, pipes and gzip data are read (and inflated)
/// into memory. Throws as read_file. The file must not shrink while the
/// bytes are in use.
class FileBytes {
 public:
  explicit FileBytes(const std::string& path);
  ~FileBytes();
  FileBytes(const FileBytes&) = delete;
  FileBytes& operator=(const FileBytes&) = delete;
  std::string_view view() const { return view_; }

 private:
  void* map_ = nullptr;
  std::size_t map_size_ = 0;
  std::string data_;
  std::string_view view_;
};

/// Bytes [offset, offset + size) of a regular, uncompressed file, mapped
/// read-only: the operating system pages them in and out, so a region larger
/// than the memory a process may allocate can still be read (it counts
/// against the address space only). Readers that stream a large file map
/// the part they must read at random (a PLY file's vertices) this way.
/// Throws DataError naming `path` if it is not a regular file, is shorter
/// than offset + size, or cannot be mapped. The file must not shrink while
/// the region is in use.
class MappedFileRegion {
 public:
  MappedFileRegion(const std::string& path, std::uint64_t offset, std::uint64_t size);
  ~MappedFileRegion();
  MappedFileRegion(const MappedFileRegion&) = delete;
  MappedFileRegion& operator=(const MappedFileRegion&) = delete;
  std::string_view view() const { return view_; }

 private:
  void* map_ = nullptr;
  std::size_t map_size_ = 0;
  std::string_view view_;
};

/// True if `data` starts with the gzip magic bytes.
bool is_gzip(std::string_view data);

/// The most a gzip stream of `compressed` bytes may inflate to: 64 times its
/// size, and at least 64 MiB. Real scenes and meshes compress 3 to 20 times;
/// a "gzip bomb" (gigabytes of spaces) 1000 times.
std::size_t max_inflated_size(std::size_t compressed);

/// Decompresses gzip data. Throws DataError naming `what` on a corrupt
/// stream, or when the data inflates to more than `max_size` bytes (0:
/// max_inflated_size(data.size())).
std::string gunzip(std::string_view data, const std::string& what, std::size_t max_size = 0);

/// The first `n` bytes of a file's content (fewer if it is shorter), inflated
/// when the file is gzip data: only as much of the file is read and inflated
/// as `n` bytes need, to tell a file's kind by its header. A file that cannot
/// be read, or whose gzip data is corrupt before `n` bytes, gives what was
/// read (possibly nothing): the reader that takes the file names the error.
std::string read_head(const std::string& path, std::size_t n);

/// Compresses `data` as one gzip member (zlib's default level; deterministic:
/// no name and no time stamp in the header).
std::string gzip(std::string_view data);

/// True if `path` ends in ".gz" (any case): the name of a gzip file.
bool is_gzip_path(std::string_view path);

/// A file written in pieces, atomically: the streaming form of
/// write_file_atomic, with the same rules ("-" is standard output, a ".gz"
/// name is written gzip-compressed, links and modes, refused nodes). The
/// pieces go to a temporary file beside the target, which commit() renames
/// into place; destroyed without commit() (an exception on the way), the
/// temporary file is removed and the target stays as it was. Throws
/// DataError as write_file_atomic.
class AtomicFileWriter {
 public:
  explicit AtomicFileWriter(const std::string& path);
  ~AtomicFileWriter();
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;
  void write(std::string_view bytes);
  void commit();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Writes `content` to `path` atomically ("-" writes to standard output,
/// uncompressed, and flushes it). When `path` ends in ".gz" the file holds
/// `content` gzip-compressed. A symbolic link stays a link: the file it ends
/// at is replaced (resolve_output_path in output_path.h). A replaced file
/// keeps its permission mode; a new file gets 0666 less the umask. Throws
/// DataError if the path is a directory, device node, FIFO or socket (checked
/// without opening it), or the file cannot be written.
void write_file_atomic(const std::string& path, std::string_view content);

}  // namespace lodforge
