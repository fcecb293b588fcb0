// The LOD pipeline for VRML97 / X3D scenes. The shapes' polygons become one
// mesh per shape whose vertices are the distinct (coordinate, normal,
// texture coordinate, colour) index tuples of their corners, so every
// attribute follows a simplified vertex through the simplifier's vertex map
// back into the input's own attribute nodes; only positions, which a
// simplifier moves, get a new Coordinate node (shared by all levels of a
// shape, each distinct position once).
#include "lodforge/lod/generate_lod_vrml97.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstring>
#include <unordered_map>
#include <unordered_set>

#include "lodforge/core/error.h"
#include "lodforge/core/math.h"
#include "lodforge/lod/choose_levels.h"
#include "lodforge/scene/face_set_mesh.h"

namespace lodforge {
namespace {

using scene::FieldKind;
using scene::Node;
using scene::NodePtr;

constexpr float kDefaultFieldOfView = 0.785398f;  // VRML97 / X3D Viewpoint default, π/4

// One corner's indices into the coordinate, normal, texture coordinate and
// colour nodes (kNone: the attribute is absent or bound per face).
using Corner = std::array<std::uint32_t, 4>;

struct CornerHash {
  std::size_t operator()(const Corner& c) const {
    std::size_t h = 1469598103934665603ull;
    for (std::uint32_t v : c) h = (h ^ v) * 1099511628211ull;
    return h;
  }
};

bool is_supported_geometry(const std::string& type) {
  return type == "IndexedFaceSet" || type == "IndexedTriangleSet" || type == "TriangleSet" ||
         type == "IndexedQuadSet" || type == "ElevationGrid";
}

// The fields whose nodes are children, where a LOD can stand for a Shape.
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

// The values of an attribute node's array field, and how many there are.
std::size_t attribute_count(const NodePtr& n, std::string_view field) {
  if (!n) return 0;
  const scene::FieldValue* v = n->value(field);
  return v ? v->count() : 0;
}

// The polygons of a geometry node as corner tuples, with per-face attributes.
struct Polygons {
  std::vector<std::uint32_t> start{0};  ///< polygon p: corners [start[p], start[p+1])
  std::vector<Corner> corners;
  std::vector<std::uint32_t> face_normal, face_color;  ///< per polygon, when bound per face
};

// One attribute of a geometry node: its node, per vertex or per face, and
// the index field that indexes it (IndexedFaceSet only).
struct Attribute {
  NodePtr node;
  std::size_t count = 0;
  bool per_vertex = true;
  const std::vector<std::int32_t>* index = nullptr;
  std::string_view index_field;
  std::string error;  ///< the first bad index found (the attribute is dropped)
};

class GeometryReader {
 public:
  GeometryReader(const Node& g, Log& log, const std::string& where) : g_(g), log_(log) {
    where_ = where;
    coord_ = node_of(g, "coord");
    coords_ = attribute_count(coord_, "point");
    node_where_ = fmt::format("{}: {}", where_, g.type);
    normal_ = {node_of(g, "normal"), 0, bool_of(g, "normalPerVertex", true),
               ints_of(g, "normalIndex"), "normalIndex"};
    normal_.count = attribute_count(normal_.node, "vector");
    tex_ = {node_of(g, "texCoord"), 0, true, ints_of(g, "texCoordIndex"), "texCoordIndex"};
    tex_.count = attribute_count(tex_.node, "point");
    color_ = {node_of(g, "color"), 0, bool_of(g, "colorPerVertex", true), ints_of(g, "colorIndex"),
              "colorIndex"};
    color_.count = attribute_count(color_.node, "color");
    if (g.type == "ElevationGrid") elevation_grid_nodes();
  }

