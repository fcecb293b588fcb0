// PLY reader and writer (Turk, "The PLY Polygon File Format", 1994).
//
// The header is parsed into a plan (per property: its type and the role it
// plays for us, or "skip"); the body is then read by one template for the
// three encodings, so the ASCII, little- and big-endian paths cannot drift
// apart. Understood elements:
//
//   element    properties used                                   result
//   ---------  ------------------------------------------------  -----------------------
//   vertex     x y z, nx ny nz, red green blue (alpha ignored),  positions and attributes
//              s t | u v | texture_u texture_v | texture_s texture_t
//   face       vertex_indices | vertex_index (list), material_index   polygons, materials
//   tristrips  vertex_indices (list, -1 = restart)               triangles
//   edge       vertex1 vertex2                                   line segments
//   others     skipped (lists too), with a warning
#include <fmt/format.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

#include "lodforge/mesh/mesh_io_detail.h"
#include "lodforge/mesh/ply_header.h"

namespace lodforge::detail {
using namespace ply;  // NOLINT(google-build-using-namespace): the reader of that format
namespace {

/// Scale that maps an integer colour channel to [0,1].
double colour_scale(PlyType t) {
  switch (t) {
    case PlyType::kInt8:
      return 1.0 / 127;
    case PlyType::kUint8:
      return 1.0 / 255;
    case PlyType::kInt16:
      return 1.0 / 32767;
    case PlyType::kUint16:
      return 1.0 / 65535;
    case PlyType::kInt32:
      return 1.0 / 2147483647.0;
    case PlyType::kUint32:
      return 1.0 / 4294967295.0;
    default:
      return 1.0;
  }
}

Role role_of(ElementKind kind, std::string_view name, bool is_list) {
  if (kind == ElementKind::kVertex && !is_list) {
    static constexpr std::pair<std::string_view, Role> kVertexRoles[] = {
        {"x", kX},
        {"y", kY},
        {"z", kZ},
        {"nx", kNx},
        {"ny", kNy},
        {"nz", kNz},
        {"red", kRed},
        {"green", kGreen},
        {"blue", kBlue},
        {"diffuse_red", kRed},
        {"diffuse_green", kGreen},
        {"diffuse_blue", kBlue},
        {"s", kU},
        {"t", kV},
        {"u", kU},
        {"v", kV},
        {"texture_u", kU},
        {"texture_v", kV},
        {"texture_s", kU},
        {"texture_t", kV},
    };
    for (auto [n, r] : kVertexRoles)
      if (n == name) return r;
  }
  if (kind == ElementKind::kFace) {
    if (is_list && (name == "vertex_indices" || name == "vertex_index")) return kIndices;
    if (!is_list && name == "material_index") return kMaterial;
  }
  if (kind == ElementKind::kTristrips && is_list && name == "vertex_indices") return kStrip;
  if (kind == ElementKind::kEdge && !is_list) {
    if (name == "vertex1") return kVertex1;
    if (name == "vertex2") return kVertex2;
  }
  return kSkip;
}

}  // namespace

Header ply::parse_header(std::string_view data, const std::string& file, Log* log) {
  Header h;
  TextCursor in(data, file, /*line_mode=*/true, '\0');
  if (in.token() != "ply") in.fail_at(data.data(), "expected 'ply' at the start of a PLY file");
  in.next_line();
  bool have_format = false;
  while (true) {
    if (in.at_end()) in.fail("expected 'end_header', got end of file");
    std::string_view key = in.token();
    if (key == "format") {
      std::string_view enc = in.token();
      if (enc == "ascii")
        h.encoding = Encoding::kAscii;
      else if (enc == "binary_little_endian")
        h.encoding = Encoding::kLittle;
      else if (enc == "binary_big_endian")
        h.encoding = Encoding::kBig;
      else
        in.fail_at(enc.data(), fmt::format("expected 'ascii', 'binary_little_endian' or "
                                           "'binary_big_endian', got {}",
                                           in.describe(enc)));
      std::string_view version = in.token();
      if (version != "1.0" && version != "1")
        in.fail_at(version.data(),
                   fmt::format("expected version '1.0', got {}", in.describe(version)));
      have_format = true;
    } else if (key == "comment" || key == "obj_info" || key.empty()) {
      // nothing to use
    } else if (key == "element") {
      Element e;
      e.line = in.line();
      std::string_view name = in.token();
      if (name.empty()) in.fail("expected an element name, got end of line");
      e.name = std::string(name);
      std::int64_t count = in.read_int("the element count");
      if (count < 0) in.fail("expected a non-negative element count");
      e.count = static_cast<std::uint64_t>(count);
      e.kind = name == "vertex"      ? ElementKind::kVertex
               : name == "face"      ? ElementKind::kFace
               : name == "tristrips" ? ElementKind::kTristrips
               : name == "edge"      ? ElementKind::kEdge
                                     : ElementKind::kOther;
      h.elements.push_back(std::move(e));
    } else if (key == "property") {
      if (h.elements.empty()) in.fail_at(key.data(), "'property' before any 'element'");
      Property p;
      auto parse_type = [&](std::string_view t) {
        for (const TypeInfo& info : kTypes)
          if (t == info.names[0] || t == info.names[1]) return info.type;
        in.fail_at(t.data(), fmt::format("expected a property type (char, uchar, short, ushort, "
                                         "int, uint, float, double), got {}",
                                         in.describe(t)));
      };
      std::string_view t = in.token();
      if (t == "list") {
        p.is_list = true;
        std::string_view ct = in.token();
        p.count_type = parse_type(ct);
        if (is_float(p.count_type))
          in.fail_at(ct.data(),
                     "expected an integer type for a list count, got " + in.describe(ct));
        t = in.token();
      }
      p.type = parse_type(t);
      std::string_view name = in.token();
      if (name.empty()) in.fail("expected a property name, got end of line");
      p.name = std::string(name);
      Element& e = h.elements.back();
      p.role = role_of(e.kind, name, p.is_list);
      if ((p.role == kIndices || p.role == kStrip || p.role == kVertex1 || p.role == kVertex2 ||
           p.role == kMaterial) &&
          is_float(p.type))
        in.fail_at(t.data(),
                   fmt::format("expected an integer type for '{}', got {}", name, in.describe(t)));
      // The first property of a role wins; a set of roles keeps headers of
      // many properties linear.
      if (p.role != kSkip) {
        const std::uint64_t bit = std::uint64_t{1} << p.role;
        if (e.roles_taken & bit) p.role = kSkip;
        e.roles_taken |= bit;
      }
      e.props.push_back(std::move(p));
    } else if (key == "end_header") {
      in.next_line();
      break;
    } else {
      in.fail_at(key.data(), fmt::format("expected 'element', 'property', 'comment' or "
                                         "'end_header', got {}",
                                         in.describe(key)));
    }
    if (!in.at_line_end()) {
      std::string_view extra = in.token();
      if (key != "comment" && key != "obj_info")
        in.fail_at(extra.data(), fmt::format("expected end of line, got {}", in.describe(extra)));
    }
    in.next_line();
  }
  if (!have_format) throw ParseError(file, 2, 1, "expected a 'format' line in the PLY header");
  h.body = in.offset();

  for (const Element& e : h.elements) {
    bool has = false;
    for (const Property& p : e.props) has |= p.role != kSkip;
    if (log && e.kind == ElementKind::kOther && e.count > 0)
      log->warn(LogCategory::kParse, fmt::format("{}:{}: element '{}' ({} items) skipped", file,
                                                 e.line, e.name, e.count));
    if (e.kind == ElementKind::kVertex) {
      int xyz = 0;
      for (const Property& p : e.props) xyz += p.role <= kZ;
      if (xyz != 3)
        throw ParseError(file, e.line, 1, "element 'vertex' needs properties 'x', 'y' and 'z'");
    }
    if (e.kind == ElementKind::kFace && e.count > 0 && !has && log)
      log->warn(LogCategory::kParse,
                fmt::format("{}:{}: element 'face' has no 'vertex_indices' list", file, e.line));
  }
  return h;
}

namespace {

// ---- The two value sources -------------------------------------------------

/// What is being read, turned into words only for an error message.
struct Where {
  const Element* e;
  std::uint64_t i;
  const Property* p;
  std::string str() const { return fmt::format("'{}' of {} {}", p->name, e->name, i); }
};

class AsciiIn {
 public:
  AsciiIn(std::string_view data, const std::string& file, std::size_t body, int first_line)
      : cursor_(data, file, /*line_mode=*/false, '\0'), size_(data.size()) {
    cursor_.start_at(body, first_line);
  }

