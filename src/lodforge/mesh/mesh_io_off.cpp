// OFF reader and writer (Geomview's Object File Format).
//
// Header keyword [ST][C][N]OFF (4OFF / nOFF, i.e. other dimensions, are
// rejected), or no keyword at all; then "#vertices #faces #edges" and free
// format data with '#' comments. A vertex line is
//   x y z [nx ny nz] [r g b [a]] [s t]
// and a face line "n i1 .. in [colour]" (the face colour is ignored). Vertex
// colours may be floats in [0,1] or integers 0..255: if any channel exceeds 1,
// all are divided by 255.
#include <fmt/format.h>

#include <limits>

#include "lodforge/mesh/mesh_io_detail.h"

namespace lodforge::detail {

TriangleMesh read_off(std::string_view data, const std::string& file, const MeshReadOptions& o) {
  TextCursor in(data, file, /*line_mode=*/false, '#');
  TriangleMesh m;
  bool has_st = false, has_c = false, has_n = false;
  std::string_view key = in.token();
  if (key.ends_with("OFF")) {
    std::string_view prefix = key.substr(0, key.size() - 3);
    if (prefix.starts_with("ST")) has_st = true, prefix.remove_prefix(2);
    if (prefix.starts_with("C")) has_c = true, prefix.remove_prefix(1);
    if (prefix.starts_with("N")) has_n = true, prefix.remove_prefix(1);
    if (!prefix.empty())
      in.fail_at(key.data(), fmt::format("expected OFF, COFF, NOFF, STOFF or a combination, got {} "
                                         "(only 3D OFF is supported)",
                                         in.describe(key)));
  } else {
    in.start_at(0, 1);  // no keyword: the counts come first
  }
  std::int64_t nv = in.read_int("the vertex count");
  std::int64_t nf = in.read_int("the face count");
  in.read_int("the edge count");
  if (nv < 0 || nv >= std::numeric_limits<std::uint32_t>::max())
    in.fail(fmt::format("vertex count {} out of range", nv));
  if (nf < 0) in.fail(fmt::format("negative face count {}", nf));
  std::size_t left = data.size() - in.offset();
  // Each vertex needs at least 6 bytes ("0 0 0\n"), each face at least 8.
  if (static_cast<std::uint64_t>(nv) > left / 6 + 1 ||
      static_cast<std::uint64_t>(nf) > left / 8 + 1)
    in.fail(fmt::format("{} vertices and {} faces cannot fit in the {} bytes that follow", nv, nf,
                        left));

  m.positions.reserve(static_cast<std::size_t>(nv));
  float max_channel = 0;
  for (std::int64_t i = 0; i < nv; ++i) {
    Vec3 p;
    for (int k = 0; k < 3; ++k) p[k] = in.read_float("a coordinate of a vertex");
    m.positions.push_back(p);
    if (has_n) {
      Vec3 n;
      for (int k = 0; k < 3; ++k) n[k] = in.read_float("a normal of a vertex");
      m.normals.push_back(n);
    }
    if (has_c) {
      Vec3 c;
      for (int k = 0; k < 3; ++k) c[k] = in.read_float("a colour of a vertex");
      max_channel = std::max({max_channel, c.x, c.y, c.z});
      m.colors.push_back(c);
      // Alpha is optional, so what follows on the line decides: [a] [s t].
      float rest[3];
      int extra = 0;
      while (extra < 3 && in.more_on_line()) rest[extra++] = in.read_float("a value of a vertex");
      if (has_st) {
        if (extra < 2) in.fail("expected s t after the vertex colour");
        m.texcoords.push_back({rest[extra - 2], rest[extra - 1]});
      }
    }
    if (has_st && !has_c) {
      Vec2 t;
      t.x = in.read_float("s of a vertex");
      t.y = in.read_float("t of a vertex");
      m.texcoords.push_back(t);
    }
  }
  if (has_c && max_channel > 1.0f)
    for (Vec3& c : m.colors) c = c / 255.0f;

  FaceCollector faces;
  faces.reserve(static_cast<std::size_t>(nf), static_cast<std::size_t>(nf) * 3);
  std::vector<std::uint32_t> corners;
  for (std::int64_t f = 0; f < nf; ++f) {
    std::int64_t n = in.read_int("the corner count of a face");
    if (n < 0 || static_cast<std::uint64_t>(n) > data.size() - in.offset())
      in.fail(fmt::format("face {}: corner count {} out of range", f, n));
    corners.clear();
    for (std::int64_t k = 0; k < n; ++k) {
      std::int64_t v = in.read_int("a vertex index of a face");
      if (v < 0 || v >= nv)
        in.fail(fmt::format("face {}: vertex index {} out of range ({} vertices)", f, v, nv));
      corners.push_back(static_cast<std::uint32_t>(v));
    }
    faces.add(corners);
    while (in.more_on_line()) in.token();  // face colour
  }
  faces.finish(m, false, file, o.log);
  normalize_normals(m.normals);
  return m;
}

std::string write_off(const TriangleMesh& m) {
  std::string out;
  if (m.has_texcoords()) out += "ST";
  if (m.has_colors()) out += "C";
  if (m.has_normals()) out += "N";
  out += fmt::format("OFF\n{} {} 0\n", m.positions.size(), m.triangles.size() + m.lines.size());
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    for (int k = 0; k < 3; ++k) append_float(out, m.positions[i][k]), out += ' ';
    if (m.has_normals())
      for (int k = 0; k < 3; ++k) append_float(out, m.normals[i][k]), out += ' ';
    if (m.has_colors()) {
      for (int k = 0; k < 3; ++k) append_float(out, m.colors[i][k]), out += ' ';
      out += "1 ";
    }
    if (m.has_texcoords()) {
      append_float(out, m.texcoords[i].x), out += ' ';
      append_float(out, m.texcoords[i].y), out += ' ';
    }
    out.back() = '\n';
  }
  for (const Triangle& t : m.triangles) out += fmt::format("3 {} {} {}\n", t[0], t[1], t[2]);
  for (const Segment& s : m.lines) out += fmt::format("2 {} {}\n", s[0], s[1]);
  return out;
}

}  // namespace lodforge::detail
