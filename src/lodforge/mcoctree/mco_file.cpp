// Reading and writing .mco models: fixed-size header, raw arrays in sections
// aligned for mapping, one checksum over the body. Corruption anywhere in the
// body is caught by the checksum; the structural checks after it keep a file
// that was written by a buggy writer (valid checksum) from indexing out of
// range during extraction.
#include "lodforge/mcoctree/mco_file.h"

#include <cstring>
#include <type_traits>

#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"

namespace lodforge {
namespace {

constexpr char kMagic[8] = {'L', 'F', 'M', 'C', 'O', '\r', '\n', '\x1a'};
constexpr std::size_t kHeader = 72;
static_assert(std::is_trivially_copyable_v<McNode>);

std::uint64_t fnv1a(std::string_view data) {
  std::uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : data) h = (h ^ c) * 1099511628211ULL;
  return h;
}

template <class T>
void put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof(T));
}
template <class T>
void put_array(std::string& out, const std::vector<T>& v) {
  out.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  while (out.size() % 8) out.push_back('\0');
}

}  // namespace

std::string write_mco_data(const McOctree& t) {
  std::string body;
  put_array(body, t.positions);
  put_array(body, t.normals);
  put_array(body, t.colors);
  put_array(body, t.nodes);
  put_array(body, t.lod);
  put_array(body, t.accumulated);
  std::string out(kMagic, 8);
  put(out, kMcoVersion);
  put(out, static_cast<std::uint32_t>(t.colors.empty() ? 0 : 1));
  put(out, static_cast<std::uint32_t>(t.depth));
  put(out, t.origin);
  put(out, t.cell_size);
  put(out, static_cast<std::uint32_t>(sizeof(McNode)));
  put(out, static_cast<std::uint64_t>(t.positions.size()));
  put(out, static_cast<std::uint64_t>(t.nodes.size()));
  put(out, static_cast<std::uint64_t>(t.lod.size()));
  put(out, fnv1a(body));
  return out + body;
}

void write_mco_file(const McOctree& tree, const std::string& path) {
  write_file_atomic(path, write_mco_data(tree));
}

McOctree read_mco_data(std::string_view data, const std::string& name) {
  auto fail = [&](const std::string& what) { return DataError(name + ": " + what); };
  if (data.size() < kHeader)
    throw fail("truncated .mco file (" + std::to_string(data.size()) + " bytes)");
  if (std::memcmp(data.data(), kMagic, 8) != 0) throw fail("not a .mco model (bad magic)");
  std::size_t at = 8;
  auto get = [&](auto& v) {
    std::memcpy(&v, data.data() + at, sizeof(v));
    at += sizeof(v);
  };
  std::uint32_t version, flags, depth, node_size;
  std::uint64_t nv, nn, nl, checksum;
  McOctree t;
  get(version);
  if (version != kMcoVersion) throw fail("unsupported .mco version " + std::to_string(version));
  get(flags);
  get(depth);
  get(t.origin);
  get(t.cell_size);
  get(node_size);
  get(nv);
  get(nn);
  get(nl);
  get(checksum);
  if (node_size != sizeof(McNode))
    throw fail("node record of " + std::to_string(node_size) + " bytes");
  if (depth > 20) throw fail("depth " + std::to_string(depth) + " out of range");
  t.depth = static_cast<int>(depth);
  auto padded = [](std::uint64_t n) { return (n + 7) / 8 * 8; };
  const std::uint64_t limit = data.size();
  if (nv > limit || nn > limit || nl > limit)
    throw fail("truncated .mco file (counts beyond its size)");
  std::uint64_t need = kHeader + 2 * padded(nv * 12) + (flags & 1 ? padded(nv * 3) : 0) +
                       padded(nn * sizeof(McNode)) + padded(nl * 4) + padded((nl + 1) * 8);
  if (data.size() < need)
    throw fail("truncated .mco file (" + std::to_string(data.size()) + " of " +
               std::to_string(need) + " bytes)");
  if (fnv1a(data.substr(kHeader, need - kHeader)) != checksum)
    throw fail("checksum mismatch (corrupted file)");
  auto take = [&](auto& vec, std::uint64_t n) {
    using T = typename std::remove_reference_t<decltype(vec)>::value_type;
    vec.resize(n);
    std::memcpy(static_cast<void*>(vec.data()), data.data() + at, n * sizeof(T));
    at += padded(n * sizeof(T));
  };
  take(t.positions, nv);
  take(t.normals, nv);
  if (flags & 1) take(t.colors, nv);
  take(t.nodes, nn);
  take(t.lod, nl);
  take(t.accumulated, nl + 1);
  for (const auto& n : t.nodes) {
    for (auto v : n.edge_vertex)
      if (v != McNode::kNone && v >= nv) throw fail("vertex index out of range");
    if (!n.leaf() && (n.first_child >= nn || n.first_child + __builtin_popcount(n.child_mask) > nn))
      throw fail("child index out of range");
  }
  for (auto i : t.lod)
    if (i >= nn) throw fail("LOD array entry out of range");
  return t;
}

McOctree read_mco_file(const std::string& path) {
  return read_mco_data(read_file(path), path);
}

}  // namespace lodforge