  double number(PlyType t, const Where& w) {
    if (t == PlyType::kFloat32) return get<float>("a number", w);
    if (t == PlyType::kFloat64) return get<double>("a number", w);
    return static_cast<double>(integer(t, w));
  }
  std::int64_t integer(PlyType, const Where& w) { return get<std::int64_t>("an integer", w); }
  void skip(PlyType, const Where& w) {
    std::string_view tok = cursor_.token();
    last_ = tok.data();
    if (tok.empty()) cursor_.fail(fmt::format("expected a value for {}, got end of file", w.str()));
  }
  void skip_n(PlyType, std::int64_t n) {
    for (std::int64_t i = 0; i < n; ++i)
      if (cursor_.token().empty()) cursor_.fail("expected a list item, got end of file");
  }
  std::size_t remaining() const { return size_ - cursor_.offset(); }
  std::size_t min_size(PlyType) const { return 2; }
  /// Fails at the start of the last value read.
  [[noreturn]] void fail(std::string_view message) { cursor_.fail_at(last_, message); }

 private:
  template <class T>
  T get(std::string_view kind, const Where& w) {
    T v{};
    std::string_view tok;
    bool ok = cursor_.try_number(v, tok);
    last_ = tok.data();
    if (!ok)
      cursor_.fail_at(tok.data(), fmt::format("expected {} for {}, got {}", kind, w.str(),
                                              cursor_.describe(tok)));
    return v;
  }

