#include "lodforge/scene/shape_mesh.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <span>
#include <tuple>

#include "lodforge/core/error.h"
#include "lodforge/scene/attribute_binding.h"
#include "lodforge/scene/face_set_mesh.h"
#include "lodforge/scene/inventor_shapes.h"
#include "lodforge/scene/schema.h"

namespace lodforge::scene {
namespace {

// The points of the current Coordinate3 (spec default: one point at the
// origin) as x, y, z floats, each checked to be finite.
std::span<const float> coordinate_floats(const TraversalState& state, const Node& shape) {
  static const Node kDefault{.type = "Coordinate3"};
  const Node& c = state.coordinate3 ? *state.coordinate3 : kDefault;
  const std::vector<float>& f = field_or_default(c, "point")->floats;
  const std::size_t n = f.size() / 3;
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(f[3 * i]) || !std::isfinite(f[3 * i + 1]) || !std::isfinite(f[3 * i + 2]))
      throw DataError(
          fmt::format("line {}: Coordinate3 point {} is not finite (used by the {} "
                      "at line {})",
                      c.first_line, i, shape.type, shape.first_line));
  return std::span(f).first(3 * n);
}

std::vector<Vec3> coordinates(const TraversalState& state, const Node& shape) {
  const std::span<const float> f = coordinate_floats(state, shape);
  std::vector<Vec3> pts(f.size() / 3);
  for (std::size_t i = 0; i < pts.size(); ++i) pts[i] = {f[3 * i], f[3 * i + 1], f[3 * i + 2]};
  return pts;
}

// The rows of the current Material as the renderer draws them.
class MaterialRows {
 public:
  explicit MaterialRows(const Node* material) {
    static const Node kDefault{.type = "Material"};
    const Node& m = material ? *material : kDefault;
    diffuse_ = field_or_default(m, "diffuseColor");
    emissive_ = field_or_default(m, "emissiveColor");
    transparency_ = field_or_default(m, "transparency");
    rows_ = std::max({std::size_t(1), diffuse_->floats.size() / 3, emissive_->floats.size() / 3,
                      transparency_->floats.size()});
  }
  std::size_t rows() const { return rows_; }
  Vec3 color(std::size_t row) const {
    const Vec3 c = value3(diffuse_, row, {0.8f, 0.8f, 0.8f}) + value3(emissive_, row, {});
    return {std::clamp(c.x, 0.f, 1.f), std::clamp(c.y, 0.f, 1.f), std::clamp(c.z, 0.f, 1.f)};
  }
  float opacity(std::size_t row) const {
    const std::vector<float>& t = transparency_->floats;
    return t.empty() ? 1.f : 1.f - std::clamp(t[std::min(row, t.size() - 1)], 0.f, 1.f);
  }

 private:
  // A field with fewer values than `row` repeats its last one.
  static Vec3 value3(const FieldValue* v, std::size_t row, Vec3 if_empty) {
    const std::size_t n = v->floats.size() / 3;
    if (n == 0) return if_empty;
    const std::size_t i = 3 * std::min(row, n - 1);
    return {v->floats[i], v->floats[i + 1], v->floats[i + 2]};
  }
  const FieldValue* diffuse_ = nullptr;
  const FieldValue* emissive_ = nullptr;
  const FieldValue* transparency_ = nullptr;
  std::size_t rows_ = 1;
};

// The Texture2 drawn under `state`: one with a filename or a non-empty
// image (an empty Texture2 turns texturing off, as the specification says).
const Node* current_texture(const TraversalState& state) {
  if (!state.texture2) return nullptr;
  const FieldValue* name = state.texture2->applied_value("filename");
  const FieldValue* image = state.texture2->applied_value("image");
  const bool named = name && !name->strings.empty() && !name->strings[0].empty();
  const bool inline_image = image && image->ints.size() > 3 && image->ints[0] > 0 &&
                            image->ints[1] > 0 && image->ints[2] > 0;
  return named || inline_image ? state.texture2 : nullptr;
}

// VRML 1.0's default texture coordinates of an indexed set: s along the
// longest side of the bounding box of the points it uses, 0..1; t along the
// second longest, 0..(its length / the longest).
class DefaultMapping {
 public:
  DefaultMapping(const std::vector<Vec3>& pts, const std::vector<std::int32_t>& coord_index) {
    for (std::int32_t i : coord_index)
      if (i >= 0 && std::size_t(i) < pts.size()) box_.add(pts[std::size_t(i)]);
    if (box_.empty()) return;
    const Vec3 size = box_.hi - box_.lo;
    const float e[3] = {size.x, size.y, size.z};
    s_ = 0;
    for (int a = 1; a < 3; ++a)
      if (e[a] > e[s_]) s_ = a;
    t_ = s_ == 0 ? 1 : 0;
    for (int a = 0; a < 3; ++a)
      if (a != s_ && e[a] > e[t_]) t_ = a;
    size_ = e[s_] > 0 ? e[s_] : 1.f;
  }
  Vec2 at(const Vec3& p) const {
    if (box_.empty()) return {};
    return {(p[s_] - box_.lo[s_]) / size_, (p[t_] - box_.lo[t_]) / size_};
  }

