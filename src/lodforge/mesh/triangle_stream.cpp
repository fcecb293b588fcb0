// Streaming reader of binary PLY and binary STL triangles.
//
// A PLY file is read as its header says: the elements in order, each item a
// run of properties. Faces are read sequentially through a small buffer;
// their corners index the vertex block, which is mapped (the operating
// system pages what the faces touch), so the vertices are never copied into
// the heap. The vertex element must therefore have a fixed record size (no
// list properties), which every exporter writes; its position in the file
// is found from the sizes of the elements before it, reading through them
// only when one has lists.
//
// STL has no shared vertices: each 50-byte record is one triangle with its
// own corners (the binary/ASCII rule of mesh_io_stl.cpp: the size must be
// 84 + 50 x count, or more with trailing bytes ignored).
#include "lodforge/mesh/triangle_stream.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstring>
#include <optional>
#include <vector>

#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"
#include "lodforge/mesh/mesh_io_detail.h"
#include "lodforge/mesh/ply_header.h"

namespace lodforge {
namespace {

using detail::fail_binary;
namespace ply = detail::ply;

constexpr std::size_t kStlHeader = 84;
constexpr std::size_t kStlRecord = 50;
constexpr std::size_t kBuffer = std::size_t{1} << 20;
constexpr std::size_t kMaxPlyHeader = std::size_t{16} << 20;

/// A file read front to back through a buffer, with the byte offset of what
/// is read next for messages.
class SequentialFile {
 public:
  SequentialFile(const std::string& path, std::uint64_t start) : path_(path) {
    fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd_ < 0) throw DataError(fmt::format("{}: cannot open: {}", path, std::strerror(errno)));
    if (start > 0 && ::lseek(fd_, static_cast<off_t>(start), SEEK_SET) < 0)
      throw DataError(fmt::format("{}: cannot seek to byte {}", path, start));
    file_offset_ = start;
    buffer_.resize(kBuffer);
  }
  ~SequentialFile() { ::close(fd_); }
  SequentialFile(const SequentialFile&) = delete;
  SequentialFile& operator=(const SequentialFile&) = delete;

  const std::string& path() const { return path_; }
  /// Offset in the file of the next byte.
  std::uint64_t offset() const { return file_offset_ - (end_ - pos_); }

  /// The next n (<= kBuffer) bytes, consumed; throws DataError naming `what`
  /// at the end of the file.
  const char* take(std::size_t n, const char* what) {
    if (end_ - pos_ < n) refill(n, what);
    const char* p = buffer_.data() + pos_;
    pos_ += n;
    return p;
  }

  /// Skips n bytes (any number), or throws like take().
  void skip(std::uint64_t n, const char* what) {
    const std::size_t here = end_ - pos_;
    if (n <= here) {
      pos_ += static_cast<std::size_t>(n);
      return;
    }
    struct stat st {};
    if (::fstat(fd_, &st) != 0 || static_cast<std::uint64_t>(st.st_size) < offset() ||
        static_cast<std::uint64_t>(st.st_size) - offset() < n)
      fail_binary(path_, static_cast<std::size_t>(offset()),
                  fmt::format("expected {} more bytes for {}, got end of file", n, what));
    const std::uint64_t target = offset() + n;
    if (::lseek(fd_, static_cast<off_t>(target), SEEK_SET) < 0)
      throw DataError(fmt::format("{}: cannot seek to byte {}", path_, target));
    file_offset_ = target;
    pos_ = end_ = 0;
  }

 private:
  void refill(std::size_t n, const char* what) {
    std::memmove(buffer_.data(), buffer_.data() + pos_, end_ - pos_);
    end_ -= pos_;
    pos_ = 0;
    while (end_ < n) {
      const ssize_t got = ::read(fd_, buffer_.data() + end_, kBuffer - end_);
      if (got < 0 && errno == EINTR) continue;
      if (got < 0) throw DataError(fmt::format("{}: read failed: {}", path_, std::strerror(errno)));
      if (got == 0)
        fail_binary(path_, static_cast<std::size_t>(offset()),
                    fmt::format("expected {} bytes for {}, got end of file", n, what));
      end_ += static_cast<std::size_t>(got);
      file_offset_ += static_cast<std::uint64_t>(got);
    }
  }