  TextCursor cursor_;
  std::size_t size_;
  const char* last_ = nullptr;
};

class BinaryIn {
 public:
  BinaryIn(std::string_view data, const std::string& file, std::size_t body, bool big)
      : data_(data),
        file_(file),
        pos_(body),
        swap_(big != (std::endian::native == std::endian::big)) {}

  double number(PlyType t, const Where& w) {
    need(type_size(t), w);
    double v = 0;
    switch (t) {
      case PlyType::kInt8:
        v = get<std::int8_t>();
        break;
      case PlyType::kUint8:
        v = get<std::uint8_t>();
        break;
      case PlyType::kInt16:
        v = get<std::int16_t>();
        break;
      case PlyType::kUint16:
        v = get<std::uint16_t>();
        break;
      case PlyType::kInt32:
        v = get<std::int32_t>();
        break;
      case PlyType::kUint32:
        v = get<std::uint32_t>();
        break;
      case PlyType::kFloat32:
        v = get<float>();
        break;
      case PlyType::kFloat64:
        v = get<double>();
        break;
    }
    if (!std::isfinite(v)) {
      pos_ -= type_size(t);
      fail(fmt::format("expected a finite number for {}, got {}", w.str(), v));
    }
    return v;
  }
  std::int64_t integer(PlyType t, const Where& w) {
    need(type_size(t), w);
    switch (t) {
      case PlyType::kInt8:
        return get<std::int8_t>();
      case PlyType::kUint8:
        return get<std::uint8_t>();
      case PlyType::kInt16:
        return get<std::int16_t>();
      case PlyType::kUint16:
        return get<std::uint16_t>();
      case PlyType::kInt32:
        return get<std::int32_t>();
      case PlyType::kUint32:
        return get<std::uint32_t>();
      default:
        break;
    }
    fail(fmt::format("expected an integer type for {}", w.str()));
  }
  void skip(PlyType t, const Where& w) {
    need(type_size(t), w);
    pos_ += static_cast<std::size_t>(type_size(t));
  }
  void skip_n(PlyType t, std::int64_t n) {
    std::uint64_t bytes = static_cast<std::uint64_t>(n) * static_cast<std::uint64_t>(type_size(t));
    if (bytes > data_.size() - pos_)
      fail(fmt::format("expected {} bytes of list data, got {}", bytes, data_.size() - pos_));
    pos_ += bytes;
  }
  std::size_t remaining() const { return data_.size() - pos_; }
  std::size_t min_size(PlyType t) const { return static_cast<std::size_t>(type_size(t)); }
  [[noreturn]] void fail(std::string_view message) { fail_binary(file_, pos_, message); }

