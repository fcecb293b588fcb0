// Vertex welding by hashing.
//
// Exact mode hashes the bit patterns of the coordinates (with -0 turned into
// +0 so that the two compare equal, as they do as floats) in an open-addressing
// table: one probe sequence per vertex, O(V) expected. Epsilon mode hashes
// vertices into a uniform grid of cell size epsilon and compares a vertex with
// the kept vertices of the 27 surrounding cells, also O(V) expected for inputs
// that are not absurdly dense.
#include "lodforge/mesh/weld.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

namespace lodforge {
namespace {

constexpr std::uint32_t kEmpty = 0xffffffffu;

std::uint32_t float_bits(float f) {
  return std::bit_cast<std::uint32_t>(f + 0.0f);
}

std::uint64_t mix(std::uint64_t h) {
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdULL;
  h ^= h >> 33;
  h *= 0xc4ceb9fe1a85ec53ULL;
  h ^= h >> 33;
  return h;
}

std::uint64_t hash_position(const Vec3& p) {
  std::uint64_t h = mix(float_bits(p.x));
  h = mix(h ^ (std::uint64_t{float_bits(p.y)} << 1));
  return mix(h ^ (std::uint64_t{float_bits(p.z)} << 2));
}

bool same_bits(const Vec3& a, const Vec3& b) {
  return float_bits(a.x) == float_bits(b.x) && float_bits(a.y) == float_bits(b.y) &&
         float_bits(a.z) == float_bits(b.z);
}

bool same_attributes(const TriangleMesh& m, std::uint32_t a, std::uint32_t b) {
  if (m.has_normals() && !same_bits(m.normals[a], m.normals[b])) return false;
  if (m.has_colors() && !same_bits(m.colors[a], m.colors[b])) return false;
  if (m.has_texcoords() && !(float_bits(m.texcoords[a].x) == float_bits(m.texcoords[b].x) &&
                             float_bits(m.texcoords[a].y) == float_bits(m.texcoords[b].y)))
    return false;
  return true;
}

/// Representative old vertex for every old vertex (itself if kept).
std::vector<std::uint32_t> exact_groups(const TriangleMesh& m, bool match_attributes) {
  std::size_t n = m.positions.size();
  std::size_t cap = 16;
  while (cap < 2 * n) cap <<= 1;
  std::vector<std::uint32_t> table(cap, kEmpty);
  std::vector<std::uint32_t> rep(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    std::size_t slot = hash_position(m.positions[i]) & (cap - 1);
    rep[i] = i;
    while (true) {
      std::uint32_t j = table[slot];
      if (j == kEmpty) {
        table[slot] = i;
        break;
      }
      if (same_bits(m.positions[i], m.positions[j]) &&
          (!match_attributes || same_attributes(m, i, j))) {
        rep[i] = j;
        break;
      }
      slot = (slot + 1) & (cap - 1);
    }
  }
  return rep;
}

struct Cell {
  std::int64_t x, y, z;
  bool operator==(const Cell&) const = default;
};
struct CellHash {
  std::size_t operator()(const Cell& c) const {
    return mix(static_cast<std::uint64_t>(c.x) ^
               mix(static_cast<std::uint64_t>(c.y) ^ mix(static_cast<std::uint64_t>(c.z))));
  }
};

std::int64_t cell_coord(float v, double inv) {
  double c = std::floor(static_cast<double>(v) * inv);
  return static_cast<std::int64_t>(std::clamp(c, -4.0e18, 4.0e18));
}

std::vector<std::uint32_t> epsilon_groups(const TriangleMesh& m, float eps, bool match_attributes) {
  std::size_t n = m.positions.size();
  double inv = 1.0 / eps;
  float eps2 = eps * eps;
  std::unordered_map<Cell, std::uint32_t, CellHash> head;
  head.reserve(n);
  std::vector<std::uint32_t> next(n, kEmpty);
  std::vector<std::uint32_t> rep(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    const Vec3& p = m.positions[i];
    Cell c{cell_coord(p.x, inv), cell_coord(p.y, inv), cell_coord(p.z, inv)};
    rep[i] = i;
    for (int dx = -1; dx <= 1 && rep[i] == i; ++dx)
      for (int dy = -1; dy <= 1 && rep[i] == i; ++dy)
        for (int dz = -1; dz <= 1 && rep[i] == i; ++dz) {
          auto it = head.find({c.x + dx, c.y + dy, c.z + dz});
          if (it == head.end()) continue;
          for (std::uint32_t j = it->second; j != kEmpty; j = next[j]) {
            if (length_squared(m.positions[j] - p) <= eps2 &&
                (!match_attributes || same_attributes(m, i, j))) {
              rep[i] = j;
              break;
            }
          }
        }
    if (rep[i] != i) continue;
    auto [it, inserted] = head.try_emplace(c, i);
    if (!inserted) {
      next[i] = it->second;
      it->second = i;
    }
  }
  return rep;
}

struct TriHash {
  std::size_t operator()(const Triangle& t) const {
    return mix(t[0] ^ mix((std::uint64_t{t[1]} << 32) ^ t[2]));
  }
};

}  // namespace

WeldResult weld(const TriangleMesh& mesh, const WeldOptions& options) {
  WeldResult r;
  std::size_t n = mesh.positions.size();
  std::vector<std::uint32_t> rep =
      options.epsilon > 0 ? epsilon_groups(mesh, options.epsilon, options.match_attributes)
                          : exact_groups(mesh, options.match_attributes);
  // New numbering in order of first occurrence.
  r.remap.resize(n);
  TriangleMesh& out = r.mesh;
  for (std::uint32_t i = 0; i < n; ++i) {
    if (rep[i] != i) {
      r.remap[i] = r.remap[rep[i]];
      ++r.merged_vertices;
      continue;
    }
    r.remap[i] = static_cast<std::uint32_t>(out.positions.size());
    out.positions.push_back(mesh.positions[i]);
    if (mesh.has_normals()) out.normals.push_back(mesh.normals[i]);
    if (mesh.has_texcoords()) out.texcoords.push_back(mesh.texcoords[i]);
    if (mesh.has_colors()) out.colors.push_back(mesh.colors[i]);
  }

  std::unordered_set<Triangle, TriHash> seen;
  if (options.remove_duplicates) seen.reserve(mesh.triangles.size());
  out.triangles.reserve(mesh.triangles.size());
  for (std::uint32_t f = 0; f < mesh.triangles.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    assert(t[0] < n && t[1] < n && t[2] < n);
    Triangle w{r.remap[t[0]], r.remap[t[1]], r.remap[t[2]]};
    if (options.remove_degenerate && (w[0] == w[1] || w[1] == w[2] || w[2] == w[0])) {
      ++r.removed_degenerate;
      continue;
    }
    if (options.remove_duplicates) {
      // Canonical rotation: smallest index first, orientation kept.
      int lo = 0;
      if (w[1] < w[lo]) lo = 1;
      if (w[2] < w[lo]) lo = 2;
      Triangle key{w[lo], w[(lo + 1) % 3], w[(lo + 2) % 3]};
      if (!seen.insert(key).second) {
        ++r.removed_duplicates;
        continue;
      }
    }
    out.triangles.push_back(w);
    r.face_origin.push_back(f);
    if (mesh.has_materials()) out.materials.push_back(mesh.materials[f]);
  }

  std::unordered_set<std::uint64_t> seen_lines;
  for (const Segment& s : mesh.lines) {
    assert(s[0] < n && s[1] < n);
    Segment w{r.remap[s[0]], r.remap[s[1]]};
    if (options.remove_degenerate && w[0] == w[1]) {
      ++r.removed_lines;
      continue;
    }
    if (options.remove_duplicates) {
      std::uint64_t key = (std::uint64_t{std::min(w[0], w[1])} << 32) | std::max(w[0], w[1]);
      if (!seen_lines.insert(key).second) {
        ++r.removed_lines;
        continue;
      }
    }
    out.lines.push_back(w);
  }
  return r;
}

}  // namespace lodforge
