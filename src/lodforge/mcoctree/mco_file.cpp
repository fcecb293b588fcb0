// Reading and writing .mco models as a progressive stream (see mco_file.h).
//
// Extraction at priority N reads (a) the nodes of priority <= N, (b) their
// children, which it triangulates, and (c) the children of a triangulated
// cell whose face or edge a neighbour splits (slot_vertex takes the split
// edge's points from them). (c) can come before the cell itself is expanded,
// so "store the children with their parent's priority" is not enough: a
// node x with parent p is stored in chunk
//   need(x) = min(p.priority, max(tri(p), split(p)))
// where tri(p) is the priority at which p starts being triangulated (its own
// parent's priority; 0 for the root) and split(p) the smallest of p's face
// and edge split priorities. Siblings share need(), so they stay contiguous.
// Each chunk has its own checksum, so a prefix can be verified on its own.
#include "lodforge/mcoctree/mco_file.h"

#include <algorithm>
#include <cstring>
#include <numeric>
#include <type_traits>

#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"

namespace lodforge {
namespace {

constexpr char kMagic[8] = {'L', 'F', 'M', 'C', 'O', '\r', '\n', '\x1a'};
constexpr std::size_t kHeader = 72;
constexpr std::size_t kChunkHeader = 24;
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
void pad(std::string& out) {
  while (out.size() % 8) out.push_back('\0');
}
std::uint64_t padded(std::uint64_t n) {
  return (n + 7) / 8 * 8;
}

std::uint32_t min_split(const McNode& n) {
  std::uint32_t m = McNode::kNone;
  for (auto f : n.face_split) m = std::min(m, f);
  for (auto e : n.edge_split) m = std::min(m, e);
  return m;
}
// Chunk of p's children, given tri(p).
std::uint32_t children_need(const McNode& p, std::uint32_t tri) {
  return std::min(p.priority, std::max(tri, min_split(p)));
}

struct Header {
  std::uint32_t version = 0, flags = 0, depth = 0, node_size = 0;
  std::uint64_t nv = 0, nn = 0, nl = 0;
};

Header read_header(std::string_view data, McOctree& t, const std::string& name) {
  auto fail = [&](const std::string& what) { return DataError(name + ": " + what); };
  if (data.size() < kHeader)
    throw fail("truncated .mco file (" + std::to_string(data.size()) + " bytes)");
  if (std::memcmp(data.data(), kMagic, 8) != 0) throw fail("not a .mco model (bad magic)");
  std::size_t at = 8;
  auto get = [&](auto& v) {
    std::memcpy(&v, data.data() + at, sizeof(v));
    at += sizeof(v);
  };
  Header h;
  std::uint64_t checksum;
  get(h.version);
  if (h.version != kMcoVersion) throw fail("unsupported .mco version " + std::to_string(h.version));
  get(h.flags);
  get(h.depth);
  get(t.origin);
  get(t.cell_size);
  get(h.node_size);
  get(h.nv);
  get(h.nn);
  get(h.nl);
  get(checksum);
  if (fnv1a(data.substr(0, 64)) != checksum) throw fail("checksum mismatch in the header");
  if (h.node_size != sizeof(McNode))
    throw fail("node record of " + std::to_string(h.node_size) + " bytes");
  if (h.depth > 20) throw fail("depth " + std::to_string(h.depth) + " out of range");
  if (h.nn > UINT32_MAX || h.nv > UINT32_MAX || h.nl >= h.nn + 1) throw fail("counts out of range");
  t.depth = static_cast<int>(h.depth);
  return h;
}

// Walks chunks 0..last; calls fn(k, chunk bytes) for each, after checking it.
template <class Fn>
std::size_t walk_chunks(std::string_view data, const Header& h, std::uint64_t last,
                        const std::string& name, Fn&& fn) {
  auto fail = [&](const std::string& what) { return DataError(name + ": " + what); };
  const std::uint64_t vsize = 24 + (h.flags & 1 ? 3 : 0);
  std::size_t at = kHeader;
  for (std::uint64_t k = 0; k <= last; ++k) {
    auto truncated = [&] {
      return fail("truncated .mco file: priority " + std::to_string(k) + " of " +
                  std::to_string(h.nl) + " missing (" + std::to_string(data.size()) + " bytes)");
    };
    if (data.size() - at < kChunkHeader) throw truncated();
    std::uint32_t nodes, verts;
    std::memcpy(&nodes, data.data() + at, 4);
    std::memcpy(&verts, data.data() + at + 4, 4);
    std::uint64_t size =
        kChunkHeader + padded(verts * vsize) + padded(std::uint64_t{nodes} * sizeof(McNode));
    if (nodes > h.nn || verts > h.nv || data.size() - at < size + 8) throw truncated();
    std::uint64_t checksum;
    std::memcpy(&checksum, data.data() + at + size, 8);
    std::string_view chunk = data.substr(at, size);
    if (fnv1a(chunk) != checksum)
      throw fail("checksum mismatch at priority " + std::to_string(k) + " (corrupted file)");
    fn(k, chunk, nodes, verts);
    at += size + 8;
  }
  return at;
}

}  // namespace

std::string write_mco_data(const McOctree& t) {
  const std::size_t nn = t.nodes.size(), nv = t.positions.size(), nl = t.lod.size();
  // need[] per node and vertex (see the top of the file).
  std::vector<std::uint32_t> need(nn, McNode::kNone), tri(nn, 0), vneed(nv, McNode::kNone);
  if (nn) need[0] = 0;
  for (std::size_t i = 0; i < nn; ++i) {  // parents come before children
    const McNode& p = t.nodes[i];
    if (p.leaf()) continue;
    std::uint32_t c = children_need(p, tri[i]);
    for (int o = 0; o < 8; ++o)
      if (auto ch = p.child(o); ch != McNode::kNone) need[ch] = c, tri[ch] = p.priority;
  }
  for (std::size_t i = 0; i < nn; ++i)
    for (auto v : t.nodes[i].edge_vertex)
      if (v != McNode::kNone) vneed[v] = std::min(vneed[v], need[i]);
  auto order_by = [](const std::vector<std::uint32_t>& key) {
    std::vector<std::uint32_t> order(key.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return key[a] < key[b]; });
    std::vector<std::uint32_t> rank(key.size());
    for (std::uint32_t i = 0; i < order.size(); ++i) rank[order[i]] = i;
    return std::pair{order, rank};
  };
  auto [node_order, node_rank] = order_by(need);
  auto [vertex_order, vertex_rank] = order_by(vneed);

