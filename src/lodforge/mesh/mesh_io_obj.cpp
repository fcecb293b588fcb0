// Wavefront OBJ reader and writer (geometry statements of the OBJ spec,
// Appendix B1 of the Advanced Visualizer manual).
//
// OBJ indexes positions, texture coordinates and normals separately per face
// corner; a TriangleMesh has one of each per vertex. Corners are therefore
// unified: vertex v keeps its number for the first (v, vt, vn) combination it
// is used with, and every further combination gets a new vertex appended
// after all positions (a split vertex at a seam). Positions no face uses are
// kept, so vertex counts match the file's `v` lines when nothing is split.
//
//   statement            | handling
//   ---------------------+-------------------------------------------------------
//   v x y z [w] [r g b]  | position (w ignored), optional vertex colour extension
//   vt u [v [w]]         | texture coordinate
//   vn x y z             | normal
//   f / fo               | polygon (triangulated), corners v, v/vt, v//vn, v/vt/vn
//   l                    | polyline -> segments
//   usemtl name          | per-face material: index of the name in first-use order
//   o g s mtllib p, ...  | ignored
//   anything else        | ignored with one warning per keyword
#include <fmt/format.h>

#include <set>
#include <unordered_map>

#include "lodforge/mesh/mesh_io_detail.h"
#include "lodforge/mesh/triangulate_polygon.h"