 private:
  void need(int bytes, const Where& w) {
    if (data_.size() - pos_ < static_cast<std::size_t>(bytes))
      fail(fmt::format("expected {} bytes for {}, got end of file", bytes, w.str()));
  }
  template <class T>
  T get() {
    T v;
    if (swap_) {
      unsigned char b[sizeof(T)];
      std::memcpy(b, data_.data() + pos_, sizeof(T));
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
      std::memcpy(&v, b, sizeof(T));
    } else {
      std::memcpy(&v, data_.data() + pos_, sizeof(T));
    }
    pos_ += sizeof(T);
    return v;
  }

  std::string_view data_;
  const std::string& file_;
  std::size_t pos_;
  bool swap_;
};

// ---- The body ---------------------------------------------------------------

struct Body {
  TriangleMesh mesh;
  FaceCollector faces;
  bool vertices_read = false;
  bool have_normals = false, have_colors = false, have_texcoords = false, have_materials = false;
  std::vector<std::uint32_t> strip_triangles;  // flat, validated later if needed
  std::uint64_t vertex_count = 0;
};

template <class In>
class BodyReader {
 public:
  BodyReader(In& in, const std::string& file) : in_(in), file_(file) {}

  void read(const Header& h, Body& b) {
    for (const Element& e : h.elements) {
      if (e.props.empty() || e.count == 0) continue;
      // Never reserve more items than the remaining data could hold.
      std::size_t min_item = 0;
      for (const Property& p : e.props) min_item += in_.min_size(p.is_list ? p.count_type : p.type);
      std::size_t cap = static_cast<std::size_t>(std::min<std::uint64_t>(
          e.count, in_.remaining() / std::max<std::size_t>(min_item, 1) + 1));
      switch (e.kind) {
        case ElementKind::kVertex:
          if (b.vertices_read) {
            skip_element(e);
          } else {
            read_vertices(e, b, cap);
          }
          break;
        case ElementKind::kFace:
          b.faces.reserve(cap, cap * 3);
          read_items(e, b);
          break;
        default:
          read_items(e, b);
      }
    }
  }

