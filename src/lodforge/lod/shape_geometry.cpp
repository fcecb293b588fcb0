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
#include "lodforge/scene/face_set_mesh.h"
#include "lodforge/scene/inventor_shapes.h"
#include "lodforge/scene/schema.h"

namespace lodforge {
namespace {

using scene::FieldValue;
using scene::make_node;
using scene::Node;
using scene::NodePtr;

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

// Reads one IndexedFaceSet or IndexedLineSet under its traversal state into
// a ShapeGeometry: a pass over the faces builds de-duplicated vertices (each
// a position with its normal, texture coordinate and material) and the
// triangles or segments; an attribute index found out of range drops that
// attribute with a warning and the pass starts over without it.
class FaceSetReader {
 public:
  FaceSetReader(const scene::ShapeVisit& visit, const ShapeGeometryOptions& options, Log& log)
      : shape_(visit.shape),
        st_(visit.state),
        options_(options),
        log_(log),
        lines_(shape_.type == "IndexedLineSet"),
        ci_(scene::field_or_default(shape_, "coordIndex")->ints),
        mat_(st_.material ? *st_.material : default_material()),
        where_(fmt::format("line {}: {}", shape_.first_line, shape_.type)) {
    static const Node kDefaultCoords{.type = "Coordinate3"};
    pts_ = scene::field_or_default(st_.coordinate3 ? *st_.coordinate3 : kDefaultCoords, "point");
    npts_ = pts_->floats.size() / 3;
    choose_bindings();
  }

  ShapeGeometry read() {
    ShapeGeometry g;
    const auto runs = scene::face_runs(ci_, npts_, {where_, "Coordinate3"});
    while (!read_pass(runs, g)) {
    }
    finish(g);
    return g;
  }

 private:
  struct Corner {
    std::uint32_t vertex;
    std::int64_t material;
  };

  static const Node& default_material() {
    static const Node kDefaultMaterial{.type = "Material"};
    return kDefaultMaterial;
  }
  static bool per_vertex(Bind b) { return b == Bind::kPerVertex || b == Bind::kPerVertexIndexed; }
  static bool per_face(Bind b) { return b == Bind::kPerFace || b == Bind::kPerFaceIndexed; }

  // The bindings in force, reduced to what the shape can use.
  void choose_bindings() {
    mbind_ = binding_of(st_.material_binding, Bind::kOverall);
    nbind_ = binding_of(st_.normal_binding, Bind::kPerVertexIndexed);
    normal_field_ = st_.normal ? scene::field_or_default(*st_.normal, "vector") : nullptr;
    nnormals_ = normal_field_ ? normal_field_->floats.size() / 3 : 0;
    if (lines_ || nnormals_ == 0) nbind_ = Bind::kOverall;
    tc_field_ = st_.texture_coordinate2 ? scene::field_or_default(*st_.texture_coordinate2, "point")
                                        : nullptr;
    ntex_ = tc_field_ ? tc_field_->floats.size() / 2 : 0;
    nmat_ = material_rows(mat_);
    if (mbind_ != Bind::kOverall && nmat_ <= 1 && mbind_ != Bind::kPerFaceIndexed &&
        mbind_ != Bind::kPerVertexIndexed)
      mbind_ = Bind::kOverall;  // one material for everything: nothing to bind
    material_ok_ = mbind_ != Bind::kOverall;
    normal_ok_ = nbind_ != Bind::kOverall;
    tex_ok_ = !lines_ && ntex_ > 0;
    material_ = {{mbind_, &scene::field_or_default(shape_, "materialIndex")->ints, &ci_},
                 nmat_,
                 "materialIndex"};
    normal_ = {{nbind_, &scene::field_or_default(shape_, "normalIndex")->ints, &ci_},
               nnormals_,
               "normalIndex"};
    tex_ = {{Bind::kPerVertexIndexed, &scene::field_or_default(shape_, "textureCoordIndex")->ints,
             &ci_},
            ntex_,
            "textureCoordIndex"};
  }

  // The value of an attribute at a corner under the one face-set rule
  // (scene::corner_attribute); a bad index switches the attribute off, with
  // a warning, and gives -1.
  std::int64_t value_of(bool& ok, const scene::FaceSetAttribute& a, const char* what, std::size_t f,
                        std::size_t p) {
    try {
      return scene::corner_attribute(a, f, corner_seq_, p, where_);
    } catch (const DataError& e) {
      if (ok)
        log_.warn(LogCategory::kParse, fmt::format("{}; the {}s are ignored", e.what(), what));
      ok = false;
      repaired_ = true;
      return -1;
    }
  }

  Vec3 normal_value(std::int64_t n) const {
    return {normal_field_->floats[3 * n], normal_field_->floats[3 * n + 1],
            normal_field_->floats[3 * n + 2]};
  }
  std::uint32_t add_normal(std::int64_t n) {
    const Vec3 v = normal_value(n);
    return normals_.add(v, {bits(v.x), bits(v.y), bits(v.z)});
  }
  std::uint32_t add_material(std::int64_t m) {
    return materials_.add(std::uint32_t(m), material_row(mat_, std::size_t(m)));
  }