  const std::string& path_;
  int fd_ = -1;
  std::vector<char> buffer_;
  std::size_t pos_ = 0, end_ = 0;
  std::uint64_t file_offset_ = 0;  ///< offset of buffer_[end_]
};

template <class T>
T load(const char* p, bool swap) {
  T v;
  if (swap) {
    char b[sizeof(T)];
    std::memcpy(b, p, sizeof(T));
    std::reverse(b, b + sizeof(T));
    std::memcpy(&v, b, sizeof(T));
  } else {
    std::memcpy(&v, p, sizeof(T));
  }
  return v;
}

/// A PLY value of type t at p, as a double (integers up to 2^32 are exact).
double load_number(const char* p, ply::PlyType t, bool swap) {
  switch (t) {
    case ply::PlyType::kInt8:
      return load<std::int8_t>(p, swap);
    case ply::PlyType::kUint8:
      return load<std::uint8_t>(p, swap);
    case ply::PlyType::kInt16:
      return load<std::int16_t>(p, swap);
    case ply::PlyType::kUint16:
      return load<std::uint16_t>(p, swap);
    case ply::PlyType::kInt32:
      return load<std::int32_t>(p, swap);
    case ply::PlyType::kUint32:
      return load<std::uint32_t>(p, swap);
    case ply::PlyType::kFloat32:
      return load<float>(p, swap);
    case ply::PlyType::kFloat64:
      return load<double>(p, swap);
  }
  return 0;
}

std::int64_t load_integer(const char* p, ply::PlyType t, bool swap) {
  return static_cast<std::int64_t>(load_number(p, t, swap));
}

std::uint32_t stl_float_bits(const char* p) {
  std::uint32_t u;
  std::memcpy(&u, p, 4);
  if constexpr (std::endian::native == std::endian::big) u = __builtin_bswap32(u);
  return u;
}

Vec3 stl_vertex(const char* p) {
  return {std::bit_cast<float>(stl_float_bits(p)), std::bit_cast<float>(stl_float_bits(p + 4)),
          std::bit_cast<float>(stl_float_bits(p + 8))};
}

/// size x count, or the largest value when that overflows (a hostile header:
/// the read then fails at the end of the file).
std::uint64_t bytes_of(std::uint64_t size, std::uint64_t count) {
  std::uint64_t bytes;
  return __builtin_mul_overflow(size, count, &bytes) ? ~std::uint64_t{0} : bytes;
}

/// The record size of an element without lists (nullopt if it has one).
std::optional<std::uint64_t> fixed_record_size(const ply::Element& e) {
  std::uint64_t size = 0;
  for (const ply::Property& p : e.props) {
    if (p.is_list) return std::nullopt;
    size += static_cast<std::uint64_t>(ply::type_size(p.type));
  }
  return size;
}

/// Reads through the items of element `e` (one with lists) in `in`.
void skip_items(SequentialFile& in, const ply::Element& e, bool swap) {
  for (std::uint64_t i = 0; i < e.count; ++i)
    for (const ply::Property& p : e.props) {
      if (!p.is_list) {
        in.skip(static_cast<std::uint64_t>(ply::type_size(p.type)), "a property value");
        continue;
      }
      const std::int64_t n = load_integer(
          in.take(static_cast<std::size_t>(ply::type_size(p.count_type)), "a list length"),
          p.count_type, swap);
      if (n < 0)
        fail_binary(in.path(), static_cast<std::size_t>(in.offset()),
                    fmt::format("negative list length {} for '{}' of {} {}", n, p.name, e.name, i));
      in.skip(static_cast<std::uint64_t>(n) * static_cast<std::uint64_t>(ply::type_size(p.type)),
              "list items");
    }
}

/// The first n bytes of a file of at least n bytes.
std::string read_prefix(const std::string& path, std::uint64_t n) {
  SequentialFile in(path, 0);
  std::string head;
  head.reserve(static_cast<std::size_t>(n));
  while (head.size() < n) {
    const std::size_t piece =
        std::min<std::size_t>(kBuffer, static_cast<std::size_t>(n) - head.size());
    head.append(in.take(piece, "the header"), piece);
  }
  return head;
}

}  // namespace

struct TriangleStream::Impl {
  std::string path;
  std::size_t chunk = 1;
  MeshFormat format = MeshFormat::kAuto;
  std::uint64_t file_size = 0;
  // STL
  std::uint64_t stl_count = 0;
  // PLY
  ply::Header header;
  bool swap = false;
  const ply::Element* vertex_element = nullptr;
  std::size_t face_index = 0;    ///< element index of the faces (elements.size(): none)
  std::uint64_t face_start = 0;  ///< offset of the first element after the vertices, or 0
  std::uint64_t vertex_start = 0;
  std::uint64_t vertex_stride = 0;
  std::array<std::uint64_t, 3> xyz_offset{};
  std::array<ply::PlyType, 3> xyz_type{};
  std::unique_ptr<MappedFileRegion> vertices;

