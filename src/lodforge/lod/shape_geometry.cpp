// IndexedFaceSet / IndexedLineSet <-> attributed triangle mesh, with the
// binding rules of the VRML 1.0 specification (MaterialBinding,
// NormalBinding, texture coordinates: scene/attribute_binding.h) and the
// binding conversion of the original LODCreator (§4: PER_FACE, PER_PART and
// PER_VERTEX become indexed, with synthesised indices, because levels share
// one attribute list).
#include "lodforge/lod/shape_geometry.h"

#include <fmt/format.h>

#include <array>
#include <cstring>
#include <map>
#include <unordered_map>

#include "lodforge/core/error.h"
#include "lodforge/scene/attribute_binding.h"
#include "lodforge/scene/inventor_shapes.h"
#include "lodforge/scene/schema.h"
#include "lodforge/scene/shape_mesh.h"

namespace lodforge {
namespace {

using scene::FieldValue;
using scene::make_node;
using scene::Node;
using scene::NodePtr;

using scene::AttributeIndexer;
using Bind = scene::Binding;
using scene::binding_of;

// Rows of a Material node: one row per index, fields of fewer values repeat
// their last value (a single colour with many transparencies, say).
constexpr std::array<const char*, 6> kMaterialFields = {
    "ambientColor", "diffuseColor", "specularColor", "emissiveColor", "shininess", "transparency"};

std::size_t material_rows(const Node& m) {
  std::size_t n = 1;
  for (const char* f : kMaterialFields)
    if (const FieldValue* v = m.value(f)) n = std::max(n, v->count());
  return n;
}

std::vector<float> material_row(const Node& m, std::size_t row) {
  std::vector<float> r;
  for (const char* f : kMaterialFields) {
    const FieldValue* v = scene::field_or_default(m, f);
    int comps = scene::float_components(v->type.kind);
    std::size_t count = v->floats.size() / std::size_t(comps);
    if (count == 0) {
      r.insert(r.end(), std::size_t(comps), -1.f);  // field given empty
      continue;
    }
    std::size_t i = std::min(row, count - 1);
    r.insert(r.end(), v->floats.begin() + std::ptrdiff_t(i * comps),
             v->floats.begin() + std::ptrdiff_t((i + 1) * comps));
  }
  return r;
}

struct VertexKey {
  std::array<std::uint32_t, 3> pos;
  std::uint32_t normal, texcoord, material;
  bool operator==(const VertexKey&) const = default;
};
struct VertexKeyHash {
  std::size_t operator()(const VertexKey& k) const {
    std::uint64_t h = 1469598103934665603ull;
    auto mix = [&](std::uint32_t v) { h = (h ^ v) * 1099511628211ull; };
    for (auto p : k.pos) mix(p);
    mix(k.normal);
    mix(k.texcoord);
    mix(k.material);
    return std::size_t(h ^ (h >> 29));
  }
};

std::uint32_t bits(float f) {
  if (f == 0) f = 0;  // -0 and +0 are one coordinate
  std::uint32_t b;
  std::memcpy(&b, &f, 4);
  return b;
}

template <typename T, typename Key>
class Deduper {
 public:
  std::uint32_t add(const T& value, const Key& key) {
    auto [it, fresh] = ids_.try_emplace(key, std::uint32_t(values.size()));
    if (fresh) values.push_back(value);
    return it->second;
  }
  std::vector<T> values;