 private:
  Box3 box_;
  int s_ = 0, t_ = 1;
  float size_ = 1;
};

// The vertices of an indexed set: without appearance one per coordinate;
// with it one per distinct (coordinate, material row, texture coordinate)
// of its corners, so colours and texture coordinates can differ at a
// coordinate (a face's own colour, a texture seam).
class CornerVertices {
 public:
  // Without appearance `pts` must be out.mesh.positions itself (one vertex
  // per coordinate, nothing copied).
  CornerVertices(ShapeSurface& out, const std::vector<Vec3>& pts, bool appearance)
      : out_(out), pts_(pts), appearance_(appearance) {}
  // `texcoord` is an index into `texcoords`, or -1 for the default mapping
  // (ignored when the shape is not textured).
  std::uint32_t vertex(std::int32_t coord, std::size_t row, std::int64_t texcoord,
                       const MaterialRows& materials, const std::vector<float>* texcoords,
                       const DefaultMapping* mapping) {
    if (!appearance_) return std::uint32_t(coord);
    const Key key{coord, std::uint32_t(row), mapping ? std::int32_t(texcoord) : -1};
    auto [it, fresh] = ids_.try_emplace(key, std::uint32_t(out_.mesh.positions.size()));
    if (fresh) {
      const Vec3& p = pts_[std::size_t(coord)];
      out_.mesh.positions.push_back(p);
      out_.mesh.colors.push_back(materials.color(row));
      out_.opacity.push_back(materials.opacity(row));
      if (mapping)
        out_.mesh.texcoords.push_back(texcoord >= 0
                                          ? Vec2{(*texcoords)[2 * std::size_t(texcoord)],
                                                 (*texcoords)[2 * std::size_t(texcoord) + 1]}
                                          : mapping->at(p));
    }
    return it->second;
  }

 private:
  struct Key {
    std::int32_t coord;
    std::uint32_t row;
    std::int32_t texcoord;
    bool operator<(const Key& o) const {
      return std::tie(coord, row, texcoord) < std::tie(o.coord, o.row, o.texcoord);
    }
  };
  ShapeSurface& out_;
  const std::vector<Vec3>& pts_;
  bool appearance_;
  std::map<Key, std::uint32_t> ids_;
};

// An attribute of the shape read under the one face-set rule
// (corner_attribute): OVERALL is `fallback`, and so is a bad index, after
// one warning per shape, because a renderer draws the shape without it.
class CheckedIndex {
 public:
  CheckedIndex(FaceSetAttribute attribute, const std::string& where, LogCategory category, Log* log)
      : attribute_(attribute), where_(where), category_(category), log_(log) {}
  std::int64_t operator()(std::size_t face, std::size_t corner_seq, std::size_t pos,
                          std::int64_t fallback) {
    if (attribute_.indexer.bind == Binding::kOverall) return fallback;
    try {
      return corner_attribute(attribute_, face, corner_seq, pos, where_);
    } catch (const DataError& e) {
      if (log_ && !warned_) log_->warn(category_, fmt::format("{}; drawn without it", e.what()));
      warned_ = true;
      return fallback;
    }
  }

