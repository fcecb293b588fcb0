// Range scans in the Stanford repository's layout (range-grid PLY + .conf).
// The PLY reader here is a small generic one (every property type, ASCII and
// binary) because mesh/'s reader triangulates faces and drops the range_grid
// element, the very thing a scan is.
#include "lodforge/mcoctree/range_scan.h"

#include <fmt/core.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"

namespace lodforge {
namespace {

enum class Type { kI8, kU8, kI16, kU16, kI32, kU32, kF32, kF64 };

bool parse_type(std::string_view s, Type& t) {
  static const std::pair<const char*, Type> names[] = {
      {"char", Type::kI8},    {"int8", Type::kI8},     {"uchar", Type::kU8},
      {"uint8", Type::kU8},   {"short", Type::kI16},   {"int16", Type::kI16},
      {"ushort", Type::kU16}, {"uint16", Type::kU16},  {"int", Type::kI32},
      {"int32", Type::kI32},  {"uint", Type::kU32},    {"uint32", Type::kU32},
      {"float", Type::kF32},  {"float32", Type::kF32}, {"double", Type::kF64},
      {"float64", Type::kF64}};
  for (const auto& [n, ty] : names)
    if (s == n) return t = ty, true;
  return false;
}
int type_size(Type t) {
  switch (t) {
    case Type::kI8:
    case Type::kU8:
      return 1;
    case Type::kI16:
    case Type::kU16:
      return 2;
    case Type::kI32:
    case Type::kU32:
    case Type::kF32:
      return 4;
    case Type::kF64:
      return 8;
  }
  return 0;
}

struct Property {
  std::string name;
  Type type = Type::kF32;
  bool list = false;
  Type count_type = Type::kU8;
};
struct Element {
  std::string name;
  std::int64_t count = 0;
  std::vector<Property> props;
};

// Reads values one at a time from the body, ASCII or binary.
class Body {
 public:
  Body(std::string_view data, std::size_t at, int format, const std::string& name)
      : d_(data), at_(at), format_(format), name_(name) {}

  double value(Type t) {
    if (format_ == 0) return ascii();
    int n = type_size(t);
    if (at_ + n > d_.size()) throw DataError(name_ + ": truncated range grid data");
    unsigned char b[8];
    std::memcpy(b, d_.data() + at_, n);
    at_ += n;
    if ((format_ == 2) != (std::endian::native == std::endian::big)) std::reverse(b, b + n);
    switch (t) {
      case Type::kI8:
        return static_cast<std::int8_t>(b[0]);
      case Type::kU8:
        return b[0];
      case Type::kI16:
        return get<std::int16_t>(b);
      case Type::kU16:
        return get<std::uint16_t>(b);
      case Type::kI32:
        return get<std::int32_t>(b);
      case Type::kU32:
        return get<std::uint32_t>(b);
      case Type::kF32:
        return get<float>(b);
      case Type::kF64:
        return get<double>(b);
    }
    return 0;
  }