  // One pass over every face; false when an attribute was dropped on the way
  // (the pass must start over without it).
  bool read_pass(const std::vector<std::pair<std::size_t, std::size_t>>& runs, ShapeGeometry& g) {
    g = ShapeGeometry{};
    g.has_texcoords = tex_ok_;
    normals_ = {};
    texcoords_ = {};
    materials_ = {};
    vertex_ids_.clear();
    corner_seq_ = 0;
    for (std::size_t f = 0; f < runs.size(); ++f)
      if (!read_face(f, runs[f].first, runs[f].second, g)) return false;
    return true;
  }

  bool read_face(std::size_t f, std::size_t b, std::size_t e, ShapeGeometry& g) {
    const bool was_ok[3] = {material_ok_, normal_ok_, tex_ok_};
    const std::int64_t fmat =
        material_ok_ && per_face(mbind_) ? value_of(material_ok_, material_, "material", f, b) : -1;
    const std::int64_t fnorm =
        normal_ok_ && per_face(nbind_) ? value_of(normal_ok_, normal_, "normal", f, b) : -1;
    corners_.clear();
    for (std::size_t p = b; p < e; ++p, ++corner_seq_) corners_.push_back(read_corner(f, p, g));
    if (was_ok[0] != material_ok_ || was_ok[1] != normal_ok_ || was_ok[2] != tex_ok_) return false;
    const std::uint32_t face_mat = material_ok_ && fmat >= 0 ? add_material(fmat) : kNone;
    const std::uint32_t face_norm = normal_ok_ && fnorm >= 0 ? add_normal(fnorm) : kNone;
    ++g.input_faces;
    if (lines_)
      add_segments(face_mat, g);
    else
      add_polygon(f, face_mat, face_norm, g);
    return true;
  }

  // Corner p of face f: its vertex (position and per-vertex attributes,
  // de-duplicated) and its per-vertex material index (-1: none).
  Corner read_corner(std::size_t f, std::size_t p, ShapeGeometry& g) {
    const std::int32_t c = ci_[p];  // in range: read() checked it
    const Vec3 x{pts_->floats[3 * std::size_t(c)], pts_->floats[3 * std::size_t(c) + 1],
                 pts_->floats[3 * std::size_t(c) + 2]};
    if (!is_finite(x))
      throw DataError(fmt::format(
          "line {}: Coordinate3 point {} used by the {} at line {} is not finite",
          st_.coordinate3 ? st_.coordinate3->first_line : 0, c, shape_.type, shape_.first_line));
    VertexKey key{{bits(x.x), bits(x.y), bits(x.z)}, kNone, kNone, kNone};
    if (normal_ok_ && per_vertex(nbind_)) {
      const std::int64_t n = value_of(normal_ok_, normal_, "normal", f, p);
      if (n >= 0) key.normal = add_normal(n);
    }
    if (tex_ok_) {
      const std::int64_t t = value_of(tex_ok_, tex_, "texture coordinate", f, p);
      if (t >= 0) {
        const Vec2 v{tc_field_->floats[2 * t], tc_field_->floats[2 * t + 1]};
        key.texcoord = texcoords_.add(v, {bits(v.x), bits(v.y)});
      }
    }
    std::int64_t vm = -1;
    if (material_ok_ && per_vertex(mbind_)) {
      vm = value_of(material_ok_, material_, "material", f, p);
      if (vm >= 0) key.material = add_material(vm);
    }
    auto [it, fresh] = vertex_ids_.try_emplace(key, std::uint32_t(g.mesh.positions.size()));
    if (fresh) {
      g.mesh.positions.push_back(x);
      g.vertex_normal.push_back(key.normal);
      g.vertex_texcoord.push_back(key.texcoord);
      g.vertex_material.push_back(key.material);
      g.vertex_face_material.push_back(kNone);
    }
    return {it->second, vm};
  }

  // A polyline's segments (repeated corners skipped).
  void add_segments(std::uint32_t face_mat, ShapeGeometry& g) {
    for (std::size_t i = 1; i < corners_.size(); ++i) {
      if (corners_[i].vertex == corners_[i - 1].vertex) continue;
      g.mesh.lines.push_back({corners_[i - 1].vertex, corners_[i].vertex});
      g.segment_material.push_back(face_mat);
    }
  }