 private:
  FaceSetAttribute attribute_;
  const std::string& where_;
  LogCategory category_;
  Log* log_;
  bool warned_ = false;
};

// An IndexedFaceSet or IndexedLineSet: faces triangulated, polylines as
// segments, with appearance when asked.
void indexed_set(const ShapeVisit& visit, const ShapeMeshOptions& options, Log* log,
                 ShapeSurface& out) {
  const Node& shape = visit.shape;
  const bool line_set = shape.type == "IndexedLineSet";
  std::vector<Vec3> coords = coordinates(visit.state, shape);
  if (!options.appearance) out.mesh.positions = std::move(coords);
  const std::vector<Vec3>& pts = options.appearance ? coords : out.mesh.positions;
  const std::vector<std::int32_t>& ci = field_or_default(shape, "coordIndex")->ints;
  CornerVertices vertices(out, pts, options.appearance);

  // Appearance: material rows by the binding, texture coordinates by
  // textureCoordIndex (scene/attribute_binding.h).
  const std::string where = fmt::format("line {}: {}", shape.first_line, shape.type);
  const MaterialRows materials(visit.state.material);
  const Binding mbind = binding_of(visit.state.material_binding, Binding::kOverall);
  CheckedIndex material_row({{mbind, &field_or_default(shape, "materialIndex")->ints, &ci},
                             materials.rows(),
                             "materialIndex"},
                            where, LogCategory::kMaterial, log);
  out.texture = options.appearance && !line_set ? current_texture(visit.state) : nullptr;
  const FieldValue* tc = out.texture && visit.state.texture_coordinate2
                             ? field_or_default(*visit.state.texture_coordinate2, "point")
                             : nullptr;
  const FieldValue* tci = field_or_default(shape, "textureCoordIndex");
  CheckedIndex texcoord_index({{Binding::kPerVertexIndexed, tci ? &tci->ints : nullptr, &ci},
                               tc ? tc->floats.size() / 2 : 0,
                               "textureCoordIndex"},
                              where, LogCategory::kTexCoord, log);
  const std::optional<DefaultMapping> mapping =
      out.texture ? std::optional<DefaultMapping>(DefaultMapping(pts, ci)) : std::nullopt;

  auto note_face = [&](std::size_t at, const char* what) {
    log->add(LogLevel::kMessage, LogCategory::kTriangulator,
             fmt::format("line {}: face at coordIndex[{}] is {}", shape.first_line, at, what));
  };
  const std::vector<FaceRun> runs = face_runs(ci, pts.size(), {where, "Coordinate3"});
  const FaceTriangulation triangulation{.triangulation = options.triangulation,
                                        .diagnose_triangles = log != nullptr};
  std::vector<std::uint32_t> poly;
  std::size_t corner_seq = 0;
  for (std::size_t face = 0; face < runs.size(); ++face) {
    const auto [b, e] = runs[face];
    poly.clear();
    for (std::size_t i = b; i < e; ++i, ++corner_seq) {
      const std::size_t row =
          options.appearance ? std::size_t(material_row(face, corner_seq, i, 0)) : 0;
      const std::int64_t t = tc ? texcoord_index(face, corner_seq, i, -1) : std::int64_t(-1);
      poly.push_back(vertices.vertex(ci[i], row, t, materials, tc ? &tc->floats : nullptr,
                                     mapping ? &*mapping : nullptr));
    }
    if (line_set) {
      for (std::size_t i = 1; i < poly.size(); ++i)
        out.mesh.lines.push_back({poly[i - 1], poly[i]});
      continue;
    }
    const FaceTriangles ft =
        face_triangles(out.mesh.positions, poly, triangulation, out.mesh.triangles);
    if (ft.corners < 3) {
      if (log)
        log->warn(LogCategory::kFace, fmt::format("line {}: IndexedFaceSet face at coordIndex[{}] "
                                                  "has {} vertices; skipped",
                                                  shape.first_line, b, poly.size()));
      continue;
    }
    if (log && (ft.degenerate || ft.not_simple))
      note_face(b, ft.degenerate ? "degenerate" : "not simple");
  }
}

ShapeSurface surface(const ShapeVisit& visit, const ShapeMeshOptions& options, Log* log) {
  if (has_indexed_equivalent(visit.shape.type)) {
    // Inventor's strips, quad meshes and face sets: as the indexed set that
    // draws the same.
    const IndexedEquivalent eq = to_indexed_shape(visit);
    return surface(ShapeVisit{*eq.shape, eq.state, visit.camera, visit.path, visit.child_index,
                              visit.path_index},
                   options, log);
  }
  const Node& shape = visit.shape;
  ShapeSurface out;
  TriangleMesh& mesh = out.mesh;
  const std::string& t = shape.type;
  if (t == "IndexedFaceSet" || t == "IndexedLineSet") {
    indexed_set(visit, options, log, out);
  } else {
    if (t == "Cube" || t == "Sphere" || t == "Cone" || t == "Cylinder") {
      TessellateOptions tess = options.tessellation;
      tess.complexity = complexity_value(visit.state);
      mesh = tessellate_primitive(shape, tess);
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
    // Primitives and points: the first material row everywhere.
    out.texture = options.appearance && !mesh.triangles.empty() && mesh.has_texcoords()
                      ? current_texture(visit.state)
                      : nullptr;
    if (!out.texture) mesh.texcoords.clear();
    if (options.appearance) {
      const MaterialRows materials(visit.state.material);
      mesh.colors.assign(mesh.positions.size(), materials.color(0));
      out.opacity.assign(mesh.positions.size(), materials.opacity(0));
    }
  }
  if (out.texture && !(visit.state.texture_transform == Mat4{}))
    for (Vec2& t : mesh.texcoords) {
      const Vec3 q = visit.state.texture_transform.transform_point({t.x, t.y, 0});
      t = {q.x, q.y};
    }
  if (options.world_space && !(visit.state.transform == Mat4{})) {
    for (auto& p : mesh.positions) p = visit.state.transform.transform_point(p);
    if (mesh.has_normals()) {
      Mat4 nm = visit.state.transform.normal_matrix();
      for (auto& n : mesh.normals) n = normalized(nm.transform_vector(n));
    }
  }
  return out;
}

}  // namespace

TriangleMesh shape_mesh(const ShapeVisit& visit, const ShapeMeshOptions& options, Log* log) {
  return surface(visit, options, log).mesh;
}

ShapeCounts shape_counts(const ShapeVisit& visit, const ShapeMeshOptions& options) {
  const Node& shape = visit.shape;
  const bool line_set = shape.type == "IndexedLineSet";
  ShapeCounts counts;
  if (!line_set && shape.type != "IndexedFaceSet") {
    ShapeMeshOptions plain = options;
    plain.appearance = false;
    const TriangleMesh m = shape_mesh(visit, plain);
    counts.triangles = m.triangle_count();
    counts.vertices = m.vertex_count();
    counts.segments = m.lines.size();
    for (const Vec3& p : m.positions) counts.bounds.add(p);
    return counts;
  }
  const std::span<const float> f = coordinate_floats(visit.state, shape);
  const std::size_t points = f.size() / 3;
  const std::vector<std::int32_t>& ci = field_or_default(shape, "coordIndex")->ints;
  const std::string where = fmt::format("line {}: {}", shape.first_line, shape.type);
  check_coord_index(ci, points, {where, "Coordinate3"});
  for_each_index_run(ci, [&](std::size_t b, std::size_t e) {
    if (line_set)
      counts.segments += e - b - 1;
    else if (e - b >= 3)
      counts.triangles += e - b - 2;
  });
  counts.vertices = points;
  const bool move = options.world_space && !(visit.state.transform == Mat4{});
  for (std::size_t i = 0; i < points; ++i) {
    const Vec3 p{f[3 * i], f[3 * i + 1], f[3 * i + 2]};
    counts.bounds.add(move ? visit.state.transform.transform_point(p) : p);
  }
  return counts;
}

ShapeSurface shape_surface(const ShapeVisit& visit, const ShapeMeshOptions& options, Log* log) {
  ShapeMeshOptions with = options;
  with.appearance = true;
  return surface(visit, with, log);
}

}  // namespace lodforge::scene
