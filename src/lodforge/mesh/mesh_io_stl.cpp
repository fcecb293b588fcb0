// STL reader and writer (3D Systems' StereoLithography Interface
// Specification, 1989), ASCII and binary.
//
// Which kind a file is cannot be read from its first bytes: many binary
// exporters begin the 80-byte header with "solid". The rule used:
//
//   size == 84 + 50 * count (count = uint32 at byte 80) | binary
//   else starts with "solid" (after blanks)               | ASCII
//   else                                                  | binary; wrong size is an error
//
// STL stores each triangle with its own three corners; equal positions are
// welded on reading (exactly equal only, see weld.h). Facet normals are
// recomputed by writers and ignored by the reader (a TriangleMesh has only
// per-vertex normals); the binary attribute word is ignored.
#include <fmt/format.h>

#include <bit>
#include <cstring>

#include "lodforge/mesh/mesh_io_detail.h"
#include "lodforge/mesh/weld.h"

namespace lodforge::detail {
namespace {

constexpr std::size_t kHeader = 84;
constexpr std::size_t kRecord = 50;

bool starts_with_solid(std::string_view data) {
  std::size_t i = data.find_first_not_of(" \t\r\n");
  if (i == std::string_view::npos || data.size() - i < 5) return false;
  std::string_view w = data.substr(i, 5);
  for (std::size_t k = 0; k < 5; ++k)
    if (std::tolower(static_cast<unsigned char>(w[k])) != "solid"[k]) return false;
  return data.size() - i == 5 || std::isspace(static_cast<unsigned char>(data[i + 5]));
}

float get_float(const char* p) {
  std::uint32_t u;
  std::memcpy(&u, p, 4);
  if constexpr (std::endian::native == std::endian::big) u = __builtin_bswap32(u);
  return std::bit_cast<float>(u);
}

TriangleMesh read_binary(std::string_view data, const std::string& file, std::uint64_t count) {
  TriangleMesh soup;
  soup.positions.reserve(count * 3);
  soup.triangles.reserve(count);
  for (std::uint64_t f = 0; f < count; ++f) {
    const char* rec = data.data() + kHeader + f * kRecord;
    for (int k = 0; k < 3; ++k) {
      const char* p = rec + 12 + 12 * k;
      Vec3 v{get_float(p), get_float(p + 4), get_float(p + 8)};
      if (!is_finite(v))
        fail_binary(file, static_cast<std::size_t>(p - data.data()),
                    fmt::format("triangle {}: expected finite vertex coordinates, got ({}, {}, {})",
                                f, v.x, v.y, v.z));
      soup.positions.push_back(v);
    }
    auto base = static_cast<std::uint32_t>(3 * f);
    soup.triangles.push_back({base, base + 1, base + 2});
  }
  return soup;
}

TriangleMesh read_ascii(std::string_view data, const std::string& file) {
  TextCursor in(data, file, /*line_mode=*/false, '\0');
  TriangleMesh soup;
  int solids = 0;
  while (true) {
    in.skip_separators();
    if (in.at_end()) break;
    in.expect("solid");
    ++solids;
    in.next_line();  // the rest of the line is the solid's name
    while (true) {
      std::string_view tok = in.token();
      auto is = [&](std::string_view kw) {
        return tok.size() == kw.size() &&
               std::equal(tok.begin(), tok.end(), kw.begin(), [](char a, char b) {
                 return std::tolower(static_cast<unsigned char>(a)) == b;
               });
      };
      if (is("endsolid")) {
        in.next_line();
        break;
      }
      if (!is("facet"))
        in.fail_at(tok.data(),
                   fmt::format("expected 'facet' or 'endsolid', got {}", in.describe(tok)));
      in.expect("normal");
      for (int k = 0; k < 3; ++k) in.read_float("a facet normal");
      in.expect("outer");
      in.expect("loop");
      auto base = static_cast<std::uint32_t>(soup.positions.size());
      for (int k = 0; k < 3; ++k) {
        in.expect("vertex");
        Vec3 v;
        for (int c = 0; c < 3; ++c) v[c] = in.read_float("a vertex coordinate");
        soup.positions.push_back(v);
      }
      in.expect("endloop");
      in.expect("endfacet");
      soup.triangles.push_back({base, base + 1, base + 2});
    }
  }
  if (solids == 0) in.fail("expected 'solid', got end of file");
  return soup;
}

}  // namespace

TriangleMesh read_stl(std::string_view data, const std::string& file, const MeshReadOptions& o) {
  TriangleMesh soup;
  std::uint32_t count = 0;
  if (data.size() >= kHeader) std::memcpy(&count, data.data() + 80, 4);
  if constexpr (std::endian::native == std::endian::big) count = __builtin_bswap32(count);
  std::uint64_t expected = kHeader + kRecord * std::uint64_t{count};
  if (data.size() >= kHeader && expected == data.size()) {
    soup = read_binary(data, file, count);
  } else if (starts_with_solid(data)) {
    soup = read_ascii(data, file);
  } else if (data.size() < kHeader) {
    fail_binary(file, data.size(),
                fmt::format("expected a binary STL header of {} bytes or an ASCII 'solid', got {} "
                            "bytes",
                            kHeader, data.size()));
  } else if (data.size() > expected) {
    if (o.log)
      o.log->warn(LogCategory::kParse, fmt::format("{}: {} bytes after the {} triangles ignored",
                                                   file, data.size() - expected, count));
    soup = read_binary(data, file, count);
  } else {
    fail_binary(
        file, data.size(),
        fmt::format("expected {} bytes for {} triangles, got end of file", expected, count));
  }
  return std::move(weld(soup, {.remove_degenerate = false}).mesh);
}

std::string write_stl(const TriangleMesh& m, bool binary) {
  std::string out;
  auto facet_normal = [&](const Triangle& t) {
    return normalized(
        cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]));
  };
  if (binary) {
    out.assign(80, ' ');
    std::memcpy(out.data(), "binary STL written by lodforge", 30);
    auto put = [&out](auto v) {
      if constexpr (std::endian::native == std::endian::big) {
        auto u = std::bit_cast<std::uint32_t>(v);
        u = __builtin_bswap32(u);
        out.append(reinterpret_cast<const char*>(&u), 4);
      } else {
        out.append(reinterpret_cast<const char*>(&v), sizeof v);
      }
    };
    put(static_cast<std::uint32_t>(m.triangles.size()));
    for (const Triangle& t : m.triangles) {
      Vec3 n = facet_normal(t);
      put(n.x), put(n.y), put(n.z);
      for (std::uint32_t v : t) put(m.positions[v].x), put(m.positions[v].y), put(m.positions[v].z);
      out.append(2, '\0');
    }
    return out;
  }
  out = "solid lodforge\n";
  auto vec = [&out](const Vec3& v) {
    for (int k = 0; k < 3; ++k) out += ' ', append_float(out, v[k]);
    out += '\n';
  };
  for (const Triangle& t : m.triangles) {
    out += "facet normal";
    vec(facet_normal(t));
    out += "outer loop\n";
    for (std::uint32_t v : t) out += "vertex", vec(m.positions[v]);
    out += "endloop\nendfacet\n";
  }
  out += "endsolid lodforge\n";
  return out;
}

}  // namespace lodforge::detail