  std::string out(kMagic, 8);
  put(out, kMcoVersion);
  put(out, static_cast<std::uint32_t>(t.colors.empty() ? 0 : 1));
  put(out, static_cast<std::uint32_t>(t.depth));
  put(out, t.origin);
  put(out, t.cell_size);
  put(out, static_cast<std::uint32_t>(sizeof(McNode)));
  put(out, static_cast<std::uint64_t>(nv));
  put(out, static_cast<std::uint64_t>(nn));
  put(out, static_cast<std::uint64_t>(nl));
  put(out, fnv1a(out));
  std::size_t ni = 0, vi = 0;
  for (std::size_t k = 0; k <= nl; ++k) {
    std::size_t n_end = ni, v_end = vi;
    while (n_end < nn && need[node_order[n_end]] <= k) ++n_end;
    while (v_end < nv && vneed[vertex_order[v_end]] <= k) ++v_end;
    std::size_t start = out.size();
    put(out, static_cast<std::uint32_t>(n_end - ni));
    put(out, static_cast<std::uint32_t>(v_end - vi));
    put(out, k == 0 ? 0u : node_rank[t.lod[k - 1]]);
    put(out, 0u);
    put(out, t.accumulated[k]);
    for (; vi < v_end; ++vi) {
      auto v = vertex_order[vi];
      put(out, t.positions[v]);
      put(out, t.normals[v]);
      if (!t.colors.empty()) put(out, t.colors[v]);
    }
    pad(out);
    for (; ni < n_end; ++ni) {
      McNode n = t.nodes[node_order[ni]];
      if (!n.leaf()) n.first_child = node_rank[n.first_child];
      for (auto& v : n.edge_vertex)
        if (v != McNode::kNone) v = vertex_rank[v];
      put(out, n);
    }
    pad(out);
    put(out, fnv1a(std::string_view(out).substr(start)));
  }
  return out;
}