  // A polygon's triangles; consecutive repeated corners (and a closing
  // repeat) carry no area, a polygon of fewer than 3 corners is dropped.
  void add_polygon(std::size_t f, std::uint32_t face_mat, std::uint32_t face_norm,
                   ShapeGeometry& g) {
    poly_.clear();
    for (const auto& c : corners_) poly_.push_back(c.vertex);
    const std::size_t first = g.mesh.triangles.size();
    const scene::FaceTriangles ft = scene::face_triangles(
        g.mesh.positions, poly_,
        {.triangulation = options_.triangulation, .merge_repeated_corners = true},
        g.mesh.triangles);
    if (ft.corners < 3) {
      ++g.dropped_faces;
      return;
    }
    if (ft.degenerate || ft.not_simple)
      log_.add(LogLevel::kMessage, LogCategory::kTriangulator,
               fmt::format("line {}: face {} is {}; triangulated anyway", shape_.first_line, f,
                           ft.degenerate ? "degenerate" : "not simple"));
    const auto polygon = std::uint32_t(g.polygon_is_quad.size());
    g.polygon_is_quad.push_back(ft.keep_as_quad);
    for (std::size_t i = first; i < g.mesh.triangles.size(); ++i) {
      const Triangle t = g.mesh.triangles[i];
      g.triangle_polygon.push_back(polygon);
      g.face_normal.push_back(face_norm);
      if (face_mat != kNone) g.mesh.materials.push_back(face_mat);
      for (int k = 0; k < 3; ++k)
        if (g.vertex_face_material[t[k]] == kNone) g.vertex_face_material[t[k]] = face_mat;
    }
  }

  // Whether every index of the input's `field` is in range of `limit`
  // values (an index field the geometry does not use, e.g.
  // textureCoordIndex without texture coordinates, still reaches a reader).
  bool in_range(const char* field, std::size_t limit) const {
    const FieldValue* idx = shape_.value(field);
    if (!idx) return true;
    for (std::int32_t i : idx->ints)
      if (i < -1 || (i >= 0 && std::size_t(i) >= limit)) return false;
    return true;
  }

  // The distinct materials as one Material node, rows in first-use order.
  NodePtr material_node() const {
    auto m = std::make_shared<Node>();
    m->type = "Material";
    for (const char* f : kMaterialFields) {
      const FieldValue* src = scene::field_or_default(mat_, f);
      const int comps = scene::float_components(src->type.kind);
      const std::size_t count = src->floats.size() / std::size_t(comps);
      if (count == 0) continue;
      std::vector<float> vals;
      for (std::uint32_t row : materials_.values) {
        const std::size_t i = std::min<std::size_t>(row, count - 1);
        vals.insert(vals.end(), src->floats.begin() + std::ptrdiff_t(i * comps),
                    src->floats.begin() + std::ptrdiff_t((i + 1) * comps));
      }
      if (mat_.value(f) || count > 1) m->set(f, scene::make_floats(src->type.kind, true, vals));
    }
    return m;
  }

  // Bindings, attribute lists and flags of the finished geometry.
  void finish(ShapeGeometry& g) const {
    if (!g.mesh.materials.empty() && g.mesh.materials.size() != g.mesh.triangles.size())
      g.mesh.materials.clear();
    g.material_binding = !material_ok_        ? AttributeBinding::kNone
                         : per_vertex(mbind_) ? AttributeBinding::kPerVertex
                                              : AttributeBinding::kPerFace;
    g.normal_binding = !normal_ok_          ? AttributeBinding::kNone
                       : per_vertex(nbind_) ? AttributeBinding::kPerVertex
                                            : AttributeBinding::kPerFace;
    g.has_texcoords = tex_ok_;
    // The input node is drawn as it is only if every index it holds is in range.
    g.repaired = repaired_ || !in_range("normalIndex", nnormals_) ||
                 !in_range("textureCoordIndex", ntex_) ||
                 !in_range("materialIndex", std::max<std::size_t>(nmat_, 1));
    g.normal_values = normals_.values;
    g.texcoord_values = texcoords_.values;
    if (g.material_binding != AttributeBinding::kNone) g.material = material_node();
    if (g.material_binding == AttributeBinding::kPerVertex && lines_) g.segment_material.clear();
    mark_inherited_attributes(g, st_);
    const Node* hints = st_.shape_hints;
    const FieldValue* face_type = hints ? scene::field_or_default(*hints, "faceType") : nullptr;
    g.needs_convex_hint =
        !lines_ && face_type && !face_type->strings.empty() && face_type->strings[0] != "CONVEX";
  }

  const Node& shape_;
  const scene::TraversalState& st_;
  const ShapeGeometryOptions& options_;
  Log& log_;
  const bool lines_;
  const std::vector<std::int32_t>& ci_;
  const Node& mat_;
  const FieldValue* pts_ = nullptr;
  std::size_t npts_ = 0;
  Bind mbind_ = Bind::kOverall, nbind_ = Bind::kOverall;
  const FieldValue* normal_field_ = nullptr;
  const FieldValue* tc_field_ = nullptr;
  std::size_t nnormals_ = 0, ntex_ = 0, nmat_ = 1;
  std::string where_;
  scene::FaceSetAttribute material_, normal_, tex_;
  bool material_ok_ = false, normal_ok_ = false, tex_ok_ = false, repaired_ = false;

  Deduper<Vec3, std::array<std::uint32_t, 3>> normals_;
  Deduper<Vec2, std::array<std::uint32_t, 2>> texcoords_;
  Deduper<std::uint32_t, std::vector<float>> materials_;  // value: source row
  std::unordered_map<VertexKey, std::uint32_t, VertexKeyHash> vertex_ids_;
  std::vector<Corner> corners_;
  std::vector<std::uint32_t> poly_;
  std::size_t corner_seq_ = 0;
};

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
  return FaceSetReader(visit, options, log).read();
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