namespace lodforge::detail {
namespace {

constexpr std::uint32_t kAbsent = 0xffffffffu;

struct Corner {
  std::uint32_t v, vt, vn;
  bool operator==(const Corner&) const = default;
};
struct CornerHash {
  std::size_t operator()(const Corner& c) const {
    std::uint64_t h = (std::uint64_t{c.v} * 0x9E3779B97F4A7C15ULL) ^ (std::uint64_t{c.vt} << 21) ^
                      (std::uint64_t{c.vn} * 0xC2B2AE3D27D4EB4FULL);
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

class ObjReader {
 public:
  ObjReader(std::string_view data, const std::string& file, const MeshReadOptions& o)
      : in_(data, file, /*line_mode=*/true, '#'), file_(file), options_(o) {}

  TriangleMesh read() {
    while (!in_.at_end()) {
      std::string_view key = in_.token();
      if (key.empty()) {
      } else if (key == "v") {
        read_vertex();
      } else if (key == "vt") {
        float u = in_.read_float("u of a texture coordinate");
        float v = in_.at_line_end() ? 0.0f : in_.read_float("v of a texture coordinate");
        texcoords_.push_back({u, v});
      } else if (key == "vn") {
        Vec3 n;
        n.x = in_.read_float("x of a normal");
        n.y = in_.read_float("y of a normal");
        n.z = in_.read_float("z of a normal");
        normals_.push_back(n);
      } else if (key == "f" || key == "fo") {
        read_face(key);
      } else if (key == "l") {
        read_line();
      } else if (key == "usemtl") {
        std::string_view name = in_.token();
        auto [it, inserted] = material_ids_.try_emplace(
            std::string(name), static_cast<std::uint32_t>(material_ids_.size()));
        material_ = it->second;
        have_materials_ = true;
      } else if (kIgnored.count(key) == 0) {
        unknown_.insert(std::string(key));
      }
      if (key != "v" && key != "vt" && key != "vn" && key != "f" && key != "fo" && key != "l") {
        in_.next_line();
        continue;
      }
      // Trailing values (vt's w, ...) are allowed only where the spec has them.
      if (!in_.at_line_end()) {
        std::string_view extra = in_.token();
        if (key != "vt")
          in_.fail_at(extra.data(),
                      fmt::format("expected end of line, got {}", in_.describe(extra)));
      }
      in_.next_line();
    }
    return build();
  }

 private:
  static inline const std::set<std::string_view, std::less<>> kIgnored = {
      "o",         "g",        "s",        "mtllib", "p",      "vp",     "cstype",
      "deg",       "bmat",     "step",     "curv",   "curv2",  "surf",   "parm",
      "trim",      "hole",     "scrv",     "sp",     "end",    "con",    "mg",
      "bevel",     "c_interp", "d_interp", "lod",    "maplib", "usemap", "shadow_obj",
      "trace_obj", "ctech",    "stech",    "call",   "csh"};

  void read_vertex() {
    Vec3 p;
    p.x = in_.read_float("x of a vertex");
    p.y = in_.read_float("y of a vertex");
    p.z = in_.read_float("z of a vertex");
    positions_.push_back(p);
    float extra[4];
    int k = 0;
    while (k < 4 && !in_.at_line_end()) extra[k++] = in_.read_float("a vertex value");
    if (k >= 3) {
      // x y z r g b (the common colour extension); x y z w r g b has 4 extras.
      int o = k == 4 ? 1 : 0;
      if (colors_.size() + 1 < positions_.size()) colors_.resize(positions_.size() - 1, {1, 1, 1});
      colors_.push_back({extra[o], extra[o + 1], extra[o + 2]});
    } else if (k == 2) {
      in_.fail("expected 1 (w) or 3 (r g b) values after x y z, got 2");
    }
  }

  /// Resolves a 1-based or negative OBJ index against `count` items.
  std::uint32_t resolve(std::int64_t idx, std::size_t count, const char* at,
                        std::string_view what) {
    std::int64_t r = idx > 0 ? idx - 1 : static_cast<std::int64_t>(count) + idx;
    if (idx == 0 || r < 0 || r >= static_cast<std::int64_t>(count))
      in_.fail_at(at, fmt::format("face {}: {} index {} out of range ({} defined)",
                                  faces_.face_count() + 1, what, idx, count));
    return static_cast<std::uint32_t>(r);
  }

  /// Parses one integer at p (up to end), advancing p.
  std::int64_t parse_index(const char*& p, const char* end, std::string_view tok) {
    std::int64_t v = 0;
    auto r = std::from_chars(p, end, v);
    if (r.ec != std::errc() || r.ptr == p)
      in_.fail_at(p, fmt::format("expected a vertex index, got {}", in_.describe(tok)));
    p = r.ptr;
    return v;
  }

  Corner read_corner(std::string_view tok) {
    const char* p = tok.data();
    const char* end = p + tok.size();
    Corner c{kAbsent, kAbsent, kAbsent};
    c.v = resolve(parse_index(p, end, tok), positions_.size(), tok.data(), "vertex");
    if (p < end && *p == '/') {
      ++p;
      if (p < end && *p != '/') {
        const char* at = p;
        c.vt = resolve(parse_index(p, end, tok), texcoords_.size(), at, "texture coordinate");
      }
      if (p < end && *p == '/') {
        ++p;
        const char* at = p;
        c.vn = resolve(parse_index(p, end, tok), normals_.size(), at, "normal");
      }
    }
    if (p != end)
      in_.fail_at(p, fmt::format("expected a face corner v, v/vt, v//vn or v/vt/vn, got {}",
                                 in_.describe(tok)));
    return c;
  }

  std::uint32_t vertex_of(const Corner& c) {
    if (c.vt == kAbsent && c.vn == kAbsent && first_.empty()) return c.v;  // plain file
    if (first_.empty()) first_.assign(positions_.size(), Corner{kAbsent, kAbsent, kAbsent});
    if (first_.size() < positions_.size())
      first_.resize(positions_.size(), Corner{kAbsent, kAbsent, kAbsent});
    Corner& f = first_[c.v];
    if (f.v == kAbsent) {
      f = c;
      return c.v;
    }
    if (f == c) return c.v;
    auto [it, inserted] =
        split_.try_emplace(c, static_cast<std::uint32_t>(kSplitBase + extra_.size()));
    if (inserted) extra_.push_back(c);
    return it->second;
  }

  void read_face(std::string_view key) {
    corners_.clear();
    while (!in_.at_line_end()) {
      std::string_view tok = in_.token();
      Corner c = read_corner(tok);
      if (c.vt != kAbsent) any_vt_ = true;
      if (c.vn != kAbsent) any_vn_ = true;
      corners_.push_back(vertex_of(c));
    }
    if (corners_.size() < 3)
      in_.fail(fmt::format("{}: expected at least 3 corners, got {}", key, corners_.size()));
    faces_.add(corners_, material_);
  }

  void read_line() {
    std::uint32_t prev = kAbsent;
    int n = 0;
    while (!in_.at_line_end()) {
      std::string_view tok = in_.token();
      const char* p = tok.data();
      std::uint32_t v =
          resolve(parse_index(p, p + tok.size(), tok), positions_.size(), tok.data(), "vertex");
      if (p < tok.data() + tok.size() && *p == '/') {
        ++p;
        const char* at = p;
        resolve(parse_index(p, tok.data() + tok.size(), tok), texcoords_.size(), at,
                "texture coordinate");
      }
      if (p != tok.data() + tok.size())
        in_.fail_at(p, fmt::format("expected a line corner v or v/vt, got {}", in_.describe(tok)));
      if (prev != kAbsent) lines_.push_back({prev, v});
      prev = v;
      ++n;
    }
    if (n < 2) in_.fail(fmt::format("l: expected at least 2 vertices, got {}", n));
  }

  TriangleMesh build() {
    TriangleMesh m;
    std::size_t nv = positions_.size();
    std::size_t total = nv + extra_.size();
    m.positions = std::move(positions_);
    m.positions.reserve(total);
    for (const Corner& c : extra_) m.positions.push_back(m.positions[c.v]);
    if (!colors_.empty()) {
      colors_.resize(nv, {1, 1, 1});
      m.colors = std::move(colors_);
      m.colors.reserve(total);
      for (const Corner& c : extra_) m.colors.push_back(m.colors[c.v]);
    }
    auto corner_of = [&](std::uint32_t v) {
      if (v >= kSplitBase) return extra_[v - kSplitBase];
      return v < first_.size() && first_[v].v != kAbsent ? first_[v] : Corner{v, kAbsent, kAbsent};
    };
    if (any_vt_) {
      m.texcoords.resize(total);
      for (std::uint32_t v = 0; v < nv; ++v)
        if (Corner c = corner_of(v); c.vt != kAbsent) m.texcoords[v] = texcoords_[c.vt];
      for (std::size_t k = 0; k < extra_.size(); ++k)
        if (extra_[k].vt != kAbsent) m.texcoords[nv + k] = texcoords_[extra_[k].vt];
    }
    std::vector<bool> need_normal;
    if (any_vn_) {
      m.normals.resize(total);
      need_normal.assign(total, false);
      for (std::size_t v = 0; v < total; ++v) {
        Corner c = v < nv ? corner_of(static_cast<std::uint32_t>(v)) : extra_[v - nv];
        if (c.vn != kAbsent)
          m.normals[v] = normals_[c.vn];
        else
          need_normal[v] = true;
      }
    }
    // Renumber split vertices from kSplitBase + k to nv + k.
    if (!extra_.empty())
      for (std::uint32_t& v : faces_.corners())
        if (v >= kSplitBase) v = static_cast<std::uint32_t>(nv + (v - kSplitBase));
    faces_.finish(m, have_materials_, file_, options_.log);
    m.lines.insert(m.lines.end(), lines_.begin(), lines_.end());
    normalize_normals(m.normals);
    if (any_vn_) fill_missing_normals(m, need_normal);
    if (options_.log)
      for (const std::string& k : unknown_)
        options_.log->warn(LogCategory::kParse,
                           fmt::format("{}: OBJ statement '{}' ignored", file_, k));
    return m;
  }

  static constexpr std::uint32_t kSplitBase = 0x80000000u;

  TextCursor in_;
  const std::string& file_;
  const MeshReadOptions& options_;
  std::vector<Vec3> positions_, normals_, colors_;
  std::vector<Vec2> texcoords_;
  FaceCollector faces_;
  std::vector<Segment> lines_;
  std::vector<std::uint32_t> corners_;
  std::vector<Corner> first_;  // per position: the first corner using it (v == kAbsent: none)
  std::unordered_map<Corner, std::uint32_t, CornerHash> split_;
  std::vector<Corner> extra_;
  std::unordered_map<std::string, std::uint32_t> material_ids_;
  std::uint32_t material_ = 0;
  bool have_materials_ = false, any_vt_ = false, any_vn_ = false;
  std::set<std::string> unknown_;
};

}  // namespace

TriangleMesh read_obj(std::string_view data, const std::string& file, const MeshReadOptions& o) {
  return ObjReader(data, file, o).read();
}

std::string write_obj(const TriangleMesh& m) {
  std::string out = "# written by lodforge\n";
  out.reserve(m.positions.size() * 40 + m.triangles.size() * 30);
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    out += "v ";
    append_float(out, m.positions[i].x), out += ' ';
    append_float(out, m.positions[i].y), out += ' ';
    append_float(out, m.positions[i].z);
    if (m.has_colors()) {
      for (int k = 0; k < 3; ++k) out += ' ', append_float(out, m.colors[i][k]);
    }
    out += '\n';
  }
  for (const Vec2& t : m.texcoords) {
    out += "vt ";
    append_float(out, t.x), out += ' ';
    append_float(out, t.y), out += '\n';
  }
  for (const Vec3& n : m.normals) {
    out += "vn ";
    append_float(out, n.x), out += ' ';
    append_float(out, n.y), out += ' ';
    append_float(out, n.z), out += '\n';
  }
  std::uint32_t material = 0xffffffffu;
  for (std::size_t f = 0; f < m.triangles.size(); ++f) {
    if (m.has_materials() && m.materials[f] != material) {
      material = m.materials[f];
      out += fmt::format("usemtl material_{}\n", material);
    }
    out += 'f';
    for (std::uint32_t v : m.triangles[f]) {
      out += ' ';
      append_uint(out, v + 1);
      if (m.has_texcoords() || m.has_normals()) out += '/';
      if (m.has_texcoords()) append_uint(out, v + 1);
      if (m.has_normals()) out += '/', append_uint(out, v + 1);
    }
    out += '\n';
  }
  for (const Segment& s : m.lines) out += fmt::format("l {} {}\n", s[0] + 1, s[1] + 1);
  return out;
}

}  // namespace lodforge::detail