 private:
  void read_vertices(const Element& e, Body& b, std::size_t cap) {
    if (e.count >= std::numeric_limits<std::uint32_t>::max())
      in_.fail(fmt::format("{} vertices are more than this reader supports", e.count));
    TriangleMesh& m = b.mesh;
    bool slot_used[kSlots] = {};
    PlyType slot_type[kSlots] = {};
    for (const Property& p : e.props)
      if (p.role < kSlots) slot_used[p.role] = true, slot_type[p.role] = p.type;
    b.have_normals = slot_used[kNx] && slot_used[kNy] && slot_used[kNz];
    b.have_colors = slot_used[kRed] && slot_used[kGreen] && slot_used[kBlue];
    b.have_texcoords = slot_used[kU] && slot_used[kV];
    double cscale[3] = {colour_scale(slot_type[kRed]), colour_scale(slot_type[kGreen]),
                        colour_scale(slot_type[kBlue])};
    m.positions.reserve(cap);
    if (b.have_normals) m.normals.reserve(cap);
    if (b.have_colors) m.colors.reserve(cap);
    if (b.have_texcoords) m.texcoords.reserve(cap);
    double v[kSlots] = {};
    {
      for (std::uint64_t i = 0; i < e.count; ++i) {
        for (const Property& p : e.props) {
          if (p.is_list) {
            std::int64_t n = in_.integer(p.count_type, Where{&e, i, &p});
            if (n < 0)
              in_.fail(fmt::format("negative list length {} for {}", n, Where{&e, i, &p}.str()));
            in_.skip_n(p.type, n);
          } else if (p.role < kSlots) {
            v[p.role] = in_.number(p.type, Where{&e, i, &p});
          } else {
            in_.skip(p.type, Where{&e, i, &p});
          }
        }
        m.positions.push_back(
            {static_cast<float>(v[kX]), static_cast<float>(v[kY]), static_cast<float>(v[kZ])});
        if (b.have_normals)
          m.normals.push_back(
              {static_cast<float>(v[kNx]), static_cast<float>(v[kNy]), static_cast<float>(v[kNz])});
        if (b.have_colors)
          m.colors.push_back({static_cast<float>(v[kRed] * cscale[0]),
                              static_cast<float>(v[kGreen] * cscale[1]),
                              static_cast<float>(v[kBlue] * cscale[2])});
        if (b.have_texcoords)
          m.texcoords.push_back({static_cast<float>(v[kU]), static_cast<float>(v[kV])});
        if (!is_finite(m.positions.back()))
          in_.fail(fmt::format("vertex {} has a coordinate that is not a finite number", i));
      }
    }
    b.vertices_read = true;
    b.vertex_count = e.count;
  }

  void skip_element(const Element& e) {
    {
      for (std::uint64_t i = 0; i < e.count; ++i)
        for (const Property& p : e.props) {
          if (p.is_list) {
            std::int64_t n = in_.integer(p.count_type, Where{&e, i, &p});
            if (n < 0)
              in_.fail(fmt::format("negative list length {} for {}", n, Where{&e, i, &p}.str()));
            in_.skip_n(p.type, n);
          } else {
            in_.skip(p.type, Where{&e, i, &p});
          }
        }
    }
  }

  /// Reads a vertex index; checks its range at once if the vertices are known.
  std::uint32_t index(const Element& e, std::uint64_t i, const Property& p, const Body& b) {
    std::int64_t v = in_.integer(p.type, Where{&e, i, &p});
    if (v < 0 || static_cast<std::uint64_t>(v) >= std::numeric_limits<std::uint32_t>::max() ||
        (b.vertices_read && static_cast<std::uint64_t>(v) >= b.vertex_count))
      in_.fail(fmt::format("{} {}: vertex index {} out of range ({} vertices)", e.name, i, v,
                           b.vertex_count));
    return static_cast<std::uint32_t>(v);
  }

