#include "lodforge/scene/face_set_mesh.h"

#include <fmt/format.h>

#include "lodforge/core/error.h"

namespace lodforge::scene {

void check_coord_index(std::span<const std::int32_t> coord_index, std::size_t point_count,
                       const FaceSetSource& source) {
  for (std::size_t i = 0; i < coord_index.size(); ++i)
    if (coord_index[i] >= 0 && std::size_t(coord_index[i]) >= point_count)
      throw DataError(
          fmt::format("{} coordIndex[{}] = {} is out of range (the current {} has {} "
                      "points)",
                      source.where, i, coord_index[i], source.coordinates, point_count));
}

std::vector<FaceRun> face_runs(std::span<const std::int32_t> coord_index, std::size_t point_count,
                               const FaceSetSource& source) {
  check_coord_index(coord_index, point_count, source);
  std::vector<FaceRun> runs;
  for_each_index_run(coord_index, [&](std::size_t b, std::size_t e) { runs.emplace_back(b, e); });
  return runs;
}

Binding vrml97_binding(bool per_vertex, bool has_index) {
  if (per_vertex) return Binding::kPerVertexIndexed;  // an empty index field reads coordIndex
  return has_index ? Binding::kPerFaceIndexed : Binding::kPerFace;
}

std::int64_t corner_attribute(const FaceSetAttribute& attribute, std::size_t face,
                              std::size_t corner_seq, std::size_t pos, std::string_view where) {
  const AttributeIndexer& ix = attribute.indexer;
  if (ix.bind == Binding::kOverall) return -1;
  const std::int64_t v = ix.at(face, corner_seq, pos);
  if (v >= 0 && std::size_t(v) < attribute.count) return v;
  std::string_view field = attribute.index_field;
  std::size_t k = pos;
  std::size_t entries = 0;
  switch (ix.bind) {
    case Binding::kPerFace:  // no index field: the n-th face takes the n-th value
      throw DataError(
          fmt::format("{} PER_FACE binding: face {} takes value {}, out of range ({} "
                      "values)",
                      where, face, v, attribute.count));
    case Binding::kPerVertex:  // the n-th corner takes the n-th value
      throw DataError(
          fmt::format("{} PER_VERTEX binding: corner {} takes value {}, out of range "
                      "({} values)",
                      where, corner_seq, v, attribute.count));
    case Binding::kPerFaceIndexed:
      k = face;
      entries = ix.index ? ix.index->size() : 0;
      if (entries == 0) throw DataError(fmt::format("{} {} is empty", where, field));
      break;
    default:
      if (ix.index_is_default()) field = "coordIndex";
      entries = (ix.index_is_default() ? ix.coord_index : ix.index)->size();
      break;
  }
  if (entries > 0 && k >= entries)
    throw DataError(fmt::format("{} {} has no entry {} ({} entries)", where, field, k, entries));
  throw DataError(fmt::format("{} {}[{}] = {} is out of range ({} values)", where, field, k, v,
                              attribute.count));
}

FaceTriangles face_triangles(std::span<const Vec3> positions, std::vector<std::uint32_t>& poly,
                             const FaceTriangulation& options, std::vector<Triangle>& triangles) {
  if (options.merge_repeated_corners) {
    std::size_t n = 0;
    for (std::uint32_t v : poly)
      if (n == 0 || poly[n - 1] != v) poly[n++] = v;
    while (n > 1 && poly[0] == poly[n - 1]) --n;
    poly.resize(n);
  }
  FaceTriangles out;
  out.corners = poly.size();
  if (poly.size() < 3) return out;
  auto add = [&](const Triangle& t) {
    if (options.drop_repeated_vertex_triangles && (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]))
      return;
    triangles.push_back(t);
    ++out.triangles;
  };
  if (poly.size() == 3) {  // a triangle passes through as it is
    if (options.diagnose_triangles)
      out.degenerate =
          triangle_is_degenerate(positions[poly[0]], positions[poly[1]], positions[poly[2]]);
    add({poly[0], poly[1], poly[2]});
    return out;
  }
  const TriangulateResult tr = triangulate_polygon(positions, poly, options.triangulation);
  out.keep_as_quad = poly.size() == 4 && tr.keep_as_quad;
  out.degenerate = tr.degenerate;
  out.not_simple = tr.not_simple;
  for (const auto& t : tr.triangles) add({poly[t[0]], poly[t[1]], poly[t[2]]});
  return out;
}

}  // namespace lodforge::scene