  void open_ply(std::string_view head);
  void open_stl(std::string_view head);

  [[noreturn]] void refuse(std::string_view what) const {
    throw DataError(
        fmt::format("{}: {}; out-of-core reading takes a binary PLY or a binary STL (uncompressed)",
                    path, what));
  }

  /// Position of vertex v of the mapped block (v < its count); throws
  /// DataError at v's record when a coordinate is not finite.
  Vec3 ply_vertex(std::uint64_t v) const {
    const char* rec = vertices->view().data() + v * vertex_stride;
    Vec3 p;
    for (int k = 0; k < 3; ++k)
      p[k] = static_cast<float>(load_number(rec + xyz_offset[k], xyz_type[k], swap));
    if (!is_finite(p))
      fail_binary(path, static_cast<std::size_t>(vertex_start + v * vertex_stride),
                  fmt::format("vertex {} has a coordinate that is not a finite number", v));
    return p;
  }

  std::uint64_t ply_triangles(const TriangleVisitor& visit) const;
  std::uint64_t stl_triangles(const TriangleVisitor& visit) const;
};

void TriangleStream::Impl::open_stl(std::string_view head) {
  std::string_view start = head.substr(0, std::min<std::size_t>(head.size(), 80));
  const std::size_t word = start.find_first_not_of(" \t\r\n");
  const bool solid = word != std::string_view::npos && start.substr(word).starts_with("solid");
  if (file_size < kStlHeader) {
    if (solid) refuse("an ASCII STL file");
    fail_binary(path, static_cast<std::size_t>(file_size),
                fmt::format("expected a binary STL header of {} bytes, got {} bytes", kStlHeader,
                            file_size));
  }
  std::uint32_t count;
  std::memcpy(&count, head.data() + 80, 4);
  if constexpr (std::endian::native == std::endian::big) count = __builtin_bswap32(count);
  const std::uint64_t expected = kStlHeader + kStlRecord * std::uint64_t{count};
  if (expected != file_size && solid) refuse("an ASCII STL file");
  if (expected > file_size)
    fail_binary(
        path, static_cast<std::size_t>(file_size),
        fmt::format("expected {} bytes for {} triangles, got end of file", expected, count));
  format = MeshFormat::kStl;
  stl_count = count;
}

void TriangleStream::Impl::open_ply(std::string_view head) {
  if (head.find("end_header") == std::string_view::npos && head.size() >= kMaxPlyHeader)
    throw DataError(
        fmt::format("{}: expected 'end_header' in the first {} MiB", path, kMaxPlyHeader >> 20));
  header = ply::parse_header(head, path, nullptr);
  if (header.encoding == ply::Encoding::kAscii) refuse("an ASCII PLY file");
  swap = (header.encoding == ply::Encoding::kBig) != (std::endian::native == std::endian::big);
  format = MeshFormat::kPly;
  const auto& elements = header.elements;
  face_index = elements.size();
  for (std::size_t i = 0; i < elements.size(); ++i) {
    const ply::Element& e = elements[i];
    if (e.kind == ply::ElementKind::kVertex && !vertex_element) vertex_element = &e;
    if (e.kind == ply::ElementKind::kFace && face_index == elements.size()) face_index = i;
    if (e.kind == ply::ElementKind::kTristrips && e.count > 0)
      refuse("element 'tristrips' (triangle strips) is not read when streaming");
  }
  if (!vertex_element)
    throw DataError(fmt::format("{}: no 'vertex' element in the PLY header", path));
  const std::optional<std::uint64_t> stride = fixed_record_size(*vertex_element);
  if (!stride)
    refuse(
        fmt::format("element 'vertex' has a list property (line {}): its records have no fixed "
                    "size",
                    vertex_element->line));
  vertex_stride = *stride;
  std::uint64_t at = 0;
  for (const ply::Property& p : vertex_element->props) {
    if (p.role <= ply::kZ) {
      xyz_offset[p.role] = at;
      xyz_type[p.role] = p.type;
    }
    at += static_cast<std::uint64_t>(ply::type_size(p.type));
  }
  // Where the vertex block starts: after the elements before it (read
  // through only if one has lists).
  vertex_start = header.body;
  std::optional<SequentialFile> through;
  for (const ply::Element& e : elements) {
    if (&e == vertex_element) break;
    const std::optional<std::uint64_t> size = fixed_record_size(e);
    if (size && !through) {
      const std::uint64_t bytes = bytes_of(*size, e.count);
      vertex_start = bytes > ~vertex_start ? ~std::uint64_t{0} : vertex_start + bytes;
      continue;
    }
    if (!through) through.emplace(path, vertex_start);
    if (size)
      through->skip(bytes_of(*size, e.count), "an element before the vertices");
    else
      skip_items(*through, e, swap);
    vertex_start = through->offset();
  }
  const std::uint64_t bytes = vertex_stride * vertex_element->count;
  if (vertex_element->count > 0 && (bytes / vertex_element->count != vertex_stride ||
                                    vertex_start > file_size || file_size - vertex_start < bytes))
    fail_binary(path, static_cast<std::size_t>(std::min(vertex_start, file_size)),
                fmt::format("expected {} vertices of {} bytes, got end of file",
                            vertex_element->count, vertex_stride));
  vertices = std::make_unique<MappedFileRegion>(path, vertex_start, bytes);
  face_start = vertex_start + bytes;
}