  void read_items(const Element& e, Body& b) {
    std::vector<std::uint32_t> corners;
    std::vector<std::int64_t> strip;
    {
      for (std::uint64_t i = 0; i < e.count; ++i) {
        std::uint32_t material = 0;
        std::int64_t ends[2] = {-1, -1};
        bool have_corners = false;
        for (const Property& p : e.props) {
          if (p.is_list) {
            std::int64_t n = in_.integer(p.count_type, Where{&e, i, &p});
            if (n < 0)
              in_.fail(fmt::format("negative list length {} for {}", n, Where{&e, i, &p}.str()));
            if (static_cast<std::uint64_t>(n) > in_.remaining())
              in_.fail(fmt::format("list of {} items for {} is longer than the rest of the file", n,
                                   Where{&e, i, &p}.str()));
            if (p.role == kIndices) {
              corners.clear();
              for (std::int64_t k = 0; k < n; ++k) corners.push_back(index(e, i, p, b));
              have_corners = true;
            } else if (p.role == kStrip) {
              read_strip(e, i, p, b, n, strip);
            } else {
              in_.skip_n(p.type, n);
            }
          } else if (p.role == kMaterial) {
            std::int64_t m = in_.integer(p.type, Where{&e, i, &p});
            if (m < 0 || m > std::numeric_limits<std::int32_t>::max())
              in_.fail(fmt::format("material_index {} of face {} out of range", m, i));
            material = static_cast<std::uint32_t>(m);
            b.have_materials = true;
          } else if (p.role == kVertex1 || p.role == kVertex2) {
            ends[p.role - kVertex1] = index(e, i, p, b);
          } else {
            in_.skip(p.type, Where{&e, i, &p});
          }
        }
        if (have_corners) b.faces.add(corners, material);
        if (e.kind == ElementKind::kEdge && ends[0] >= 0 && ends[1] >= 0)
          b.faces.add_line(static_cast<std::uint32_t>(ends[0]),
                           static_cast<std::uint32_t>(ends[1]));
      }
    }
  }

  /// Triangle strips with -1 restarts; orientation alternates along a strip,
  /// and the zero-area triangles that stitch strips together are dropped.
  void read_strip(const Element& e, std::uint64_t i, const Property& p, Body& b, std::int64_t n,
                  std::vector<std::int64_t>& strip) {
    strip.clear();
    auto flush = [&] {
      for (std::size_t k = 2; k < strip.size(); ++k) {
        auto a = static_cast<std::uint32_t>(strip[k - 2]);
        auto c = static_cast<std::uint32_t>(strip[k - 1]);
        auto d = static_cast<std::uint32_t>(strip[k]);
        if (a == c || c == d || d == a) continue;
        if (k % 2 == 0)
          b.faces.add_triangle(a, c, d);
        else
          b.faces.add_triangle(c, a, d);
      }
      strip.clear();
    };
    for (std::int64_t k = 0; k < n; ++k) {
      std::int64_t v = in_.integer(p.type, Where{&e, i, &p});
      if (v == -1) {
        flush();
        continue;
      }
      if (v < 0 || v >= std::numeric_limits<std::uint32_t>::max() ||
          (b.vertices_read && static_cast<std::uint64_t>(v) >= b.vertex_count))
        in_.fail(fmt::format("{} {}: vertex index {} out of range ({} vertices)", e.name, i, v,
                             b.vertex_count));
      strip.push_back(v);
    }
    flush();
  }