 private:
  std::map<Key, std::uint32_t> ids_;
};

constexpr std::uint32_t kNone = 0xFFFFFFFFu;

}  // namespace

ShapeGeometry read_shape_geometry(const scene::ShapeVisit& visit,
                                  const ShapeGeometryOptions& options, Log& log) {
  if (scene::has_indexed_equivalent(visit.shape.type)) {
    // Inventor's strips, quad meshes and face sets: read as the indexed set
    // that draws the same; what the levels inherit is the input's state.
    const scene::IndexedEquivalent eq = scene::to_indexed_shape(visit);
    ShapeGeometry g =
        read_shape_geometry(scene::ShapeVisit{*eq.shape, eq.state, visit.camera, visit.path,
                                              visit.child_index, visit.path_index},
                            options, log);
    mark_inherited_attributes(g, visit.state);
    return g;
  }
  const Node& shape = visit.shape;
  const scene::TraversalState& st = visit.state;
  const bool lines = shape.type == "IndexedLineSet";
  ShapeGeometry g;

  // Coordinates (checked as the scene module does).
  static const Node kDefaultCoords{.type = "Coordinate3"};
  const FieldValue* pts =
      scene::field_or_default(st.coordinate3 ? *st.coordinate3 : kDefaultCoords, "point");
  const std::size_t npts = pts->floats.size() / 3;
  auto point = [&](std::size_t i) {
    return Vec3{pts->floats[3 * i], pts->floats[3 * i + 1], pts->floats[3 * i + 2]};
  };
  const FieldValue* coord_index = scene::field_or_default(shape, "coordIndex");
  const std::vector<std::int32_t>& ci = coord_index->ints;

  // Bindings.
  Bind mbind = binding_of(st.material_binding, Bind::kOverall);
  Bind nbind = binding_of(st.normal_binding, Bind::kPerVertexIndexed);
  const FieldValue* normal_field =
      st.normal ? scene::field_or_default(*st.normal, "vector") : nullptr;
  std::size_t nnormals = normal_field ? normal_field->floats.size() / 3 : 0;
  if (lines || nnormals == 0) nbind = Bind::kOverall;
  const FieldValue* tc_field =
      st.texture_coordinate2 ? scene::field_or_default(*st.texture_coordinate2, "point") : nullptr;
  std::size_t ntex = tc_field ? tc_field->floats.size() / 2 : 0;
  g.has_texcoords = !lines && ntex > 0;

  const Node* material = st.material;
  static const Node kDefaultMaterial{.type = "Material"};
  const Node& mat = material ? *material : kDefaultMaterial;
  const std::size_t nmat = material_rows(mat);
  if (mbind != Bind::kOverall && nmat <= 1 && mbind != Bind::kPerFaceIndexed &&
      mbind != Bind::kPerVertexIndexed)
    mbind = Bind::kOverall;  // one material for everything: nothing to bind

  AttributeIndexer mindex{mbind, &scene::field_or_default(shape, "materialIndex")->ints, &ci};
  AttributeIndexer nindex{nbind, &scene::field_or_default(shape, "normalIndex")->ints, &ci};
  const FieldValue* tci = scene::field_or_default(shape, "textureCoordIndex");
  AttributeIndexer tindex{Bind::kPerVertexIndexed, &tci->ints, &ci};

  bool material_ok = mbind != Bind::kOverall, normal_ok = nbind != Bind::kOverall,
       tex_ok = g.has_texcoords;
  bool repaired = false;
  auto drop = [&](bool& ok, const char* what, std::int64_t bad, std::size_t limit) {
    if (!ok) return;
    ok = false;
    repaired = true;
    log.warn(LogCategory::kParse,
             fmt::format("line {}: {} {} index {} is out of range (0..{}); the {}s are ignored",
                         shape.first_line, shape.type, what, bad, std::int64_t(limit) - 1, what));
  };

  Deduper<Vec3, std::array<std::uint32_t, 3>> normals;
  Deduper<Vec2, std::array<std::uint32_t, 2>> texcoords;
  Deduper<std::uint32_t, std::vector<float>> materials;  // value: source row
  std::unordered_map<VertexKey, std::uint32_t, VertexKeyHash> vertex_ids;

  struct Corner {
    std::uint32_t vertex;
    std::int64_t material;
  };
  std::vector<Corner> corners;
  std::vector<std::uint32_t> poly;
  std::vector<std::int64_t> face_materials;
  std::vector<std::uint32_t> face_normals;
  std::size_t corner_seq = 0;

  // A pass reads every face; an attribute found out of range switches its
  // binding off and the pass starts over (at most once per attribute).
  auto runs = scene::split_index_runs(ci);
  while (true) {
    bool was_ok[3] = {material_ok, normal_ok, tex_ok};
    g = ShapeGeometry{};
    g.has_texcoords = tex_ok;
    normals = {};
    texcoords = {};
    materials = {};
    vertex_ids.clear();
    corner_seq = 0;
    std::vector<std::uint32_t>& vertex_face_material = g.vertex_face_material;
    for (std::size_t f = 0; f < runs.size(); ++f) {
      auto [b, e] = runs[f];
      corners.clear();
      std::int64_t fmat = material_ok && (mbind == Bind::kPerFace || mbind == Bind::kPerFaceIndexed)
                              ? mindex.at(f, 0, b)
                              : -1;
      if (fmat != -1 && (fmat < 0 || std::size_t(fmat) >= nmat))
        drop(material_ok, "material", fmat, nmat);
      std::int64_t fnorm = normal_ok && (nbind == Bind::kPerFace || nbind == Bind::kPerFaceIndexed)
                               ? nindex.at(f, 0, b)
                               : -1;
      if (fnorm != -1 && (fnorm < 0 || std::size_t(fnorm) >= nnormals))
        drop(normal_ok, "normal", fnorm, nnormals);
      for (std::size_t p = b; p < e; ++p, ++corner_seq) {
        std::int32_t c = ci[p];
        if (c < 0 || std::size_t(c) >= npts)
          throw DataError(
              fmt::format("line {}: {} coordIndex[{}] = {} is out of range (the "
                          "current Coordinate3 has {} points)",
                          shape.first_line, shape.type, p, c, npts));
        Vec3 x = point(std::size_t(c));
        if (!is_finite(x))
          throw DataError(fmt::format(
              "line {}: Coordinate3 point {} used by the {} at line {} is "
              "not finite",
              st.coordinate3 ? st.coordinate3->first_line : 0, c, shape.type, shape.first_line));
        VertexKey key{{bits(x.x), bits(x.y), bits(x.z)}, kNone, kNone, kNone};
        if (normal_ok && (nbind == Bind::kPerVertex || nbind == Bind::kPerVertexIndexed)) {
          std::int64_t n = nindex.at(f, corner_seq, p);
          if (n < 0 || std::size_t(n) >= nnormals)
            drop(normal_ok, "normal", n, nnormals);
          else {
            Vec3 v{normal_field->floats[3 * n], normal_field->floats[3 * n + 1],
                   normal_field->floats[3 * n + 2]};
            key.normal = normals.add(v, {bits(v.x), bits(v.y), bits(v.z)});
          }
        }
        if (tex_ok) {
          std::int64_t t = tindex.at(f, corner_seq, p);
          if (t < 0 || std::size_t(t) >= ntex)
            drop(tex_ok, "texture coordinate", t, ntex);
          else {
            Vec2 v{tc_field->floats[2 * t], tc_field->floats[2 * t + 1]};
            key.texcoord = texcoords.add(v, {bits(v.x), bits(v.y)});
          }
        }
        std::int64_t vm = -1;
        if (material_ok && (mbind == Bind::kPerVertex || mbind == Bind::kPerVertexIndexed)) {
          vm = mindex.at(f, corner_seq, p);
          if (vm < 0 || std::size_t(vm) >= nmat)
            drop(material_ok, "material", vm, nmat);
          else
            key.material = materials.add(std::uint32_t(vm), material_row(mat, std::size_t(vm)));
        }
        auto [it, fresh] = vertex_ids.try_emplace(key, std::uint32_t(g.mesh.positions.size()));
        if (fresh) {
          g.mesh.positions.push_back(x);
          g.vertex_normal.push_back(key.normal);
          g.vertex_texcoord.push_back(key.texcoord);
          g.vertex_material.push_back(key.material);
          vertex_face_material.push_back(kNone);
        }
        corners.push_back({it->second, vm});
      }
      if (was_ok[0] != material_ok || was_ok[1] != normal_ok || was_ok[2] != tex_ok)
        break;  // an attribute was dropped: start over without it
      std::uint32_t face_mat = kNone;
      if (material_ok && fmat >= 0)
        face_mat = materials.add(std::uint32_t(fmat), material_row(mat, std::size_t(fmat)));
      std::uint32_t face_norm = kNone;
      if (normal_ok && fnorm >= 0) {
        Vec3 v{normal_field->floats[3 * fnorm], normal_field->floats[3 * fnorm + 1],
               normal_field->floats[3 * fnorm + 2]};
        face_norm = normals.add(v, {bits(v.x), bits(v.y), bits(v.z)});
      }
      ++g.input_faces;
      if (lines) {
        for (std::size_t i = 1; i < corners.size(); ++i) {
          if (corners[i].vertex == corners[i - 1].vertex) continue;
          g.mesh.lines.push_back({corners[i - 1].vertex, corners[i].vertex});
          g.segment_material.push_back(face_mat);
        }
        continue;
      }
      // Consecutive repeated corners (and a closing repeat) carry no area.
      poly.clear();
      for (const auto& c : corners)
        if (poly.empty() || poly.back() != c.vertex) poly.push_back(c.vertex);
      while (poly.size() > 1 && poly.front() == poly.back()) poly.pop_back();
      if (poly.size() < 3) {
        ++g.dropped_faces;
        continue;
      }
      TriangulateResult tr = triangulate_polygon(g.mesh.positions, poly, options.triangulation);
      if (tr.has_warning())
        log.add(LogLevel::kMessage, LogCategory::kTriangulator,
                fmt::format("line {}: face {} is {}; triangulated anyway", shape.first_line, f,
                            tr.degenerate ? "degenerate" : "not simple"));
      std::uint32_t polygon = std::uint32_t(g.polygon_is_quad.size());
      g.polygon_is_quad.push_back(poly.size() == 4 && tr.keep_as_quad);
      for (const auto& t : tr.triangles) {
        g.mesh.triangles.push_back({poly[t[0]], poly[t[1]], poly[t[2]]});
        g.triangle_polygon.push_back(polygon);
        g.face_normal.push_back(face_norm);
        if (face_mat != kNone) g.mesh.materials.push_back(face_mat);
        for (int k = 0; k < 3; ++k)
          if (vertex_face_material[poly[t[k]]] == kNone)
            vertex_face_material[poly[t[k]]] = face_mat;
      }
    }
    if (was_ok[0] == material_ok && was_ok[1] == normal_ok && was_ok[2] == tex_ok) break;
  }
  if (!g.mesh.materials.empty() && g.mesh.materials.size() != g.mesh.triangles.size())
    g.mesh.materials.clear();

  g.material_binding = !material_ok ? AttributeBinding::kNone
                       : (mbind == Bind::kPerVertex || mbind == Bind::kPerVertexIndexed)
                           ? AttributeBinding::kPerVertex
                           : AttributeBinding::kPerFace;
  g.normal_binding = !normal_ok ? AttributeBinding::kNone
                     : (nbind == Bind::kPerVertex || nbind == Bind::kPerVertexIndexed)
                         ? AttributeBinding::kPerVertex
                         : AttributeBinding::kPerFace;
  g.has_texcoords = tex_ok;
  // The input node is drawn as it is only if every index it holds is in
  // range of what it indexes (an index field the geometry does not use, e.g.
  // textureCoordIndex without texture coordinates, still reaches a reader).
  auto in_range = [&](const char* field, std::size_t limit) {
    const FieldValue* idx = shape.value(field);
    if (!idx) return true;
    for (std::int32_t i : idx->ints)
      if (i < -1 || (i >= 0 && std::size_t(i) >= limit)) return false;
    return true;
  };
  g.repaired = repaired || !in_range("normalIndex", nnormals) ||
               !in_range("textureCoordIndex", ntex) ||
               !in_range("materialIndex", std::max<std::size_t>(nmat, 1));
  g.normal_values = normals.values;
  g.texcoord_values = texcoords.values;
  if (g.material_binding != AttributeBinding::kNone) {
    // The distinct materials as one Material node, rows in first-use order.
    auto m = std::make_shared<Node>();
    m->type = "Material";
    for (const char* f : kMaterialFields) {
      const FieldValue* src = scene::field_or_default(mat, f);
      int comps = scene::float_components(src->type.kind);
      std::size_t count = src->floats.size() / std::size_t(comps);
      if (count == 0) continue;
      std::vector<float> vals;
      for (std::uint32_t row : materials.values) {
        std::size_t i = std::min<std::size_t>(row, count - 1);
        vals.insert(vals.end(), src->floats.begin() + std::ptrdiff_t(i * comps),
                    src->floats.begin() + std::ptrdiff_t((i + 1) * comps));
      }
      if (mat.value(f) || count > 1) m->set(f, scene::make_floats(src->type.kind, true, vals));
    }
    g.material = m;
  }
  if (g.material_binding == AttributeBinding::kPerVertex && lines) g.segment_material.clear();
  mark_inherited_attributes(g, st);
  const Node* hints = st.shape_hints;
  const FieldValue* face_type = hints ? scene::field_or_default(*hints, "faceType") : nullptr;
  g.needs_convex_hint =
      !lines && face_type && !face_type->strings.empty() && face_type->strings[0] != "CONVEX";
  return g;
}

void mark_inherited_attributes(ShapeGeometry& g, const scene::TraversalState& st) {
  g.override_normals = st.normal && g.normal_binding == AttributeBinding::kNone;
  g.override_texcoords = st.texture_coordinate2 && !g.has_texcoords;
  g.override_material_binding = g.material_binding == AttributeBinding::kNone &&
                                binding_of(st.material_binding, Bind::kOverall) != Bind::kOverall;
}

}  // namespace lodforge