 private:
  template <class T>
  static double get(const unsigned char* b) {
    T v;
    std::memcpy(&v, b, sizeof(T));
    return static_cast<double>(v);
  }
  double ascii() {
    while (at_ < d_.size() && std::isspace(static_cast<unsigned char>(d_[at_]))) ++at_;
    if (at_ >= d_.size()) throw DataError(name_ + ": truncated range grid data");
    double v = 0;
    auto [p, ec] = std::from_chars(d_.data() + at_, d_.data() + d_.size(), v);
    if (ec != std::errc()) {
      std::size_t end = at_;
      while (end < d_.size() && !std::isspace(static_cast<unsigned char>(d_[end]))) ++end;
      throw DataError(fmt::format("{}: expected a number, got '{}'", name_,
                                  d_.substr(at_, std::min<std::size_t>(end - at_, 20))));
    }
    at_ = static_cast<std::size_t>(p - d_.data());
    return v;
  }
  std::string_view d_;
  std::size_t at_;
  int format_;  // 0 ascii, 1 little endian, 2 big endian
  const std::string& name_;
};

// Quaternion rotation of v (unit q = (x, y, z, w)).
Vec3 quat_rotate(const std::array<float, 4>& q, const Vec3& v) {
  Vec3 u{q[0], q[1], q[2]};
  float w = q[3];
  Vec3 t = cross(u, v) * 2.0f;
  return v + t * w + cross(u, t);
}

}  // namespace

// Stanford's .conf quaternions are applied as their conjugate in column-vector
// terms (scanalyze builds the matrix for row vectors, p' = p R): with q as
// written, bun045, bun090 and bun315 land on bun000 only this way (checked
// on bun.conf: 92 % of bun045's points within 1 mm of bun000's, under 2 % with
// q itself).
Vec3 RangeScan::rotate(const Vec3& v) const {
  return quat_rotate({-rotation[0], -rotation[1], -rotation[2], rotation[3]}, v);
}
Vec3 RangeScan::to_world(const Vec3& p) const {
  return rotate(p) + translation;
}

Vec3 RangeScan::to_scan(const Vec3& p) const {
  return quat_rotate(rotation, p - translation);
}

float RangeScan::spacing() const {
  std::vector<float> d;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c + 1 < cols; ++c) {
      auto a = grid[static_cast<std::size_t>(r) * cols + c],
           b = grid[static_cast<std::size_t>(r) * cols + c + 1];
      if (a >= 0 && b >= 0) d.push_back(length(points[a] - points[b]));
    }
  if (d.empty()) return 0;
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return d[d.size() / 2];
}

namespace {

// The unit normals of the triangles point i of `scan` makes with its 4
// lattice neighbours (right/up, up/left, left/down, down/right), for each
// point: fn(i, sum of those normals, how many there are). Edges longer than
// 4 x spacing() (depth jumps) make no triangle.
template <class Fn>
void for_each_lattice_normal(const RangeScan& scan, Fn&& fn) {
  const int rows = scan.rows, cols = scan.cols;
  const auto& grid = scan.grid;
  const auto& points = scan.points;
  auto at = [&](int r, int c) -> std::int32_t {
    if (r < 0 || c < 0 || r >= rows || c >= cols) return -1;
    return grid[static_cast<std::size_t>(r) * cols + c];
  };
  // A lattice edge much longer than the spacing crosses a depth jump (an
  // occluding contour): its triangle is not surface.
  const float limit = 4 * scan.spacing();
  const float limit2 = limit > 0 ? limit * limit : INFINITY;
  // Neighbours counter-clockwise in (col, row): right, up, left, down.
  const int dr[4] = {0, 1, 0, -1}, dc[4] = {1, 0, -1, 0};
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      std::int32_t i = at(r, c);
      if (i < 0) continue;
      Vec3 sum{};
      int count = 0;
      for (int k = 0; k < 4; ++k) {
        std::int32_t a = at(r + dr[k], c + dc[k]), b = at(r + dr[(k + 1) % 4], c + dc[(k + 1) % 4]);
        if (a < 0 || b < 0) continue;
        Vec3 ea = points[a] - points[i], eb = points[b] - points[i];
        if (length_squared(ea) > limit2 || length_squared(eb) > limit2) continue;
        sum += normalized(cross(ea, eb));
        ++count;
      }
      fn(i, sum, count);
    }
}

}  // namespace

std::vector<Vec3> RangeScan::normals() const {
  std::vector<Vec3> out(points.size(), Vec3{0, 0, 1});
  double flip = 0;
  for_each_lattice_normal(*this, [&](std::int32_t i, const Vec3& sum, int) {
    if (length_squared(sum) > 0) {
      out[i] = normalized(sum);
      flip += out[i].z;
    }
  });
  // The grid's handedness (rows up or down) decides the cross products' side;
  // the sensor is on +z, so the majority must face +z.
  if (flip < 0)
    for (auto& n : out) n = -n;
  return out;
}