void write_mco_file(const McOctree& tree, const std::string& path) {
  write_file_atomic(path, write_mco_data(tree));
}

McOctree read_mco_data(std::string_view data, const std::string& name,
                       const McoReadOptions& options) {
  auto fail = [&](const std::string& what) { return DataError(name + ": " + what); };
  McOctree t;
  Header h = read_header(data, t, name);
  const std::uint64_t last =
      options.max_priority < 0
          ? h.nl
          : std::min<std::uint64_t>(h.nl, static_cast<std::uint64_t>(options.max_priority));
  const bool colored = h.flags & 1;
  t.nodes.reserve(last == h.nl ? h.nn : 0);
  t.positions.reserve(last == h.nl ? h.nv : 0);
  walk_chunks(
      data, h, last, name,
      [&](std::uint64_t k, std::string_view chunk, std::uint32_t nodes, std::uint32_t verts) {
        std::size_t at = 8;
        std::uint32_t lod;
        std::uint64_t acc;
        std::memcpy(&lod, chunk.data() + at, 4);
        std::memcpy(&acc, chunk.data() + 16, 8);
        at = kChunkHeader;
        if (k > 0) t.lod.push_back(lod);
        t.accumulated.push_back(acc);
        for (std::uint32_t v = 0; v < verts; ++v) {
          Vec3 p, n;
          std::memcpy(&p, chunk.data() + at, 12);
          std::memcpy(&n, chunk.data() + at + 12, 12);
          at += 24;
          t.positions.push_back(p);
          t.normals.push_back(n);
          if (colored) {
            Rgb8 c;
            std::memcpy(c.data(), chunk.data() + at, 3);
            at += 3;
            t.colors.push_back(c);
          }
        }
        at = padded(at);
        for (std::uint32_t i = 0; i < nodes; ++i) {
          McNode n;
          std::memcpy(static_cast<void*>(&n), chunk.data() + at, sizeof(McNode));
          at += sizeof(McNode);
          t.nodes.push_back(n);
        }
      });
  if (t.nodes.empty() && h.nn > 0) throw fail("no root node");
  // Structure: every index extraction up to `last` follows must be loaded.
  const std::uint64_t nn = t.nodes.size(), nv = t.positions.size();
  std::vector<std::uint32_t> tri(nn, 0);
  for (std::size_t i = 0; i < nn; ++i) {
    const McNode& n = t.nodes[i];
    for (auto v : n.edge_vertex)
      if (v != McNode::kNone && v >= nv) throw fail("vertex index out of range");
    if (n.leaf()) continue;
    std::uint64_t end = std::uint64_t{n.first_child} + __builtin_popcount(n.child_mask);
    if (end > h.nn) throw fail("child index out of range");
    if (end <= nn) {
      for (int o = 0; o < 8; ++o)
        if (auto c = n.child(o); c != McNode::kNone) {
          if (c <= i) throw fail("child index out of range");
          tri[c] = n.priority;
        }
    } else if (children_need(n, tri[i]) <= last) {
      throw fail("child index out of range");
    }
  }
  for (std::size_t k = 0; k < t.lod.size(); ++k)
    if (t.lod[k] >= nn || t.nodes[t.lod[k]].priority != k + 1)
      throw fail("LOD array entry out of range");
  return t;
}

McOctree read_mco_file(const std::string& path, const McoReadOptions& options) {
  return read_mco_data(read_file(path), path, options);
}

std::uint64_t mco_prefix_size(std::string_view data, std::uint32_t priority,
                              const std::string& name) {
  McOctree t;
  Header h = read_header(data, t, name);
  return walk_chunks(data, h, std::min<std::uint64_t>(priority, h.nl), name, [](auto&&...) {});
}

}  // namespace lodforge