  /// False (with a warning) if the shape cannot be read as it is.
  bool read(Polygons& out) {
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

  const NodePtr& coord() const { return coord_; }
  const Attribute& normal() const { return normal_; }
  const Attribute& tex() const { return tex_; }
  const Attribute& color() const { return color_; }

 private:
  void read_indexed_face_set(Polygons& out) {
    const std::vector<std::int32_t>* ci = ints_of(g_, "coordIndex");
    if (!ci) return;
    const std::vector<scene::FaceRun> runs =
        scene::face_runs(*ci, coords_, {node_where_, coord_->type});
    for (std::size_t face = 0; face < runs.size(); ++face)
      add_face(out, *ci, face, runs[face].first, runs[face].second);
  }

  // IndexedTriangleSet / IndexedQuadSet (`index`) and TriangleSet (the
  // coordinates in order): attributes are indexed like the coordinates.
  void read_triangle_sets(Polygons& out) {
    const std::size_t per = g_.type == "IndexedQuadSet" ? 4 : 3;
    std::vector<std::int32_t> order;
    if (const auto* index = ints_of(g_, "index")) {
      order = *index;
    } else if (g_.type == "TriangleSet") {
      for (std::size_t i = 0; i < coords_; ++i) order.push_back(std::int32_t(i));
    }
    for (std::size_t f = 0; f + per <= order.size(); f += per)
      add_face(out, order, f / per, f, f + per);
  }

  int int_of(std::string_view field) const {
    const scene::FieldValue* v = g_.value(field);
    return v && !v->ints.empty() ? v->ints[0] : 0;
  }
  float float_of(std::string_view field) const {
    const scene::FieldValue* v = g_.value(field);
    return v && !v->floats.empty() ? v->floats[0] : 1.f;
  }

  // An ElevationGrid's points and its default texture coordinates (s along
  // x, t along z: X3D 13.3.4) as nodes, so its levels are IndexedFaceSets.
  void elevation_grid_nodes() {
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

  // Quads (x, z), (x, z+1), (x+1, z+1), (x+1, z): counter-clockwise seen
  // from +y; attributes per vertex by the vertex number, per face by the quad's.
  void read_elevation_grid(Polygons& out) {
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

  // Face `face`: the corners at [b, e) of the coordinate index `ci`, each
  // with its per-vertex attribute values, and the face's per-face values.
  void add_face(Polygons& out, const std::vector<std::int32_t>& ci, std::size_t face, std::size_t b,
                std::size_t e) {
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

  // The value of attribute `a` at a corner (per_vertex) or a face, by the
  // one face-set rule (scene::corner_attribute); kNone when it is not bound
  // that way or the index is bad (the first bad index is kept in a.error).
  std::uint32_t value(Attribute& a, bool per_vertex, const std::vector<std::int32_t>& ci,
                      std::size_t face, std::size_t pos) {
    if (!a.node || a.per_vertex != per_vertex) return kNone;
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

  // An attribute with a bad index is dropped (browsers generate normals, or
  // draw without texture coordinates or colours).
  void drop_bad(Polygons& out, Attribute& a, std::size_t slot, std::vector<std::uint32_t>* per_face,
                std::string_view what) {
    if (!a.node || a.error.empty()) return;
    log_.warn(LogCategory::kParse, fmt::format("{}; the levels have no {}s", a.error, what));
    a.node = nullptr;
    for (Corner& c : out.corners) c[slot] = kNone;
    if (per_face) std::fill(per_face->begin(), per_face->end(), kNone);
  }

  const Node& g_;
  Log& log_;
  std::string where_, node_where_;
  NodePtr coord_;
  std::size_t coords_ = 0;
  Attribute normal_, tex_, color_;
};

// One distinct shape: its mesh and what its levels are made of.
struct Job {
  NodePtr shape;
  NodePtr geometry;
  double scale = 0;
  std::size_t occurrences = 0;
  TriangleMesh mesh;
  std::vector<Corner> vertex_corner;            ///< #V of mesh
  std::vector<std::uint32_t> triangle_polygon;  ///< #F of mesh
  Polygons polygons;
  NodePtr lod;
};

// The mesh of a shape's polygons: a vertex per distinct corner tuple.
void build_mesh(Job& j, const GeometryReader& reader, const TriangulateOptions& triangulation) {
  const std::vector<float>& points = reader.coord()->value("point")->floats;
  std::unordered_map<Corner, std::uint32_t, CornerHash> vertex_of;
  std::vector<std::uint32_t> corner_vertex;
  scene::FaceTriangulation rule{.triangulation = triangulation,
                                .drop_repeated_vertex_triangles = true,
                                .diagnose_triangles = false};
  rule.triangulation.keep_quads = false;
  const Polygons& p = j.polygons;
  for (std::size_t f = 0; f + 1 < p.start.size(); ++f) {
    corner_vertex.clear();
    for (std::uint32_t k = p.start[f]; k < p.start[f + 1]; ++k) {
      const Corner& c = p.corners[k];
      auto [it, fresh] = vertex_of.try_emplace(c, std::uint32_t(j.mesh.positions.size()));
      if (fresh) {
        j.mesh.positions.push_back({points[3 * c[0]], points[3 * c[0] + 1], points[3 * c[0] + 2]});
        j.vertex_corner.push_back(c);
      }
      corner_vertex.push_back(it->second);
    }
    scene::face_triangles(j.mesh.positions, corner_vertex, rule, j.mesh.triangles);
    j.triangle_polygon.resize(j.mesh.triangles.size(), std::uint32_t(f));
  }
}

// The simplified levels of one shape as Shape nodes sharing one Coordinate.
class LevelBuilder {
 public:
  LevelBuilder(const Job& j, const GeometryReader& reader) : j_(j), reader_(reader) {
    coord_ = scene::make_node("Coordinate");
    coord_->set("point", scene::make_floats(FieldKind::kVec3f, true, {}));
  }

  NodePtr level(const SimplifyResult& r) {
    std::vector<std::int32_t> coord_index, normal_index, tex_index, color_index;
    std::vector<float>& points = coord_->find("point")->value.floats;
    const Attribute& normal = reader_.normal();
    const Attribute& color = reader_.color();
    for (std::size_t t = 0; t < r.mesh.triangles.size(); ++t) {
      const Triangle& tri = r.mesh.triangles[t];
      std::array<std::int32_t, 3> idx{};
      for (int k = 0; k < 3; ++k) idx[k] = position_index(r.mesh.positions[tri[k]], points);
      if (idx[0] == idx[1] || idx[1] == idx[2] || idx[0] == idx[2]) continue;
      for (int k = 0; k < 3; ++k) {
        const Corner& c = j_.vertex_corner[r.vertex_map[tri[k]]];
        coord_index.push_back(idx[k]);
        if (normal.node && normal.per_vertex) normal_index.push_back(std::int32_t(c[1]));
        if (reader_.tex().node) tex_index.push_back(std::int32_t(c[2]));
        if (color.node && color.per_vertex) color_index.push_back(std::int32_t(c[3]));
      }
      const std::uint32_t polygon = j_.triangle_polygon[r.face_map[t]];
      if (normal.node && !normal.per_vertex)
        normal_index.push_back(std::int32_t(j_.polygons.face_normal[polygon]));
      if (color.node && !color.per_vertex)
        color_index.push_back(std::int32_t(j_.polygons.face_color[polygon]));
      coord_index.push_back(-1);
      if (normal.node && normal.per_vertex) normal_index.push_back(-1);
      if (reader_.tex().node) tex_index.push_back(-1);
      if (color.node && color.per_vertex) color_index.push_back(-1);
    }
    auto ifs = scene::make_node("IndexedFaceSet");
    ifs->set("coord", node_value(coord_));
    ifs->set("coordIndex", scene::make_longs(std::move(coord_index)));
    if (normal.node) {
      ifs->set("normal", node_value(normal.node));
      ifs->set("normalIndex", scene::make_longs(std::move(normal_index)));
    }
    if (reader_.tex().node) {
      ifs->set("texCoord", node_value(reader_.tex().node));
      ifs->set("texCoordIndex", scene::make_longs(std::move(tex_index)));
    }
    if (color.node) {
      ifs->set("color", node_value(color.node));
      ifs->set("colorIndex", scene::make_longs(std::move(color_index)));
    }
    for (const char* f : {"ccw", "solid", "colorPerVertex", "normalPerVertex", "creaseAngle"})
      if (const scene::FieldValue* v = j_.geometry->value(f)) ifs->set(f, *v);
    auto shape = scene::make_node("Shape");
    if (NodePtr app = node_of(*j_.shape, "appearance")) shape->set("appearance", node_value(app));
    shape->set("geometry", node_value(ifs));
    return shape;
  }

  static scene::FieldValue node_value(NodePtr n) {
    scene::FieldValue v;
    v.type = {FieldKind::kNode, false};
    v.nodes.push_back(std::move(n));
    return v;
  }

 private:
  std::int32_t position_index(const Vec3& p, std::vector<float>& points) {
    std::array<std::uint32_t, 3> bits{};
    std::memcpy(bits.data(), &p.x, sizeof(float));
    std::memcpy(bits.data() + 1, &p.y, sizeof(float));
    std::memcpy(bits.data() + 2, &p.z, sizeof(float));
    const Corner key{bits[0], bits[1], bits[2], 0};
    auto [it, fresh] = index_.try_emplace(key, std::int32_t(points.size() / 3));
    if (fresh) points.insert(points.end(), {p.x, p.y, p.z});
    return it->second;
  }

  const Job& j_;
  const GeometryReader& reader_;
  NodePtr coord_;
  std::unordered_map<Corner, std::int32_t, CornerHash> index_;
};

class Pipeline {
 public:
  Pipeline(const LodOptions& options, LodResult& result) : opt_(options), result_(result) {}

  void run(scene::Scene& s) {
    x3d_ = s.header.starts_with("#X3D");
    camera_angle_ = opt_.range.camera_angle;
    for (const auto& r : s.roots) collect(r, 1.0, "children");
    if (!opt_.camera_angle_given && found_viewpoint_) camera_angle_ = viewpoint_angle_;
    result_.camera_angle = camera_angle_;
    for (Job& j : jobs_) make_lod(j);
    std::unordered_map<const Node*, NodePtr> lods;
    for (const Job& j : jobs_)
      if (j.lod) lods[j.shape.get()] = j.lod;
    std::unordered_set<const Node*> done;
    for (auto& r : s.roots) {
      if (auto it = lods.find(r.get()); it != lods.end()) r = it->second;
      replace(r, lods, done);
    }
  }

 private:
  // `via`: the name of the field that holds `n`. Only a Shape that is a child
  // (of a grouping node, a LOD or a Switch) can be replaced by a LOD.
  void collect(const NodePtr& n, double scale, std::string_view via) {
    if (!n || n->statement) return;
    if (n->type == "Viewpoint" && !found_viewpoint_) {
      found_viewpoint_ = true;
      const scene::FieldValue* fov = n->value("fieldOfView");
      viewpoint_angle_ = fov && !fov->floats.empty() && fov->floats[0] > 0 && fov->floats[0] < 3.1
                             ? fov->floats[0]
                             : kDefaultFieldOfView;
    }
    if (n->type == "Shape") {
      NodePtr g = node_of(*n, "geometry");
      if (!g || !is_supported_geometry(g->type)) return;
      if (!is_child_list(via)) {
        if (via == "skin" || via == "shapes")
          result_.log.warn(
              LogCategory::kGeneral,
              fmt::format("line {}: a skinned Shape (HAnim skin, Castle Skin) is left at full "
                          "detail: simplifying it needs its joint weights",
                          n->first_line));
        return;
      }
      auto [it, fresh] = job_of_.try_emplace(n.get(), jobs_.size());
      if (fresh) jobs_.push_back({.shape = n, .geometry = g});
      Job& j = jobs_[it->second];
      j.scale = std::max(j.scale, scale);
      ++j.occurrences;
      return;
    }
    if (n->type == "Transform")
      if (const scene::FieldValue* sc = n->value("scale"); sc && sc->floats.size() == 3)
        scale *= std::max(
            {std::fabs(sc->floats[0]), std::fabs(sc->floats[1]), std::fabs(sc->floats[2])});
    // A subgraph met again at no larger scale adds nothing new.
    auto [seen, fresh] = seen_scale_.try_emplace(n.get(), scale);
    if (!fresh && seen->second >= scale) return;
    seen->second = std::max(seen->second, scale);
    for (const auto& f : n->fields)
      for (const auto& c : f.value.nodes) collect(c, scale, f.name);
  }

  void make_lod(Job& j) {
    const std::string where = fmt::format("line {}", j.shape->first_line);
    GeometryReader reader(*j.geometry, result_.log, where);
    if (!reader.read(j.polygons)) return;
    build_mesh(j, reader, opt_.triangulation);
    if (j.mesh.triangles.empty()) return;
    Box3 box = j.mesh.bounds();
    const Vec3 center = (box.lo + box.hi) * 0.5f;
    double radius = 0;
    for (const Vec3& p : j.mesh.positions) radius = std::max(radius, double(length(p - center)));
    ShapeStatistics stats{.type = j.geometry->type,
                          .name = j.shape->name,
                          .line = j.shape->first_line,
                          .occurrences = j.occurrences,
                          .radius = radius,
                          .scale = j.scale};
    stats.levels.push_back({j.mesh.triangle_count(), j.mesh.vertex_count(), 0});
    ChooseLevelsOptions c{.method = opt_.method,
                          .min_diff = opt_.min_diff,
                          .spacing = {.spacing = opt_.level_spacing, .max_ratio = opt_.level_ratio},
                          .range = opt_.range,
                          .max_simplified = opt_.max_levels > 2 ? opt_.max_levels - 2 : 0,
                          .measure_samples = opt_.measure_samples,
                          .threads = opt_.threads};
    c.range.camera_angle = float(camera_angle_);
    ChosenLevels chosen = choose_levels(j.mesh, radius, c);
    stats.method = chosen.method;
    stats.stop_reason = chosen.stop_reason;
    LevelBuilder builder(j, reader);
    scene::FieldValue levels;
    levels.type = {FieldKind::kNode, true};
    levels.nodes.push_back(j.shape);
    std::vector<double> errors;
    for (const ChosenLevel& l : chosen.levels) {
      const SimplifyResult& r = l.measured.level;
      levels.nodes.push_back(builder.level(r));
      errors.push_back(l.switch_error);
      stats.levels.push_back({r.mesh.triangle_count(), r.mesh.vertex_count(), l.measured.error});
    }
    levels.nodes.push_back(scene::make_node("Group"));
    errors.push_back(vanishing_error(radius));
    stats.levels.push_back({0, 0, vanishing_error(radius)});
    RangeOptions range = opt_.range;
    range.camera_angle = float(camera_angle_);
    stats.ranges = switching_ranges(errors, std::max(j.scale, 1e-12), radius, range);
    j.lod = scene::make_node("LOD");
    j.lod->set("range", scene::make_floats(FieldKind::kFloat, true, stats.ranges));
    j.lod->set("center",
               scene::make_floats(FieldKind::kVec3f, false, {center.x, center.y, center.z}));
    j.lod->set(x3d_ ? "children" : "level", std::move(levels));
    result_.shapes.push_back(std::move(stats));
  }

  // Puts each shape's LOD where the shape was a child (children, level,
  // choice of grouping nodes).
  void replace(const NodePtr& n, const std::unordered_map<const Node*, NodePtr>& lods,
               std::unordered_set<const Node*>& done) {
    if (!n || !done.insert(n.get()).second) return;
    for (auto& f : n->fields) {
      const bool child_list = f.value.type.kind == FieldKind::kNode && is_child_list(f.name);
      for (auto& c : f.value.nodes) {
        if (!c) continue;
        auto it = child_list ? lods.find(c.get()) : lods.end();
        if (it != lods.end() && it->second != n) {
          c = it->second;
          continue;
        }
        replace(c, lods, done);
      }
    }
  }

  const LodOptions& opt_;
  LodResult& result_;
  bool x3d_ = false;
  double camera_angle_ = kDefaultFieldOfView;
  bool found_viewpoint_ = false;
  double viewpoint_angle_ = kDefaultFieldOfView;
  std::vector<Job> jobs_;
  std::unordered_map<const Node*, std::size_t> job_of_;
  std::unordered_map<const Node*, double> seen_scale_;
};

}  // namespace

LodResult generate_lod_vrml97(scene::Scene scene, const LodOptions& options) {
  LodResult result;
  Pipeline(options, result).run(scene);
  result.scene = std::move(scene);
  return result;
}

}  // namespace lodforge