std::vector<float> RangeScan::weights(const std::vector<Vec3>& normals) const {
  // Confidence scales differ between scanners and tools: relative to the
  // scan's largest.
  float top = 0;
  for (float c : confidence) top = std::max(top, c);
  std::vector<float> out(points.size(), kMinWeight);
  for_each_lattice_normal(*this, [&](std::int32_t i, const Vec3&, int count) {
    float w = std::max(normals[i].z, 0.0f) * static_cast<float>(count) / 4;
    if (top > 0) w *= confidence[i] / top;
    out[i] = std::max(w, kMinWeight);
  });
  return out;
}

RangeScan read_range_grid_data(std::string_view data, const std::string& name) {
  auto fail = [&](const std::string& what) { return DataError(name + ": " + what); };
  // A list's length, refused unless it is a count (a float type may hold anything).
  auto list_length = [&](Body& in, Type count_type) {
    const double count = in.value(count_type);
    if (!(count >= 0 && count <= double(std::numeric_limits<std::int32_t>::max())))
      throw fail(fmt::format("list length {} is not a count", count));
    return static_cast<std::int64_t>(count);
  };
  if (data.substr(0, 4) != "ply\n" && data.substr(0, 5) != "ply\r\n") throw fail("not a PLY file");
  std::size_t end = data.find("end_header");
  if (end == std::string_view::npos) throw fail("PLY header without end_header");
  std::size_t body = data.find('\n', end);
  body = body == std::string_view::npos ? data.size() : body + 1;
  std::istringstream header{std::string(data.substr(0, end))};
  std::string line;
  int format = -1;
  RangeScan scan;
  scan.name = name;
  std::vector<Element> elements;
  while (std::getline(header, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream ls(line);
    std::string key;
    ls >> key;
    if (key == "format") {
      std::string f;
      ls >> f;
      format = f == "ascii"                  ? 0
               : f == "binary_little_endian" ? 1
               : f == "binary_big_endian"    ? 2
                                             : -1;
      if (format < 0) throw fail("unknown PLY format '" + f + "'");
    } else if (key == "obj_info") {
      std::string k;
      ls >> k;
      if (k == "num_cols") ls >> scan.cols;
      if (k == "num_rows") ls >> scan.rows;
    } else if (key == "element") {
      Element e;
      ls >> e.name >> e.count;
      if (!ls || e.count < 0) throw fail("bad element line '" + line + "'");
      elements.push_back(e);
    } else if (key == "property") {
      if (elements.empty()) throw fail("'property' before any 'element'");
      Property p;
      std::string t;
      ls >> t;
      if (t == "list") {
        std::string ct, it;
        ls >> ct >> it >> p.name;
        p.list = true;
        if (!parse_type(ct, p.count_type) || !parse_type(it, p.type))
          throw fail("bad property line '" + line + "'");
      } else {
        ls >> p.name;
        if (!parse_type(t, p.type)) throw fail("bad property line '" + line + "'");
      }
      elements.back().props.push_back(p);
    }
  }
  if (format < 0) throw fail("PLY header without a format line");
  if (scan.cols <= 0 || scan.rows <= 0)
    throw fail("not a range grid (no 'obj_info num_cols' / 'num_rows')");
  bool has_vertex = false, has_grid = false;
  Body in(data, body, format, name);
  for (const Element& e : elements) {
    if (e.name == "vertex") {
      has_vertex = true;
      int xyz[3] = {-1, -1, -1}, rgb[3] = {-1, -1, -1}, confidence = -1;
      static const char* const kXyz[3] = {"x", "y", "z"};
      static const char* const kRgb[2][3] = {{"red", "green", "blue"},
                                             {"diffuse_red", "diffuse_green", "diffuse_blue"}};
      for (std::size_t k = 0; k < e.props.size(); ++k) {
        const auto& n = e.props[k].name;
        if (n == "confidence") confidence = static_cast<int>(k);
        for (int a = 0; a < 3; ++a) {
          if (n == kXyz[a]) xyz[a] = static_cast<int>(k);
          if (n == kRgb[0][a] || n == kRgb[1][a]) rgb[a] = static_cast<int>(k);
        }
      }
      if (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0) throw fail("vertex element without x, y, z");
      bool colored = rgb[0] >= 0 && rgb[1] >= 0 && rgb[2] >= 0;
      scan.points.resize(static_cast<std::size_t>(e.count));
      if (colored) scan.colors.resize(scan.points.size());
      if (confidence >= 0) scan.confidence.resize(scan.points.size());
      std::vector<double> v(e.props.size());
      for (std::int64_t i = 0; i < e.count; ++i) {
        for (std::size_t k = 0; k < e.props.size(); ++k) {
          const Property& p = e.props[k];
          if (p.list) {
            const std::int64_t n = list_length(in, p.count_type);
            for (std::int64_t j = 0; j < n; ++j) in.value(p.type);
          } else {
            v[k] = in.value(p.type);
          }
        }
        Vec3 q{static_cast<float>(v[xyz[0]]), static_cast<float>(v[xyz[1]]),
               static_cast<float>(v[xyz[2]])};
        if (!is_finite(q)) throw fail(fmt::format("vertex {} has a non-finite coordinate", i));
        scan.points[i] = q;
        if (confidence >= 0) {
          const double c = v[confidence];
          if (!(c >= 0 && std::isfinite(c)))
            throw fail(fmt::format("vertex {} has confidence {}", i, c));
          scan.confidence[i] = static_cast<float>(c);
        }
        if (colored)
          for (int a = 0; a < 3; ++a)
            scan.colors[i][a] = static_cast<std::uint8_t>(std::clamp(v[rgb[a]], 0.0, 255.0));
      }
    } else if (e.name == "range_grid") {
      has_grid = true;
      if (e.count != static_cast<std::int64_t>(scan.cols) * scan.rows)
        throw fail(fmt::format("range_grid has {} entries, num_cols x num_rows is {}", e.count,
                               static_cast<std::int64_t>(scan.cols) * scan.rows));
      scan.grid.assign(static_cast<std::size_t>(e.count), -1);
      for (std::int64_t i = 0; i < e.count; ++i)
        for (const Property& p : e.props) {
          if (!p.list) {
            in.value(p.type);
            continue;
          }
          const std::int64_t n = list_length(in, p.count_type);
          for (std::int64_t j = 0; j < n; ++j) {
            const double idx = in.value(p.type);
            if (j != 0) continue;
            // The range against the vertex count is checked once every element is read.
            if (!(idx >= -1 && idx <= double(std::numeric_limits<std::int32_t>::max())))
              throw fail(fmt::format("range_grid index {} is not a vertex index", idx));
            scan.grid[i] = static_cast<std::int32_t>(idx);
          }
        }
    } else {
      for (std::int64_t i = 0; i < e.count; ++i)
        for (const Property& p : e.props) {
          const std::int64_t n = p.list ? list_length(in, p.count_type) : 1;
          for (std::int64_t j = 0; j < n; ++j) in.value(p.type);
        }
    }
  }
  if (!has_vertex) throw fail("no 'vertex' element");
  if (!has_grid) throw fail("no 'range_grid' element");
  for (auto& g : scan.grid)
    if (g < -1 || g >= static_cast<std::int64_t>(scan.points.size()))
      throw fail(fmt::format("range_grid index {} out of range (0..{})", g, scan.points.size()));
  return scan;
}

std::vector<RangeScan> read_range_scans(const std::string& path) {
  namespace fs = std::filesystem;
  fs::path p(path);
  std::error_code ec;
  if (fs::is_directory(p, ec)) {
    std::vector<fs::path> confs, plys;
    for (const auto& entry : fs::directory_iterator(p)) {
      if (entry.path().extension() == ".conf") confs.push_back(entry.path());
      if (entry.path().extension() == ".ply") plys.push_back(entry.path());
    }
    if (confs.size() == 1) return read_range_scans(confs[0].string());
    if (confs.size() > 1) throw DataError(path + ": more than one .conf file; name one");
    if (plys.empty()) throw DataError(path + ": no .conf and no .ply range scans");
    std::sort(plys.begin(), plys.end());
    std::vector<RangeScan> out;
    for (const auto& f : plys) {
      out.push_back(read_range_grid_data(read_file(f.string()), f.string()));
      out.back().name = f.filename().string();
    }
    return out;
  }
  if (p.extension() != ".conf") {
    RangeScan s = read_range_grid_data(read_file(path), path);
    s.name = p.filename().string();
    return {s};
  }
  std::istringstream conf(read_file(path));
  std::vector<RangeScan> out;
  std::string line;
  int line_no = 0;
  while (std::getline(conf, line)) {
    ++line_no;
    std::istringstream ls(line);
    std::string key;
    ls >> key;
    if (key != "bmesh") continue;  // camera lines, blank lines
    std::string name;
    Vec3 t;
    std::array<float, 4> q{};
    ls >> name >> t.x >> t.y >> t.z >> q[0] >> q[1] >> q[2] >> q[3];
    if (!ls) throw ParseError(path, line_no, 1, "expected 'bmesh NAME tx ty tz qx qy qz qw'");
    float norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!(norm > 0) || !is_finite(t))
      throw ParseError(path, line_no, 1, "bad transformation for " + name);
    for (auto& c : q) c /= norm;
    fs::path file = p.parent_path() / name;
    RangeScan s = read_range_grid_data(read_file(file.string()), file.string());
    s.name = name;
    s.translation = t;
    s.rotation = q;
    out.push_back(std::move(s));
  }
  if (out.empty()) throw DataError(path + ": no 'bmesh' lines");
  return out;
}

