// Reading and writing .mco models as a progressive stream (see mco_file.h).
//
// The run-time model is already in stream order: its cells are grouped by
// their parent's priority, and its vertices are numbered in order of first
// use by those groups, so chunk k is group k's cells with all their
// intervals and triangles, plus the vertices that group uses first. Each
// chunk has its own checksum, so a prefix can be verified on its own.
//
// A reader cannot trust the accumulation table blindly: extraction sizes its
// output by it. So reading recomputes, from the cells' intervals, how the
// triangle count changes at each priority and checks every entry:
//
//   event                              | change at priority
//   -----------------------------------+-----------------------------
//   cell of group g appears            | + its first interval's count, at g
//   its interval j > 0 starts at s     | + count(j) - count(j - 1), at s
//   it is expanded (until = u)         | - its last interval's count, at u
#include "lodforge/mcoctree/mco_file.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"

namespace lodforge {
namespace {

constexpr char kMagic[8] = {'L', 'F', 'M', 'C', 'O', '\r', '\n', '\x1a'};
constexpr std::size_t kHeader = 88;
constexpr std::size_t kChunkHeader = 32;

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

struct Header {
  std::uint32_t version = 0, flags = 0, depth = 0;
  std::uint32_t full_triangles = 0;  // version 4; 0 in version 3 (not recorded)
  std::uint64_t nv = 0, nc = 0, ni = 0, nt = 0, nl = 0;
  std::uint64_t vertex_size() const { return 16 + (flags & 1 ? 3 : 0); }
};

struct ChunkCounts {
  std::uint32_t cells = 0, intervals = 0, triangles = 0, vertices = 0, centroids = 0;
  std::uint64_t accumulated = 0;
};

Header read_header(std::string_view data, McLodModel& m, const std::string& name,
                   bool verify = true) {
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
  if (h.version != kMcoVersion && h.version != 3)
    throw fail("unsupported .mco version " + std::to_string(h.version));
  get(h.flags);
  get(h.depth);
  get(m.origin);
  get(m.cell_size);
  get(h.full_triangles);
  get(h.nv);
  get(h.nc);
  get(h.ni);
  get(h.nt);
  get(h.nl);
  get(checksum);
  if (verify && fnv1a(data.substr(0, kHeader - 8)) != checksum)
    throw fail("checksum mismatch in the header");
  if (h.depth > 20) throw fail("depth " + std::to_string(h.depth) + " out of range");
  if (!is_finite(m.origin) || !std::isfinite(m.cell_size) || !(m.cell_size >= 0))
    throw fail("the lattice origin or cell size is not a finite number");
  constexpr std::uint64_t kMax = UINT32_MAX - 16;  // indices and sentinels fit in u32
  if (h.nv > kMax || h.nc > kMax || h.ni > kMax || h.nt > kMax || h.nl >= h.nc + 1)
    throw fail("counts out of range");
  m.depth = static_cast<int>(h.depth);
  return h;
}

// Walks chunks 0..last; calls fn(k, chunk bytes, counts) for each, after
// checking its size and checksum. Returns the end offset. Data that end
// before chunk `last` is complete are an error, unless `complete` is given:
// it then receives the number of complete chunks and the walk stops there.
template <class Fn>
std::size_t walk_chunks(std::string_view data, const Header& h, std::uint64_t last,
                        const std::string& name, bool verify, Fn&& fn,
                        std::uint64_t* complete = nullptr) {
  auto fail = [&](const std::string& what) { return DataError(name + ": " + what); };
  std::size_t at = kHeader;
  ChunkCounts total;
  for (std::uint64_t k = 0; k <= last; ++k) {
    auto truncated = [&] {
      return fail("truncated .mco file: priority " + std::to_string(k) + " of " +
                  std::to_string(h.nl) + " missing (" + std::to_string(data.size()) + " bytes)");
    };
    auto stop = [&] {
      if (!complete) throw truncated();
      *complete = k;
      return at;
    };
    if (data.size() - at < kChunkHeader) return stop();
    ChunkCounts c;
    std::memcpy(&c.cells, data.data() + at, 4);
    std::memcpy(&c.intervals, data.data() + at + 4, 4);
    std::memcpy(&c.triangles, data.data() + at + 8, 4);
    std::memcpy(&c.vertices, data.data() + at + 12, 4);
    std::memcpy(&c.centroids, data.data() + at + 16, 4);
    std::memcpy(&c.accumulated, data.data() + at + 24, 8);
    // Against the header's totals first: no size computed below can overflow.
    if (c.cells > h.nc - total.cells || c.intervals > h.ni - total.intervals ||
        c.triangles > h.nt - total.triangles || c.vertices > h.nv - total.vertices ||
        c.centroids > c.vertices)
      throw fail("counts out of range at priority " + std::to_string(k));
    total.cells += c.cells, total.intervals += c.intervals, total.triangles += c.triangles;
    total.vertices += c.vertices;
    std::uint64_t size = kChunkHeader + padded(std::uint64_t{c.vertices} * h.vertex_size()) +
                         8 * std::uint64_t{c.cells} + 8 * std::uint64_t{c.intervals} +
                         padded(12 * std::uint64_t{c.triangles} + 4 * std::uint64_t{c.centroids});
    if (data.size() - at < size + 8) return stop();
    std::uint64_t checksum;
    std::memcpy(&checksum, data.data() + at + size, 8);
    std::string_view chunk = data.substr(at, size);
    if (verify && fnv1a(chunk) != checksum)
      throw fail("checksum mismatch at priority " + std::to_string(k) + " (corrupted file)");
    fn(k, chunk, c);
    at += size + 8;
  }
  if (complete) *complete = last + 1;
  return at;
}

}  // namespace

std::string write_mco_data(const McLodModel& m) {
  const std::uint32_t L = m.priorities();
  const std::size_t nc = m.cell_count(), nv = m.positions.size();
  std::string out(kMagic, 8);
  put(out, kMcoVersion);
  put(out, static_cast<std::uint32_t>(m.colors.empty() ? 0 : 1));
  put(out, static_cast<std::uint32_t>(m.depth));
  put(out, m.origin);
  put(out, m.cell_size);
  put(out, static_cast<std::uint32_t>(m.full_triangles()));
  put(out, static_cast<std::uint64_t>(nv));
  put(out, static_cast<std::uint64_t>(nc));
  put(out, static_cast<std::uint64_t>(nc ? m.intervals.size() - 1 : 0));
  put(out, static_cast<std::uint64_t>(m.stored_triangles()));
  put(out, static_cast<std::uint64_t>(L));
  put(out, fnv1a(out));
  if (m.group.empty()) {  // a default-constructed model: one empty chunk
    const std::size_t start = out.size();
    out.append(kChunkHeader, '\0');
    put(out, fnv1a(std::string_view(out).substr(start)));
    return out;
  }
  std::uint32_t v_begin = 0;
  auto centroid = m.centroids.begin();
  for (std::uint32_t k = 0; k <= L; ++k) {
    const std::uint32_t c0 = m.group[k], c1 = m.group[k + 1];
    const std::uint32_t i0 = m.cells[c0].first_interval, i1 = m.cells[c1].first_interval;
    const std::uint32_t t0 = m.intervals[i0].first_triangle, t1 = m.intervals[i1].first_triangle;
    // Vertices are numbered by first use: this group's new ones follow the
    // previous groups'. The last chunk takes any vertex no triangle uses.
    std::uint32_t v_end = v_begin;
    for (std::uint32_t t = t0; t < t1; ++t)
      for (auto v : m.triangles[t]) v_end = std::max(v_end, v + 1);
    if (k == L) v_end = static_cast<std::uint32_t>(nv);
    auto centroid_end = std::lower_bound(centroid, m.centroids.end(), v_end);
    const std::size_t start = out.size();
    put(out, c1 - c0);
    put(out, i1 - i0);
    put(out, t1 - t0);
    put(out, v_end - v_begin);
    put(out, static_cast<std::uint32_t>(centroid_end - centroid));
    put(out, 0u);
    put(out, m.accumulated[k]);
    for (std::uint32_t v = v_begin; v < v_end; ++v) {
      put(out, m.positions[v]);
      put(out, m.normals[v]);
      if (!m.colors.empty()) put(out, m.colors[v]);
    }
    pad(out);
    for (std::uint32_t c = c0; c < c1; ++c) {
      put(out, m.cells[c].until);
      put(out, m.cells[c + 1].first_interval - m.cells[c].first_interval);
    }
    for (std::uint32_t i = i0; i < i1; ++i) {
      put(out, m.intervals[i].from);
      put(out, m.intervals[i + 1].first_triangle - m.intervals[i].first_triangle);
    }
    for (std::uint32_t t = t0; t < t1; ++t) put(out, m.triangles[t]);
    for (; centroid != centroid_end; ++centroid) put(out, *centroid);
    pad(out);
    put(out, fnv1a(std::string_view(out).substr(start)));
    v_begin = v_end;
  }
  return out;
}

void write_mco_file(const McLodModel& model, const std::string& path) {
  write_file_atomic(path, write_mco_data(model));
}

McLodModel read_mco_data(std::string_view data, const std::string& name,
                         const McoReadOptions& options) {
  auto fail = [&](const std::string& what) { return DataError(name + ": " + what); };
  McLodModel m;
  Header h = read_header(data, m, name, options.verify_checksums);
  std::uint64_t last =
      options.max_priority < 0
          ? h.nl
          : std::min<std::uint64_t>(h.nl, static_cast<std::uint64_t>(options.max_priority));
  if (options.prefix) {
    std::uint64_t complete = 0;
    walk_chunks(
        data, h, last, name, options.verify_checksums, [](auto&&...) {}, &complete);
    if (complete == 0) walk_chunks(data, h, 0, name, options.verify_checksums, [](auto&&...) {});
    last = complete - 1;
  }
  // Each chunk takes at least its header and checksum: a file too short for
  // `last` is truncated, found (with its message) before anything is sized
  // by a forged count.
  if ((last + 1) * (kChunkHeader + 8) > data.size() - kHeader)
    walk_chunks(data, h, last, name, options.verify_checksums, [](auto&&...) {});
  const bool colored = h.flags & 1;
  if (last == h.nl) {
    // At most what the data can hold: a forged header must not allocate more.
    auto fit = [&](std::uint64_t n, std::uint64_t record) {
      return static_cast<std::size_t>(std::min<std::uint64_t>(n, data.size() / record));
    };
    m.positions.reserve(fit(h.nv, 16));
    m.normals.reserve(fit(h.nv, 16));
    m.cells.reserve(fit(h.nc, 8) + 1);
    m.intervals.reserve(fit(h.ni, 8) + 1);
    m.triangles.reserve(fit(h.nt, 12) + McLodModel::kCopyBlock);
  }
  // delta[k]: the change of the triangle count at priority k (see the top).
  std::vector<std::int64_t> delta(last + 2, 0);
  m.group.reserve(last + 2);
  walk_chunks(data, h, last, name, options.verify_checksums,
              [&](std::uint64_t k, std::string_view chunk, const ChunkCounts& c) {
                auto bad = [&](const char* what) {
                  return fail(std::string(what) + " at priority " + std::to_string(k));
                };
                std::size_t at = kChunkHeader;
                auto get = [&](auto& v) {
                  std::memcpy(&v, chunk.data() + at, sizeof(v));
                  at += sizeof(v);
                };
                m.group.push_back(static_cast<std::uint32_t>(m.cells.size()));
                m.accumulated.push_back(c.accumulated);
                for (std::uint32_t v = 0; v < c.vertices; ++v) {
                  Vec3 p;
                  std::uint32_t n;
                  get(p);
                  get(n);
                  // A NaN or infinite vertex would reach every extracted mesh.
                  if (!is_finite(p)) throw bad("vertex position not finite");
                  m.positions.push_back(p);
                  m.normals.push_back(n);
                  if (colored) {
                    Rgb8 col;
                    get(col);
                    m.colors.push_back(col);
                  }
                }
                at = padded(at);
                // Cells, then their intervals in order: check the shape as they come.
                const std::size_t cell_at = at, interval_at = at + 8 * std::size_t{c.cells};
                std::size_t interval_count = 0, triangle_count = 0;
                at = interval_at;
                for (std::uint32_t i = 0; i < c.cells; ++i) {
                  std::uint32_t until, n;
                  std::memcpy(&until, chunk.data() + cell_at + 8 * i, 4);
                  std::memcpy(&n, chunk.data() + cell_at + 8 * i + 4, 4);
                  if (until <= k || n == 0 || n > c.intervals - interval_count)
                    throw bad("cell out of range");
                  m.cells.push_back({until, static_cast<std::uint32_t>(m.intervals.size())});
                  interval_count += n;
                  std::int64_t previous = 0;
                  std::uint32_t previous_from = 0;
                  for (std::uint32_t j = 0; j < n; ++j) {
                    std::uint32_t from, count;
                    get(from);
                    get(count);
                    if ((j == 0 && from != k) || (j > 0 && from <= previous_from) ||
                        from >= until || count > c.triangles - triangle_count)
                      throw bad("interval out of range");
                    m.intervals.push_back(
                        {from, static_cast<std::uint32_t>(m.triangles.size() + triangle_count)});
                    triangle_count += count;
                    if (from <= last) delta[from] += static_cast<std::int64_t>(count) - previous;
                    previous = count, previous_from = from;
                  }
                  if (until <= last) delta[until] -= previous;
                }
                if (interval_count != c.intervals || triangle_count != c.triangles)
                  throw bad("interval counts disagree");
                const auto nv = static_cast<std::uint32_t>(m.positions.size());
                for (std::uint32_t t = 0; t < c.triangles; ++t) {
                  Triangle tri;
                  get(tri);
                  for (auto v : tri)
                    if (v >= nv) throw bad("vertex index out of range");
                  m.triangles.push_back(tri);
                }
                for (std::uint32_t i = 0; i < c.centroids; ++i) {
                  std::uint32_t v;
                  get(v);
                  if (v >= nv || (!m.centroids.empty() && v <= m.centroids.back()))
                    throw bad("centroid index out of range");
                  m.centroids.push_back(v);
                }
              });
  m.group.push_back(static_cast<std::uint32_t>(m.cells.size()));
  m.cells.push_back({0, static_cast<std::uint32_t>(m.intervals.size())});
  m.intervals.push_back({McLodModel::kNever, static_cast<std::uint32_t>(m.triangles.size())});
  m.triangles.resize(m.triangles.size() + McLodModel::kCopyBlock, Triangle{0, 0, 0});
  std::int64_t count = 0;
  for (std::uint64_t k = 0; k <= last; ++k) {
    count += delta[k];
    if (count < 0 || static_cast<std::uint64_t>(count) != m.accumulated[k])
      throw fail("accumulation table disagrees with the cells at priority " + std::to_string(k));
  }
  return m;
}

McLodModel read_mco_file(const std::string& path, const McoReadOptions& options) {
  return read_mco_data(read_file(path), path, options);
}

McoFileSummary summarize_mco_data(std::string_view data, const std::string& name) {
  McLodModel m;
  const Header h = read_header(data, m, name);
  McoFileSummary out;
  out.version = h.version;
  out.priorities = h.nl;
  out.full_triangles = h.full_triangles;
  std::uint64_t complete = 0;
  walk_chunks(
      data, h, h.nl, name, true, [](auto&&...) {}, &complete);
  out.complete_priorities = complete;
  return out;
}

std::uint64_t mco_prefix_size(std::string_view data, std::uint32_t priority,
                              const std::string& name) {
  McLodModel m;
  Header h = read_header(data, m, name);
  return walk_chunks(data, h, std::min<std::uint64_t>(priority, h.nl), name, true,
                     [](auto&&...) {});
}

}  // namespace lodforge