  In& in_;
  const std::string& file_;
};

int count_lines(std::string_view s) {
  return static_cast<int>(std::count(s.begin(), s.end(), '\n'));
}

}  // namespace

TriangleMesh read_ply(std::string_view data, const std::string& file, const MeshReadOptions& o) {
  Header h = parse_header(data, file, o.log);
  Body b;
  if (h.encoding == Encoding::kAscii) {
    AsciiIn in(data, file, h.body, count_lines(data.substr(0, h.body)) + 1);
    BodyReader<AsciiIn>(in, file).read(h, b);
  } else {
    BinaryIn in(data, file, h.body, h.encoding == Encoding::kBig);
    BodyReader<BinaryIn>(in, file).read(h, b);
  }
  if (!b.vertices_read) {
    bool declared = false;
    for (const Element& e : h.elements) declared |= e.kind == ElementKind::kVertex;
    if (!declared) throw DataError(fmt::format("{}: no 'vertex' element in the PLY header", file));
  }
  // Faces that came before the vertices could not be checked while reading.
  const auto& corners = b.faces.corners();
  for (std::size_t k = 0; k < corners.size(); ++k)
    if (corners[k] >= b.mesh.positions.size())
      throw DataError(fmt::format("{}: vertex index {} out of range ({} vertices)", file,
                                  corners[k], b.mesh.positions.size()));
  b.faces.finish(b.mesh, b.have_materials, file, o.log);
  for (const Segment& s : b.mesh.lines)
    if (s[0] >= b.mesh.positions.size() || s[1] >= b.mesh.positions.size())
      throw DataError(fmt::format("{}: edge vertex index out of range ({} vertices)", file,
                                  b.mesh.positions.size()));
  normalize_normals(b.mesh.normals);
  return std::move(b.mesh);
}

std::string write_ply(const TriangleMesh& m, bool binary) {
  std::string out = "ply\n";
  out += binary ? (std::endian::native == std::endian::little ? "format binary_little_endian 1.0\n"
                                                              : "format binary_big_endian 1.0\n")
                : "format ascii 1.0\n";
  out += "comment written by lodforge\n";
  out += fmt::format("element vertex {}\nproperty float x\nproperty float y\nproperty float z\n",
                     m.positions.size());
  if (m.has_normals()) out += "property float nx\nproperty float ny\nproperty float nz\n";
  if (m.has_colors()) out += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  if (m.has_texcoords()) out += "property float s\nproperty float t\n";
  out +=
      fmt::format("element face {}\nproperty list uchar int vertex_indices\n", m.triangles.size());
  if (m.has_materials()) out += "property int material_index\n";
  if (!m.lines.empty())
    out += fmt::format("element edge {}\nproperty int vertex1\nproperty int vertex2\n",
                       m.lines.size());
  out += "end_header\n";

  auto byte = [](float c) {
    return static_cast<std::uint8_t>(std::lround(std::clamp(c, 0.0f, 1.0f) * 255.0f));
  };
  if (binary) {
    auto put = [&out](auto v) {
      char b[sizeof v];
      std::memcpy(b, &v, sizeof v);
      out.append(b, sizeof v);
    };
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
      put(m.positions[i].x), put(m.positions[i].y), put(m.positions[i].z);
      if (m.has_normals()) put(m.normals[i].x), put(m.normals[i].y), put(m.normals[i].z);
      if (m.has_colors())
        put(byte(m.colors[i].x)), put(byte(m.colors[i].y)), put(byte(m.colors[i].z));
      if (m.has_texcoords()) put(m.texcoords[i].x), put(m.texcoords[i].y);
    }
    for (std::size_t f = 0; f < m.triangles.size(); ++f) {
      put(std::uint8_t{3});
      for (std::uint32_t v : m.triangles[f]) put(static_cast<std::int32_t>(v));
      if (m.has_materials()) put(static_cast<std::int32_t>(m.materials[f]));
    }
    for (const Segment& s : m.lines)
      put(static_cast<std::int32_t>(s[0])), put(static_cast<std::int32_t>(s[1]));
    return out;
  }
  auto num = [&out](float v, char sep) {
    append_float(out, v);
    out += sep;
  };
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    num(m.positions[i].x, ' '), num(m.positions[i].y, ' '), num(m.positions[i].z, ' ');
    if (m.has_normals())
      num(m.normals[i].x, ' '), num(m.normals[i].y, ' '), num(m.normals[i].z, ' ');
    if (m.has_colors())
      out +=
          fmt::format("{} {} {} ", byte(m.colors[i].x), byte(m.colors[i].y), byte(m.colors[i].z));
    if (m.has_texcoords()) num(m.texcoords[i].x, ' '), num(m.texcoords[i].y, ' ');
    out.back() = '\n';
  }
  for (std::size_t f = 0; f < m.triangles.size(); ++f) {
    out += "3";
    for (std::uint32_t v : m.triangles[f]) out += ' ', append_uint(out, v);
    if (m.has_materials()) out += ' ', append_uint(out, m.materials[f]);
    out += '\n';
  }
  for (const Segment& s : m.lines) out += fmt::format("{} {}\n", s[0], s[1]);
  return out;
}

}  // namespace lodforge::detail
