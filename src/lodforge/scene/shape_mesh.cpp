#include "lodforge/scene/shape_mesh.h"

#include <fmt/format.h>

#include "lodforge/core/error.h"
#include "lodforge/scene/inventor_shapes.h"
#include "lodforge/scene/schema.h"

namespace lodforge::scene {
namespace {

// The points of the current Coordinate3 (spec default: one point at the origin).
std::vector<Vec3> coordinates(const TraversalState& state, const Node& shape) {
  static const Node kDefault{.type = "Coordinate3"};
  const Node& c = state.coordinate3 ? *state.coordinate3 : kDefault;
  const FieldValue* v = field_or_default(c, "point");
  std::vector<Vec3> pts(v->floats.size() / 3);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    pts[i] = {v->floats[3 * i], v->floats[3 * i + 1], v->floats[3 * i + 2]};
    if (!is_finite(pts[i]))
      throw DataError(
          fmt::format("line {}: Coordinate3 point {} is not finite (used by the {} "
                      "at line {})",
                      c.first_line, i, shape.type, shape.first_line));
  }
  return pts;
}

void check_index(std::int32_t i, std::size_t n, const Node& shape, std::size_t pos) {
  if (i < 0 || std::size_t(i) >= n)
    throw DataError(
        fmt::format("line {}: {} coordIndex[{}] = {} is out of range (the current "
                    "Coordinate3 has {} points)",
                    shape.first_line, shape.type, pos, i, n));
}

}  // namespace

std::vector<std::pair<std::size_t, std::size_t>> split_index_runs(
    const std::vector<std::int32_t>& index) {
  std::vector<std::pair<std::size_t, std::size_t>> runs;
  std::size_t begin = 0;
  for (std::size_t i = 0; i <= index.size(); ++i) {
    if (i == index.size() || index[i] < 0) {
      if (i > begin) runs.emplace_back(begin, i);
      begin = i + 1;
    }
  }
  return runs;
}

TriangleMesh shape_mesh(const ShapeVisit& visit, const ShapeMeshOptions& options, Log* log) {
  if (has_indexed_equivalent(visit.shape.type)) {
    // Inventor's strips, quad meshes and face sets: as the indexed set that
    // draws the same.
    const IndexedEquivalent eq = to_indexed_shape(visit);
    return shape_mesh(ShapeVisit{*eq.shape, eq.state, visit.camera, visit.path, visit.child_index,
                                 visit.path_index},
                      options, log);
  }
  const Node& shape = visit.shape;
  TriangleMesh mesh;
  const std::string& t = shape.type;
  if (t == "Cube" || t == "Sphere" || t == "Cone" || t == "Cylinder") {
    TessellateOptions tess = options.tessellation;
    tess.complexity = complexity_value(visit.state);
    mesh = tessellate_primitive(shape, tess);
  } else if (t == "IndexedFaceSet" || t == "IndexedLineSet") {
    mesh.positions = coordinates(visit.state, shape);
    const FieldValue* idx = field_or_default(shape, "coordIndex");
    std::vector<std::uint32_t> poly;
    for (auto [b, e] : split_index_runs(idx->ints)) {
      poly.clear();
      for (std::size_t i = b; i < e; ++i) {
        check_index(idx->ints[i], mesh.positions.size(), shape, i);
        poly.push_back(static_cast<std::uint32_t>(idx->ints[i]));
      }
      if (t == "IndexedLineSet") {
        for (std::size_t i = 1; i < poly.size(); ++i) mesh.lines.push_back({poly[i - 1], poly[i]});
        continue;
      }
      if (poly.size() < 3) {
        if (log)
          log->warn(LogCategory::kFace,
                    fmt::format("line {}: IndexedFaceSet face at coordIndex[{}] "
                                "has {} vertices; skipped",
                                shape.first_line, b, poly.size()));
        continue;
      }
      TriangulateResult tr = triangulate_polygon(mesh.positions, poly, options.triangulation);
      if (log && tr.has_warning())
        log->add(LogLevel::kMessage, LogCategory::kTriangulator,
                 fmt::format("line {}: face at coordIndex[{}] is {}", shape.first_line, b,
                             tr.degenerate ? "degenerate" : "not simple"));
      for (const auto& tri : tr.triangles)
        mesh.triangles.push_back({poly[tri[0]], poly[tri[1]], poly[tri[2]]});
    }
  } else if (t == "PointSet") {
    std::vector<Vec3> pts = coordinates(visit.state, shape);
    const FieldValue* start = field_or_default(shape, "startIndex");
    const FieldValue* num = field_or_default(shape, "numPoints");
    std::int64_t s = start->ints.empty() ? 0 : start->ints[0];
    std::int64_t n = num->ints.empty() ? -1 : num->ints[0];
    s = std::clamp<std::int64_t>(s, 0, std::int64_t(pts.size()));
    std::int64_t e = n < 0 ? std::int64_t(pts.size()) : std::min<std::int64_t>(s + n, pts.size());
    mesh.positions.assign(pts.begin() + s, pts.begin() + e);
  }
  if (options.world_space && !(visit.state.transform == Mat4{})) {
    for (auto& p : mesh.positions) p = visit.state.transform.transform_point(p);
    if (mesh.has_normals()) {
      Mat4 nm = visit.state.transform.normal_matrix();
      for (auto& n : mesh.normals) n = normalized(nm.transform_vector(n));
    }
  }
  return mesh;
}

}  // namespace lodforge::scene