namespace lodforge {
namespace {

// The index lists of one IndexedFaceSet or IndexedLineSet being written.
struct IndexWriter {
  std::vector<std::int32_t> coord, normal, texcoord, material;
};

// The values of a pool as one flat list (x y [z] per value).
template <typename V>
std::vector<float> flat(const std::vector<V>& values) {
  constexpr std::size_t n = sizeof(V) / sizeof(float);
  std::vector<float> out;
  out.reserve(n * values.size());
  for (const V& v : values) out.insert(out.end(), &v.x, &v.x + n);
  return out;
}

NodePtr binding_node(const char* type, AttributeBinding b) {
  auto n = make_node(type);
  n->set("value", scene::make_enum(b == AttributeBinding::kPerFace ? "PER_FACE_INDEXED"
                                                                   : "PER_VERTEX_INDEXED"));
  return n;
}

}  // namespace

struct LevelWriter::Impl {
  const ShapeGeometry& g;
  bool no_lines;
  Deduper<Vec3, std::array<std::uint32_t, 3>> coords, normals;
  Deduper<Vec2, std::array<std::uint32_t, 2>> texs;
  std::vector<NodePtr> properties;  // shared by every level, in order
  NodePtr coord_node, normal_node, tex_node;
};

LevelWriter::LevelWriter(const ShapeGeometry& g, const scene::TraversalState& state, bool no_lines)
    : impl_(new Impl{.g = g, .no_lines = no_lines}) {
  using scene::FieldKind;
  auto& props = impl_->properties;
  if (g.material_binding != AttributeBinding::kNone) {
    props.push_back(g.material);
    props.push_back(binding_node("MaterialBinding", g.material_binding));
  } else if (g.override_material_binding) {
    auto overall = make_node("MaterialBinding");
    overall->set("value", scene::make_enum("OVERALL"));
    props.push_back(overall);
  }
  if (g.normal_binding != AttributeBinding::kNone)
    props.push_back(binding_node("NormalBinding", g.normal_binding));
  if (g.needs_convex_hint && state.shape_hints) {
    auto hints = std::make_shared<Node>(*state.shape_hints);
    hints->name.clear();
    hints->children.clear();
    hints->set("faceType", scene::make_enum("CONVEX"));
    props.push_back(hints);
  }
  impl_->coord_node = make_node("Coordinate3");
  props.push_back(impl_->coord_node);
  if (g.normal_binding != AttributeBinding::kNone || g.override_normals) {
    impl_->normal_node = make_node("Normal");
    props.push_back(impl_->normal_node);
  }
  if (g.has_texcoords || g.override_texcoords) {
    impl_->tex_node = make_node("TextureCoordinate2");
    props.push_back(impl_->tex_node);
  }
}

LevelWriter::~LevelWriter() = default;

scene::NodePtr LevelWriter::level(const TriangleMesh& mesh,
                                  const std::vector<std::uint32_t>& vertex_map,
                                  const std::vector<std::uint32_t>& face_map) {
  using scene::FieldKind;
  const ShapeGeometry& g = impl_->g;
  const bool no_lines = impl_->no_lines;
  auto add3 = [](auto& pool, const Vec3& v) {
    return std::int32_t(pool.add(v, {bits(v.x), bits(v.y), bits(v.z)}));
  };
  auto coord_of = [&](std::uint32_t v) { return add3(impl_->coords, mesh.positions[v]); };
  auto normal_of = [&](std::uint32_t value) {
    return add3(impl_->normals, g.normal_values[value]);
  };
  auto tex_of = [&](std::uint32_t value) {
    const Vec2& t = g.texcoord_values[value];
    return std::int32_t(impl_->texs.add(t, {bits(t.x), bits(t.y)}));
  };
  auto origin = [&](std::uint32_t v) { return vertex_map.empty() ? v : vertex_map[v]; };
  auto origin_face = [&](std::size_t t) {
    return face_map.empty() ? std::uint32_t(t) : face_map[t];
  };

  IndexWriter faces;
  auto corner = [&](std::uint32_t v) {
    std::uint32_t o = origin(v);
    faces.coord.push_back(coord_of(v));
    if (g.normal_binding == AttributeBinding::kPerVertex)
      faces.normal.push_back(normal_of(g.vertex_normal[o]));
    if (g.has_texcoords) faces.texcoord.push_back(tex_of(g.vertex_texcoord[o]));
    if (g.material_binding == AttributeBinding::kPerVertex)
      faces.material.push_back(std::int32_t(g.vertex_material[o]));
  };
  auto end_face = [&](std::size_t t) {
    std::uint32_t of = origin_face(t);
    faces.coord.push_back(-1);
    if (g.normal_binding == AttributeBinding::kPerVertex) faces.normal.push_back(-1);
    if (g.normal_binding == AttributeBinding::kPerFace)
      faces.normal.push_back(normal_of(g.face_normal[of]));
    if (g.has_texcoords) faces.texcoord.push_back(-1);
    if (g.material_binding == AttributeBinding::kPerVertex) faces.material.push_back(-1);
    if (g.material_binding == AttributeBinding::kPerFace)
      faces.material.push_back(std::int32_t(g.mesh.materials[of]));
  };

  // Triangles of a polygon kept as a quad become the quad again when both
  // survive, still share their diagonal, and no corner moved: a reader may
  // split a quad along either diagonal, which for moved corners would draw a
  // surface other than the one measured.
  std::unordered_map<std::uint32_t, std::vector<std::size_t>> by_polygon;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    std::uint32_t poly = g.triangle_polygon.empty() ? 0 : g.triangle_polygon[origin_face(t)];
    if (!g.polygon_is_quad.empty() && g.polygon_is_quad[poly]) by_polygon[poly].push_back(t);
  }
  std::vector<bool> done(mesh.triangles.size(), false);
  for (auto& [poly, tris] : by_polygon) {
    if (tris.size() != 2) continue;
    const Triangle& a = mesh.triangles[tris[0]];
    const Triangle& b = mesh.triangles[tris[1]];
    for (int i = 0; i < 3; ++i) {
      std::uint32_t u = a[i], v = a[(i + 1) % 3], x = a[(i + 2) % 3];
      for (int j = 0; j < 3; ++j) {
        if (b[j] == v && b[(j + 1) % 3] == u) {
          std::uint32_t y = b[(j + 2) % 3];
          if (y == x) continue;
          bool moved = false;
          for (std::uint32_t q : {v, x, u, y})
            moved = moved || !(mesh.positions[q] == g.mesh.positions[origin(q)]);
          if (moved) continue;
          for (std::uint32_t q : {v, x, u, y}) corner(q);
          end_face(tris[0]);
          done[tris[0]] = done[tris[1]] = true;
          i = 3;
          break;
        }
      }
    }
  }
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (done[t]) continue;
    for (std::uint32_t v : mesh.triangles[t]) corner(v);
    end_face(t);
  }

  // Line segments: the input's (a line set) or faces collapsed to lines.
  IndexWriter segs;
  const bool line_set = g.mesh.triangles.empty() && !g.mesh.lines.empty();
  if (line_set || !no_lines) {
    for (std::size_t l = 0; l < mesh.lines.size(); ++l) {
      const Segment& s = mesh.lines[l];
      for (std::uint32_t v : s) {
        segs.coord.push_back(coord_of(v));
        if (g.material_binding == AttributeBinding::kPerVertex)
          segs.material.push_back(std::int32_t(g.vertex_material[origin(v)]));
      }
      segs.coord.push_back(-1);
      if (g.material_binding == AttributeBinding::kPerVertex) segs.material.push_back(-1);
      if (g.material_binding == AttributeBinding::kPerFace) {
        // A line keeps the material of a face (or line) it came from.
        std::uint32_t o = origin(s[0]);
        std::uint32_t m = line_set && l < g.segment_material.size() && vertex_map.empty()
                              ? g.segment_material[l]
                          : g.vertex_face_material.empty() ? 0u
                                                           : g.vertex_face_material[o];
        segs.material.push_back(std::int32_t(m == kNone ? 0 : m));
      }
    }
  }

  auto level = make_node("Separator");
  level->children = impl_->properties;
  impl_->coord_node->set("point",
                         scene::make_floats(FieldKind::kVec3f, true, flat(impl_->coords.values)));
  if (impl_->normal_node)
    impl_->normal_node->set(
        "vector", scene::make_floats(FieldKind::kVec3f, true, flat(impl_->normals.values)));
  if (impl_->tex_node)
    impl_->tex_node->set("point",
                         scene::make_floats(FieldKind::kVec2f, true, flat(impl_->texs.values)));
  auto add_set = [&](const char* type, IndexWriter& w) {
    if (w.coord.empty()) return;
    auto s = make_node(type);
    s->set("coordIndex", scene::make_longs(std::move(w.coord)));
    if (!w.material.empty()) s->set("materialIndex", scene::make_longs(std::move(w.material)));
    if (!w.normal.empty()) s->set("normalIndex", scene::make_longs(std::move(w.normal)));
    if (!w.texcoord.empty()) s->set("textureCoordIndex", scene::make_longs(std::move(w.texcoord)));
    level->children.push_back(s);
  };
  add_set("IndexedFaceSet", faces);
  add_set("IndexedLineSet", segs);
  return level;
}

}  // namespace lodforge