std::uint64_t TriangleStream::Impl::ply_triangles(const TriangleVisitor& visit) const {
  if (face_index == header.elements.size()) return 0;
  const auto& elements = header.elements;
  // Read from the vertex block's end when the faces follow it, else from the body.
  const bool after = vertex_element < &elements[face_index];
  SequentialFile in(path, after ? face_start : header.body);
  const std::size_t first_element =
      after ? static_cast<std::size_t>(vertex_element - &elements[0]) + 1 : 0;
  for (std::size_t i = first_element; i < face_index; ++i) {
    const ply::Element& e = elements[i];
    if (const std::optional<std::uint64_t> size = fixed_record_size(e))
      in.skip(bytes_of(*size, e.count), "an element before the faces");
    else
      skip_items(in, e, swap);
  }
  const ply::Element& faces = elements[face_index];
  if (faces.props.empty()) return 0;  // items of no bytes: nothing to read, however many
  const std::uint64_t vertex_count = vertex_element->count;
  std::vector<StreamedTriangle> chunk_tris;
  chunk_tris.reserve(chunk);
  std::vector<std::uint64_t> corners;
  std::uint64_t triangles = 0;
  auto flush = [&] {
    if (chunk_tris.empty()) return;
    visit(chunk_tris, triangles - chunk_tris.size());
    chunk_tris.clear();
  };
  for (std::uint64_t f = 0; f < faces.count; ++f) {
    for (const ply::Property& p : faces.props) {
      const auto size = static_cast<std::size_t>(ply::type_size(p.type));
      if (!p.is_list) {
        in.skip(size, "a face property");
        continue;
      }
      const std::uint64_t list_at = in.offset();
      const std::int64_t n = load_integer(
          in.take(static_cast<std::size_t>(ply::type_size(p.count_type)), "a list length"),
          p.count_type, swap);
      if (n < 0)
        fail_binary(path, static_cast<std::size_t>(list_at),
                    fmt::format("negative list length {} for '{}' of face {}", n, p.name, f));
      if (p.role != ply::kIndices) {
        in.skip(static_cast<std::uint64_t>(n) * size, "list items");
        continue;
      }
      corners.clear();
      for (std::int64_t k = 0; k < n; ++k) {
        const std::uint64_t at = in.offset();
        const std::int64_t v = load_integer(in.take(size, "a vertex index"), p.type, swap);
        if (v < 0 || static_cast<std::uint64_t>(v) >= vertex_count)
          fail_binary(path, static_cast<std::size_t>(at),
                      fmt::format("face {}: vertex index {} out of range ({} vertices)", f, v,
                                  vertex_count));
        corners.push_back(static_cast<std::uint64_t>(v));
      }
      // Fan triangulation: (c0, ck, ck+1).
      for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
        StreamedTriangle& t = chunk_tris.emplace_back();
        t.vertex = {corners[0], corners[k], corners[k + 1]};
        for (int c = 0; c < 3; ++c) t.corner[c] = ply_vertex(t.vertex[c]);
        ++triangles;
        if (chunk_tris.size() == chunk) flush();
      }
    }
  }
  flush();
  return triangles;
}

