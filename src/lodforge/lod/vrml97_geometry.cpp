#include "lodforge/lod/vrml97_geometry.h"

#include <fmt/format.h>

#include <unordered_map>

#include "lodforge/core/error.h"
#include "lodforge/scene/face_set_mesh.h"

namespace lodforge::vrml97_geometry {

using scene::FieldKind;

bool is_supported_geometry(const std::string& type) {
  return type == "IndexedFaceSet" || type == "IndexedTriangleSet" || type == "TriangleSet" ||
         type == "IndexedQuadSet" || type == "ElevationGrid";
}

bool is_child_list(std::string_view field) {
  return field == "children" || field == "level" || field == "choice";
}

NodePtr node_of(const Node& n, std::string_view field) {
  const scene::FieldValue* v = n.value(field);
  return v && v->type.kind == FieldKind::kNode && !v->nodes.empty() ? v->nodes[0] : nullptr;
}

bool bool_of(const Node& n, std::string_view field, bool fallback) {
  const scene::FieldValue* v = n.value(field);
  return v && v->type.kind == FieldKind::kBool && !v->ints.empty() ? v->ints[0] != 0 : fallback;
}

const std::vector<std::int32_t>* ints_of(const Node& n, std::string_view field) {
  const scene::FieldValue* v = n.value(field);
  return v && v->type.kind == FieldKind::kLong && !v->ints.empty() ? &v->ints : nullptr;
}

std::size_t attribute_count(const NodePtr& n, std::string_view field) {
  if (!n) return 0;
  const scene::FieldValue* v = n->value(field);
  return v ? v->count() : 0;
}

std::vector<NodePtr> texture_coordinate_lists(const NodePtr& tex) {
  std::vector<NodePtr> lists{tex};
  if (tex && tex->type == "MultiTextureCoordinate") {
    const scene::FieldValue* v = tex->value("texCoord");
    lists = v && v->type.kind == FieldKind::kNode ? v->nodes : std::vector<NodePtr>{};
  }
  std::erase_if(lists, [](const NodePtr& n) {
    return !n || !n->type.starts_with("TextureCoordinate") ||
           n->type == "TextureCoordinateGenerator";
  });
  return lists;
}

NodePtr first_texture_coordinates(const NodePtr& tex) {
  for (const NodePtr& t : texture_coordinate_lists(tex))
    if (t->type == "TextureCoordinate") return t;
  return nullptr;
}

namespace {

// How many texture coordinates a texCoord node holds (the fewest among its
// lists, which one texCoordIndex indexes alike), or that it computes them.
void count_texture_coordinates(Attribute& a) {
  if (!a.node) return;
  const std::vector<NodePtr> lists = texture_coordinate_lists(a.node);
  a.generated = lists.empty();
  for (std::size_t k = 0; k < lists.size(); ++k) {
    const std::size_t count = attribute_count(lists[k], "point");
    a.count = k == 0 ? count : std::min(a.count, count);
  }
}

}  // namespace

GeometryReader::GeometryReader(const Node& g, Log& log, const std::string& where)
    : g_(g), log_(log) {
  where_ = where;
  coord_ = node_of(g, "coord");
  coords_ = attribute_count(coord_, "point");
  node_where_ = fmt::format("{}: {}", where_, g.type);
  normal_ = {node_of(g, "normal"), 0, bool_of(g, "normalPerVertex", true),
             ints_of(g, "normalIndex"), "normalIndex"};
  normal_.count = attribute_count(normal_.node, "vector");
  tex_ = {node_of(g, "texCoord"), 0, true, ints_of(g, "texCoordIndex"), "texCoordIndex"};
  count_texture_coordinates(tex_);
  color_ = {node_of(g, "color"), 0, bool_of(g, "colorPerVertex", true), ints_of(g, "colorIndex"),
            "colorIndex"};
  color_.count = attribute_count(color_.node, "color");
  if (g.type == "ElevationGrid") elevation_grid_nodes();
}

bool GeometryReader::read(Polygons& out) {
  if (!coord_ || !coord_->value("point")) return false;  // (an ElevationGrid's is made)
  if (g_.type == "IndexedFaceSet") {
    try {
      read_indexed_face_set(out);
    } catch (const DataError& e) {
      log_.warn(LogCategory::kParse, fmt::format("{}; shape left without LOD", e.what()));
      return false;
    }
  } else if (g_.type == "ElevationGrid") {
    read_elevation_grid(out);
  } else {
    read_triangle_sets(out);
  }
  for (const Corner& c : out.corners)
    if (c[0] >= coords_) {
      log_.warn(LogCategory::kParse,
                fmt::format("{}: {} index {} out of range ({} coordinates); shape left without "
                            "LOD",
                            where_, g_.type, c[0], coords_));
      return false;
    }
  drop_bad(out, normal_, 1, &out.face_normal, "normal");
  drop_bad(out, tex_, 2, nullptr, "texture coordinate");
  drop_bad(out, color_, 3, &out.face_color, "colour");
  return true;
}

void GeometryReader::read_indexed_face_set(Polygons& out) {
  const std::vector<std::int32_t>* ci = ints_of(g_, "coordIndex");
  if (!ci) return;
  const std::vector<scene::FaceRun> runs =
      scene::face_runs(*ci, coords_, {node_where_, coord_->type});
  for (std::size_t face = 0; face < runs.size(); ++face)
    add_face(out, *ci, face, runs[face].first, runs[face].second);
}

std::size_t corners_per_face(const Node& set) {
  return set.type == "IndexedQuadSet" ? 4 : 3;
}

std::vector<std::int32_t> set_corner_order(const Node& set) {
  if (const auto* index = ints_of(set, "index")) return *index;
  std::vector<std::int32_t> order;
  if (set.type == "TriangleSet")
    for (std::size_t i = 0, n = attribute_count(node_of(set, "coord"), "point"); i < n; ++i)
      order.push_back(std::int32_t(i));
  return order;
}

void GeometryReader::read_triangle_sets(Polygons& out) {
  const std::size_t per = corners_per_face(g_);
  const std::vector<std::int32_t> order = set_corner_order(g_);
  for (std::size_t f = 0; f + per <= order.size(); f += per)
    add_face(out, order, f / per, f, f + per);
}

int GeometryReader::int_of(std::string_view field) const {
  const scene::FieldValue* v = g_.value(field);
  return v && !v->ints.empty() ? v->ints[0] : 0;
}

float GeometryReader::float_of(std::string_view field) const {
  const scene::FieldValue* v = g_.value(field);
  return v && !v->floats.empty() ? v->floats[0] : 1.f;
}

void GeometryReader::elevation_grid_nodes() {
  const int nx = int_of("xDimension"), nz = int_of("zDimension");
  const scene::FieldValue* h = g_.value("height");
  if (nx < 2 || nz < 2 || !h || h->floats.size() < std::size_t(nx) * std::size_t(nz)) return;
  const float dx = float_of("xSpacing"), dz = float_of("zSpacing");
  std::vector<float> points, tex;
  for (int z = 0; z < nz; ++z)
    for (int x = 0; x < nx; ++x) {
      points.insert(points.end(), {x * dx, h->floats[std::size_t(z * nx + x)], z * dz});
      tex.insert(tex.end(), {float(x) / float(nx - 1), float(z) / float(nz - 1)});
    }
  coord_ = scene::make_node("Coordinate");
  coord_->set("point", scene::make_floats(FieldKind::kVec3f, true, std::move(points)));
  coords_ = std::size_t(nx) * std::size_t(nz);
  if (!tex_.node) {
    tex_.node = scene::make_node("TextureCoordinate");
    tex_.node->set("point", scene::make_floats(FieldKind::kVec2f, true, std::move(tex)));
    tex_.count = coords_;
  }
}

void GeometryReader::read_elevation_grid(Polygons& out) {
  if (!coord_) return;
  const std::uint32_t nx = std::uint32_t(int_of("xDimension"));
  const std::uint32_t nz = std::uint32_t(int_of("zDimension"));
  std::vector<std::int32_t> quads;
  for (std::uint32_t z = 0; z + 1 < nz; ++z)
    for (std::uint32_t x = 0; x + 1 < nx; ++x)
      for (std::uint32_t v : {z * nx + x, (z + 1) * nx + x, (z + 1) * nx + x + 1, z * nx + x + 1})
        quads.push_back(std::int32_t(v));
  for (std::size_t f = 0; 4 * f < quads.size(); ++f) add_face(out, quads, f, 4 * f, 4 * f + 4);
}

void GeometryReader::add_face(Polygons& out, const std::vector<std::int32_t>& ci, std::size_t face,
                              std::size_t b, std::size_t e) {
  for (std::size_t p = b; p < e; ++p) {
    // A negative coordinate is out of range as an unsigned index: read() rejects the shape.
    const std::uint32_t v = ci[p] < 0 ? kNone - 1 : std::uint32_t(ci[p]);
    out.corners.push_back({v, value(normal_, true, ci, face, p), value(tex_, true, ci, face, p),
                           value(color_, true, ci, face, p)});
  }
  out.start.push_back(std::uint32_t(out.corners.size()));
  out.face_normal.push_back(value(normal_, false, ci, face, b));
  out.face_color.push_back(value(color_, false, ci, face, b));
}

std::uint32_t GeometryReader::value(Attribute& a, bool per_vertex,
                                    const std::vector<std::int32_t>& ci, std::size_t face,
                                    std::size_t pos) {
  if (!a.node || a.generated || a.per_vertex != per_vertex) return kNone;
  const scene::FaceSetAttribute rule{
      {scene::vrml97_binding(a.per_vertex, a.index != nullptr), a.index, &ci},
      a.count,
      a.index_field};
  try {
    return std::uint32_t(scene::corner_attribute(rule, face, pos, pos, node_where_));
  } catch (const DataError& e) {
    if (a.error.empty()) a.error = e.what();
    return kNone;
  }
}

void GeometryReader::drop_bad(Polygons& out, Attribute& a, std::size_t slot,
                              std::vector<std::uint32_t>* per_face, std::string_view what) {
  if (!a.node || a.error.empty()) return;
  log_.warn(LogCategory::kParse, fmt::format("{}; the levels have no {}s", a.error, what));
  a.node = nullptr;
  for (Corner& c : out.corners) c[slot] = kNone;
  if (per_face) std::fill(per_face->begin(), per_face->end(), kNone);
}

void build_mesh(const Polygons& p, const GeometryReader& reader,
                const TriangulateOptions& triangulation, ShapeMesh& out) {
  const std::vector<float>& points = reader.coord()->value("point")->floats;
  std::unordered_map<Corner, std::uint32_t, CornerHash> vertex_of;
  std::vector<std::uint32_t> corner_vertex;
  scene::FaceTriangulation rule{.triangulation = triangulation,
                                .drop_repeated_vertex_triangles = true,
                                .diagnose_triangles = false};
  rule.triangulation.keep_quads = false;
  for (std::size_t f = 0; f + 1 < p.start.size(); ++f) {
    corner_vertex.clear();
    for (std::uint32_t k = p.start[f]; k < p.start[f + 1]; ++k) {
      const Corner& c = p.corners[k];
      auto [it, fresh] = vertex_of.try_emplace(c, std::uint32_t(out.mesh.positions.size()));
      if (fresh) {
        out.mesh.positions.push_back(
            {points[3 * c[0]], points[3 * c[0] + 1], points[3 * c[0] + 2]});
        out.vertex_corner.push_back(c);
      }
      corner_vertex.push_back(it->second);
    }
    scene::face_triangles(out.mesh.positions, corner_vertex, rule, out.mesh.triangles);
    out.triangle_polygon.resize(out.mesh.triangles.size(), std::uint32_t(f));
  }
}

}  // namespace lodforge::vrml97_geometry
