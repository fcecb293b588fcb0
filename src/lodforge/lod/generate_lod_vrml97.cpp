// The LOD pipeline for VRML97 / X3D scenes. The shapes' polygons become one
// mesh per shape whose vertices are the distinct (coordinate, normal,
// texture coordinate, colour) index tuples of their corners, so every
// attribute follows a simplified vertex through the simplifier's vertex map
// back into the input's own attribute nodes; only positions, which a
// simplifier moves, get a new Coordinate node (shared by all levels of a
// shape, each distinct position once).
#include "lodforge/lod/generate_lod_vrml97.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <array>
#include <cmath>
#include <cstring>
#include <memory>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include "lodforge/core/error.h"
#include "lodforge/core/math.h"
#include "lodforge/lod/choose_levels.h"
#include "lodforge/lod/flatten_vrml97.h"
#include "lodforge/lod/vrml97_geometry.h"
#include "lodforge/scene/face_set_mesh.h"

namespace lodforge {
namespace {

using scene::FieldKind;
using scene::FieldValue;
using scene::Node;
using scene::NodePtr;
using namespace vrml97_geometry;

// One distinct shape: its mesh and what its levels are made of.
struct Job {
  NodePtr shape;
  NodePtr geometry;
  double scale = 0;
  std::size_t occurrences = 0;
  ShapeMesh shape_mesh;
  Polygons polygons;
  std::unique_ptr<GeometryReader> reader;  ///< set when the shape was read
  Vec3 center;
  double radius = 0;
  NodePtr lod;
  Log log;                               ///< the shape's messages, merged in order
  std::optional<ShapeStatistics> stats;  ///< set when it got levels
};

// `shape` (build_mesh's) with each vertex's texture coordinate and colour
// (per-vertex ones: a vertex is one corner tuple), as gltf_lod gives a
// primitive's: the simplifier then keeps the seams where they differ between
// coincident vertices (texture islands, colour borders), and each level
// vertex's source corner lies on its triangle's side of them. Normals are not
// given: a flat-shaded shape splits every vertex by them.
void add_seam_attributes(const GeometryReader& reader, ShapeMesh& shape) {
  const std::size_t n = shape.mesh.positions.size();
  const NodePtr list =
      reader.tex().generated ? nullptr : first_texture_coordinates(reader.tex().node);
  const FieldValue* uv = list ? list->value("point") : nullptr;
  const Attribute& color = reader.color();
  const FieldValue* rgb = color.node && color.per_vertex ? color.node->value("color") : nullptr;
  const std::size_t stride = color.node && color.node->type == "ColorRGBA" ? 4 : 3;
  for (std::size_t v = 0; v < n && (uv || rgb); ++v) {
    const Corner& c = shape.vertex_corner[v];
    if (uv) {
      const std::size_t at = 2 * std::size_t(c[2]);
      shape.mesh.texcoords.push_back(c[2] != kNone && at + 1 < uv->floats.size()
                                         ? Vec2{uv->floats[at], uv->floats[at + 1]}
                                         : Vec2{});
    }
    if (rgb) {
      const std::size_t at = stride * std::size_t(c[3]);
      shape.mesh.colors.push_back(
          c[3] != kNone && at + 2 < rgb->floats.size()
              ? Vec3{rgb->floats[at], rgb->floats[at + 1], rgb->floats[at + 2]}
              : Vec3{});
    }
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
    const bool indexed_tex = reader_.tex().node && !reader_.tex().generated;
    for (std::size_t t = 0; t < r.mesh.triangles.size(); ++t) {
      const Triangle& tri = r.mesh.triangles[t];
      std::array<std::int32_t, 3> idx{};
      for (int k = 0; k < 3; ++k) idx[k] = position_index(r.mesh.positions[tri[k]], points);
      if (idx[0] == idx[1] || idx[1] == idx[2] || idx[0] == idx[2]) continue;
      for (int k = 0; k < 3; ++k) {
        const Corner& c = j_.shape_mesh.vertex_corner[r.vertex_map[tri[k]]];
        coord_index.push_back(idx[k]);
        if (normal.node && normal.per_vertex) normal_index.push_back(std::int32_t(c[1]));
        if (indexed_tex) tex_index.push_back(std::int32_t(c[2]));
        if (color.node && color.per_vertex) color_index.push_back(std::int32_t(c[3]));
      }
      const std::uint32_t polygon = j_.shape_mesh.triangle_polygon[r.face_map[t]];
      if (normal.node && !normal.per_vertex)
        normal_index.push_back(std::int32_t(j_.polygons.face_normal[polygon]));
      if (color.node && !color.per_vertex)
        color_index.push_back(std::int32_t(j_.polygons.face_color[polygon]));
      coord_index.push_back(-1);
      if (normal.node && normal.per_vertex) normal_index.push_back(-1);
      if (indexed_tex) tex_index.push_back(-1);
      if (color.node && color.per_vertex) color_index.push_back(-1);
    }
    auto ifs = scene::make_node("IndexedFaceSet");
    ifs->set("coord", scene::make_node_value(coord_));
    ifs->set("coordIndex", scene::make_longs(std::move(coord_index)));
    if (normal.node) {
      ifs->set("normal", scene::make_node_value(normal.node));
      ifs->set("normalIndex", scene::make_longs(std::move(normal_index)));
    }
    if (reader_.tex().node) {
      ifs->set("texCoord", scene::make_node_value(reader_.tex().node));
      if (indexed_tex) ifs->set("texCoordIndex", scene::make_longs(std::move(tex_index)));
    }
    if (color.node) {
      ifs->set("color", scene::make_node_value(color.node));
      ifs->set("colorIndex", scene::make_longs(std::move(color_index)));
    }
    for (const char* f : {"ccw", "solid", "colorPerVertex", "normalPerVertex", "creaseAngle"})
      if (const scene::FieldValue* v = j_.geometry->value(f)) ifs->set(f, *v);
    auto shape = scene::make_node("Shape");
    if (NodePtr app = node_of(*j_.shape, "appearance"))
      shape->set("appearance", scene::make_node_value(app));
    shape->set("geometry", scene::make_node_value(ifs));
    return shape;
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
    if (const auto fov = viewpoint_field_of_view(s); fov && !opt_.camera_angle_given)
      camera_angle_ = *fov;
    result_.camera_angle = camera_angle_;
    // Shapes in parallel (nested loops of the simplifiers and the
    // measurement too), within an arena of the requested size; messages and
    // statistics in the scene's order, so the result is the same for any
    // number of threads. Every shape is read before any is simplified:
    // --differentiate-by-size needs the largest.
    tbb::task_arena arena(opt_.threads > 0 ? opt_.threads : tbb::task_arena::automatic);
    arena.execute([&] {
      tbb::parallel_for(std::size_t(0), jobs_.size(), [&](std::size_t i) { read(jobs_[i]); });
      for (const Job& j : jobs_)
        if (j.reader) largest_radius_ = std::max(largest_radius_, j.radius * j.scale);
      tbb::parallel_for(std::size_t(0), jobs_.size(), [&](std::size_t i) {
        if (jobs_[i].reader) make_lod(jobs_[i]);
        // The level nodes are made: the working geometry is not needed.
        jobs_[i].shape_mesh = {};
        jobs_[i].polygons = {};
        jobs_[i].reader.reset();
      });
    });
    for (Job& j : jobs_) {
      result_.log.merge(j.log);
      if (j.stats) result_.shapes.push_back(std::move(*j.stats));
    }
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

  // The settings of manual mode for this pipeline's shapes (all polygons),
  // or none.
  const ShapeTypeSettings* manual() const {
    const auto it = opt_.manual.find("polygon");
    return it == opt_.manual.end() ? nullptr : &it->second;
  }

  ChooseLevelsOptions choose_options() const {
    ChooseLevelsOptions c{.method = opt_.method,
                          .min_diff = opt_.min_diff,
                          .spacing = {.spacing = opt_.level_spacing, .max_ratio = opt_.level_ratio},
                          .range = opt_.range,
                          .max_simplified = opt_.max_levels > 2 ? opt_.max_levels - 2 : 0,
                          .measure_samples = opt_.measure_samples,
                          .threads = opt_.threads};
    c.range.camera_angle = float(camera_angle_);
    return c;
  }

  // The shape's mesh and bounding sphere; j.reader stays unset when it
  // cannot be read or has no triangles.
  void read(Job& j) {
    const std::string where = fmt::format("line {}", j.shape->first_line);
    auto reader = std::make_unique<GeometryReader>(*j.geometry, j.log, where);
    if (!reader->read(j.polygons)) return;
    build_mesh(j.polygons, *reader, opt_.triangulation, j.shape_mesh);
    if (j.shape_mesh.mesh.triangles.empty()) return;
    add_seam_attributes(*reader, j.shape_mesh);
    const Box3 box = j.shape_mesh.mesh.bounds();
    j.center = (box.lo + box.hi) * 0.5f;
    for (const Vec3& p : j.shape_mesh.mesh.positions)
      j.radius = std::max(j.radius, double(length(p - j.center)));
    j.reader = std::move(reader);
  }

  void make_lod(Job& j) {
    // The shape as it is: --extract 0 (level 0) or -1 (the scene cleaned),
    // --quality polygon=1 (no LOD).
    int quality = manual() ? manual()->quality : -1;
    if (opt_.differentiate_by_size)
      quality = sized_quality(quality, j.radius, j.scale, largest_radius_);
    if ((opt_.extract && *opt_.extract <= 0) || quality == 1) return;
    if (quality == 0) {  // --quality polygon=0: an empty node in its place
      j.lod = scene::make_node("Group");
      return;
    }
    const GeometryReader& reader = *j.reader;
    const Vec3 center = j.center;
    const double radius = j.radius;
    ShapeStatistics stats{.type = j.geometry->type,
                          .name = j.shape->name,
                          .line = j.shape->first_line,
                          .occurrences = j.occurrences,
                          .radius = radius,
                          .scale = j.scale};
    stats.levels.push_back(
        {j.shape_mesh.mesh.triangle_count(), j.shape_mesh.mesh.vertex_count(), 0});
    ChooseLevelsOptions options = choose_options();
    options.quality = quality;
    ChosenLevels chosen = choose_levels(j.shape_mesh.mesh, radius, options);
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
    stats.ranges = switching_ranges(errors, std::max(j.scale, 1e-12), radius, options.range);
    if (manual()) apply_given_ranges(stats.ranges, manual()->ranges);
    // --extract K: level K alone in the shape's place (beyond the last
    // simplified level, the empty one).
    if (opt_.extract) {
      j.lod = levels.nodes[std::min(std::size_t(*opt_.extract), levels.nodes.size() - 1)];
      stats.ranges.clear();  // no LOD node
    } else {
      j.lod = lod_node(stats.ranges, center, std::move(levels));
    }
    j.stats = std::move(stats);
  }

  NodePtr lod_node(const std::vector<float>& ranges, const Vec3& center,
                   scene::FieldValue levels) const {
    NodePtr lod = scene::make_node("LOD");
    lod->set("range", scene::make_floats(FieldKind::kFloat, true, ranges));
    lod->set("center",
             scene::make_floats(FieldKind::kVec3f, false, {center.x, center.y, center.z}));
    lod->set(x3d_ ? "children" : "level", std::move(levels));
    return lod;
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
  double largest_radius_ = 0;  ///< of the shapes read, radius x scale
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