std::uint64_t TriangleStream::Impl::stl_triangles(const TriangleVisitor& visit) const {
  SequentialFile in(path, kStlHeader);
  std::vector<StreamedTriangle> chunk_tris;
  chunk_tris.reserve(chunk);
  for (std::uint64_t f = 0; f < stl_count; ++f) {
    const std::uint64_t at = in.offset();
    const char* rec = in.take(kStlRecord, "a triangle record");
    StreamedTriangle& t = chunk_tris.emplace_back();
    for (int c = 0; c < 3; ++c) {
      t.corner[c] = stl_vertex(rec + 12 + 12 * c);
      t.vertex[c] = 3 * f + static_cast<std::uint64_t>(c);
      if (!is_finite(t.corner[c]))
        fail_binary(path, static_cast<std::size_t>(at + 12 + 12 * c),
                    fmt::format("triangle {}: expected finite vertex coordinates", f));
    }
    if (chunk_tris.size() == chunk || f + 1 == stl_count) {
      visit(chunk_tris, f + 1 - chunk_tris.size());
      chunk_tris.clear();
    }
  }
  return stl_count;
}

TriangleStream::TriangleStream(const std::string& path, const TriangleStreamOptions& options)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.path = path;
  m.chunk = std::max<std::size_t>(options.chunk_triangles, 1);
  if (path == "-") m.refuse("standard input cannot be streamed");
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    throw DataError(fmt::format("{}: cannot open: {}", path, std::strerror(errno)));
  if (!S_ISREG(st.st_mode)) throw DataError(fmt::format("{}: not a regular file", path));
  m.file_size = static_cast<std::uint64_t>(st.st_size);
  // The first bytes: the PLY header (grown until 'end_header' is in it) or the STL header.
  std::string head = read_prefix(path, std::min<std::uint64_t>(m.file_size, 4096));
  while (head.starts_with("ply") && head.find("end_header") == std::string::npos &&
         head.size() < std::min<std::uint64_t>(m.file_size, kMaxPlyHeader))
    head =
        read_prefix(path, std::min<std::uint64_t>({m.file_size, 4 * head.size(), kMaxPlyHeader}));
  if (is_gzip(head)) m.refuse("gzip-compressed (decompress it first)");
  if (head.starts_with("ply\n") || head.starts_with("ply\r\n")) {
    m.open_ply(head);
  } else {
    const MeshFormat by_name = format_from_path(path);
    if (by_name != MeshFormat::kStl && by_name != MeshFormat::kAuto)
      m.refuse("not a PLY or STL file");
    m.open_stl(head);
  }
}

TriangleStream::~TriangleStream() = default;

bool TriangleStream::accepts(const std::string& path) {
  try {
    TriangleStream probe(path);
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

MeshFormat TriangleStream::format() const {
  return impl_->format;
}
std::uint64_t TriangleStream::file_size() const {
  return impl_->file_size;
}
std::uint64_t TriangleStream::vertex_count() const {
  return impl_->format == MeshFormat::kStl ? 3 * impl_->stl_count : impl_->vertex_element->count;
}
std::uint64_t TriangleStream::face_count() const {
  if (impl_->format == MeshFormat::kStl) return impl_->stl_count;
  const auto& elements = impl_->header.elements;
  return impl_->face_index < elements.size() ? elements[impl_->face_index].count : 0;
}

std::uint64_t TriangleStream::for_each_triangle(const TriangleVisitor& visit) const {
  return impl_->format == MeshFormat::kStl ? impl_->stl_triangles(visit)
                                           : impl_->ply_triangles(visit);
}

void TriangleStream::for_each_vertex(const VertexVisitor& visit) const {
  const Impl& m = *impl_;
  if (m.format == MeshFormat::kStl) {
    std::vector<Vec3> corners;
    for_each_triangle([&](std::span<const StreamedTriangle> chunk, std::uint64_t first) {
      corners.clear();
      for (const StreamedTriangle& t : chunk)
        corners.insert(corners.end(), t.corner.begin(), t.corner.end());
      visit(corners, 3 * first);
    });
    return;
  }
  std::vector<Vec3> block;
  const std::uint64_t n = m.vertex_element->count;
  for (std::uint64_t first = 0; first < n; first += m.chunk) {
    const std::uint64_t count = std::min<std::uint64_t>(m.chunk, n - first);
    block.resize(static_cast<std::size_t>(count));
    for (std::uint64_t i = 0; i < count; ++i) block[i] = m.ply_vertex(first + i);
    visit(block, first);
  }
}

}  // namespace lodforge
