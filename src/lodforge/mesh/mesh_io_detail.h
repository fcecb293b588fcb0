#pragma once
/// Internals of mesh_io shared by the per-format readers and writers
/// (mesh_io_ply.cpp, mesh_io_obj.cpp, mesh_io_off.cpp, mesh_io_stl.cpp).
/// Not part of the public API.
#include <charconv>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "lodforge/core/error.h"
#include "lodforge/mesh/mesh_io.h"
#include "lodforge/mesh/triangle_mesh.h"

namespace lodforge::detail {

/// Position-tracking reader over text: every error it raises is a ParseError
/// with file:line:col. In line mode (OBJ) separators do not cross line ends;
/// in free mode (PLY ASCII, OFF, STL) they do. `comment` ('\0' = none) starts
/// a comment that runs to the end of the line.
class TextCursor {
 public:
  TextCursor(std::string_view data, const std::string& file, bool line_mode, char comment)
      : begin_(data.data()),
        p_(data.data()),
        end_(data.data() + data.size()),
        file_(file),
        line_mode_(line_mode),
        comment_(comment) {}

  bool at_end() const { return p_ >= end_; }
  const char* pos() const { return p_; }
  std::size_t offset() const { return static_cast<std::size_t>(p_ - begin_); }
  int line() const { return line_; }

  /// Skips separators (and comments); in line mode stops at a line end.
  void skip_separators();
  /// Line mode: true if only blanks or a comment remain on this line.
  bool at_line_end();
  /// Moves past the next line end (or to the end of data).
  void next_line();
  /// Free mode: true if another token follows on the current line.
  bool more_on_line();
  /// The next token (maximal run of non-space characters); empty at the end
  /// (of data, or of the line in line mode).
  std::string_view token();
  /// Starts reading at byte `offset`, which is on line `line` at its column 1.
  void start_at(std::size_t offset, int line) {
    p_ = line_start_ = begin_ + offset;
    line_ = line;
  }
  /// Reads the next token as a number (finite for floating point types; int64,
  /// float and double are instantiated). On failure returns false and leaves
  /// the token in `tok` for the message, so that callers build it only then.
  template <class T>
  bool try_number(T& value, std::string_view& tok);
  /// Reads a finite number; `what` names it in the error ("x of vertex 3").
  float read_float(std::string_view what);
  double read_double(std::string_view what);
  std::int64_t read_int(std::string_view what);
  /// Expects the keyword (case-insensitive) as the next token.
  void expect(std::string_view keyword);

  [[noreturn]] void fail(std::string_view message) const { fail_at(p_, message); }
  [[noreturn]] void fail_at(const char* at, std::string_view message) const;
  /// "'tok'", "end of line" or "end of file" for messages of the form "got X".
  std::string describe(std::string_view token) const;

  /// Line and column of a position at or after the start of the current line.
  int column_of(const char* at) const { return static_cast<int>(at - line_start_) + 1; }

 private:
  const char* begin_;
  const char* p_;
  const char* end_;
  const char* line_start_ = begin_;
  int line_ = 1;
  const std::string& file_;
  bool line_mode_;
  char comment_;
};

/// Collects the faces of a reader and turns them into triangles. Polygons
/// are triangulated with triangulate_polygon (so the positions must be final
/// when finish() runs), 2-gons become line segments, smaller faces are
/// dropped; the counts of each are reported to the log.
class FaceCollector {
 public:
  void add(std::span<const std::uint32_t> corners, std::uint32_t material = 0);
  void add_line(std::uint32_t a, std::uint32_t b) { lines_.push_back({a, b}); }
  void add_triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t material = 0);
  void reserve(std::size_t faces, std::size_t corners);
  /// Number of faces added so far.
  std::size_t face_count() const { return face_start_.size(); }
  /// Writes triangles (and materials if `with_materials`) and lines into
  /// mesh; corners are indices into mesh.positions (checked by the caller).
  void finish(TriangleMesh& mesh, bool with_materials, const std::string& source, Log* log);
  std::vector<std::uint32_t>& corners() { return corners_; }

 private:
  std::vector<std::uint32_t> corners_;
  std::vector<std::uint32_t> face_start_;
  std::vector<std::uint32_t> face_material_;
  std::vector<Segment> lines_;
  std::size_t small_faces_ = 0;
};

/// Normalises normals in place (zero ones stay zero).
void normalize_normals(std::vector<Vec3>& normals);
/// Area-weighted vertex normals of `mesh` for the vertices where `need[v]`.
void fill_missing_normals(TriangleMesh& mesh, const std::vector<bool>& need);

/// Shortest round-tripping text of a float, appended to out.
void append_float(std::string& out, float v);
void append_uint(std::string& out, std::uint64_t v);

[[noreturn]] void fail_binary(const std::string& file, std::size_t offset,
                              std::string_view message);

TriangleMesh read_ply(std::string_view data, const std::string& file, const MeshReadOptions& o);
TriangleMesh read_obj(std::string_view data, const std::string& file, const MeshReadOptions& o);
TriangleMesh read_off(std::string_view data, const std::string& file, const MeshReadOptions& o);
TriangleMesh read_stl(std::string_view data, const std::string& file, const MeshReadOptions& o);

std::string write_ply(const TriangleMesh& mesh, bool binary);
std::string write_obj(const TriangleMesh& mesh);
std::string write_off(const TriangleMesh& mesh);
std::string write_stl(const TriangleMesh& mesh, bool binary);

}  // namespace lodforge::detail