std::string write_range_grid_data(const RangeScan& scan) {
  const bool colored = !scan.colors.empty();
  std::string out = fmt::format(
      "ply\nformat binary_little_endian 1.0\nobj_info num_cols {}\nobj_info num_rows {}\n"
      "element vertex {}\nproperty float x\nproperty float y\nproperty float z\n",
      scan.cols, scan.rows, scan.points.size());
  const bool confident = !scan.confidence.empty();
  if (colored) out += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  if (confident) out += "property float confidence\n";
  out += fmt::format("element range_grid {}\nproperty list uchar int vertex_indices\nend_header\n",
                     scan.grid.size());
  auto put = [&](const auto& v) {
    static_assert(std::endian::native == std::endian::little);
    out.append(reinterpret_cast<const char*>(&v), sizeof(v));
  };
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    put(scan.points[i].x), put(scan.points[i].y), put(scan.points[i].z);
    if (colored) out.append(reinterpret_cast<const char*>(scan.colors[i].data()), 3);
    if (confident) put(scan.confidence[i]);
  }
  for (auto g : scan.grid) {
    if (g < 0) {
      out.push_back('\0');
    } else {
      out.push_back('\1');
      put(g);
    }
  }
  return out;
}

void write_range_scans(const std::vector<RangeScan>& scans, const std::string& dir,
                       const std::string& conf_name) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw DataError(dir + ": cannot create directory (" + ec.message() + ")");
  std::string conf = "camera 0 0 0 0 0 0 1\n";
  for (const auto& s : scans) {
    write_file_atomic((fs::path(dir) / s.name).string(), write_range_grid_data(s));
    conf += fmt::format("bmesh {} {:.9g} {:.9g} {:.9g} {:.9g} {:.9g} {:.9g} {:.9g}\n", s.name,
                        s.translation.x, s.translation.y, s.translation.z, s.rotation[0],
                        s.rotation[1], s.rotation[2], s.rotation[3]);
  }
  write_file_atomic((fs::path(dir) / conf_name).string(), conf);
}

}  // namespace lodforge
