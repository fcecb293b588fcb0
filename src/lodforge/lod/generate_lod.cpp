// The LODCreator pipeline (original thesis §4, Figure 4.1):
//  1. copy the scene (sharing kept), find the camera height angle;
//  2. copy each shared group for every further property context it is used
//     in (unshare_contexts.h); traverse the scene and collect every shape
//     occurrence with its state; group occurrences into jobs (same shape node
//     under the same property nodes);
//  3. per job, in parallel: read the geometry (bindings converted, attributes
//     de-duplicated), make the levels, measure each level's error;
//  4. per occurrence: switching ranges from the errors and the occurrence's
//     transform scale, and the LOD subtree in place of the shape.
#include "lodforge/lod/generate_lod.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <set>
#include <unordered_map>

#include "lodforge/core/error.h"
#include "lodforge/lod/choose_levels.h"
#include "lodforge/lod/join_nodes.h"
#include "lodforge/lod/measure_deviation.h"
#include "lodforge/lod/shape_geometry.h"
#include "lodforge/lod/unshare_contexts.h"
#include "lodforge/metrics/compare_meshes.h"
#include "lodforge/scene/inventor_shapes.h"
#include "lodforge/scene/schema.h"
#include "lodforge/scene/shape_mesh.h"
#include "lodforge/scene/tessellate_primitive.h"
#include "lodforge/scene/traverse.h"

namespace lodforge {
namespace {

using scene::FieldKind;
using scene::make_node;
using scene::Node;
using scene::NodePtr;

// A shape whose levels are made by a simplifier: VRML 1.0's indexed sets and
// Inventor's vertex shapes (read as their indexed equivalent).
bool is_set_shape(const std::string& t) {
  return t == "IndexedFaceSet" || t == "IndexedLineSet" || scene::has_indexed_equivalent(t);
}

bool is_line_shape(const std::string& t) {
  return t == "IndexedLineSet" || t == "LineSet";
}

std::string type_key(const std::string& node_type) {
  if (is_set_shape(node_type)) return is_line_shape(node_type) ? "line" : "polygon";
  std::string k = node_type;
  for (char& ch : k) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  return k;
}

bool is_lod_shape(const std::string& t) {
  return is_set_shape(t) || t == "Cube" || t == "Sphere" || t == "Cone" || t == "Cylinder";
}

// A shape node and the property nodes its geometry depends on.
struct JobKey {
  const Node* shape;
  PropertyContext context;
  auto operator<=>(const JobKey&) const = default;
};

struct Occurrence {
  Node* parent;  // nullptr: a root
  std::size_t index;
  std::size_t job;
  double scale;
  Mat4 transform;
  std::vector<float> ranges;  // of the LOD node written here (empty: none)
};

struct Job {
  const Node* shape = nullptr;
  scene::TraversalState state;
  // Results.
  std::vector<NodePtr> level_nodes;  // level 0 .. last simplified level (no empty level)
  std::vector<double> errors;        // per level (0 for level 0)
  std::vector<float> ranges_override;
  ShapeGeometry geometry;
  std::unique_ptr<LevelWriter> writer;  // the levels' shared vertex data
  Vec3 center;
  double radius = 0;
  int segments = 24;    // primitives: level 0's tessellation (the state's Complexity)
  bool remove = false;  // quality 0
  bool keep = false;    // nothing to simplify: the shape stays as it is
  bool no_lod = false;  // quality 1
  ShapeStatistics stats;
  Log log;
};

double max_scale_of(const Mat4& m) {
  double s = m.max_scale();
  return s > 0 && std::isfinite(s) ? s : 1.0;
}

// Bounding sphere about the box centre.
void bounding_sphere(const std::vector<Vec3>& pts, Vec3& center, double& radius) {
  const BoxSphere s = box_centred_sphere(pts);
  center = s.center;
  radius = s.radius;
}

ShapeGeometry primitive_geometry(const TriangleMesh& tess, bool textured) {
  ShapeGeometry g;
  g.mesh.positions = tess.positions;
  g.mesh.triangles = tess.triangles;
  g.normal_binding = AttributeBinding::kPerVertex;
  g.normal_values = tess.normals;
  g.vertex_normal.resize(tess.positions.size());
  g.vertex_texcoord.resize(tess.positions.size());
  for (std::uint32_t i = 0; i < tess.positions.size(); ++i)
    g.vertex_normal[i] = g.vertex_texcoord[i] = i;
  g.has_texcoords = textured && !tess.texcoords.empty();
  g.texcoord_values = tess.texcoords;
  g.triangle_polygon.resize(tess.triangles.size());
  for (std::uint32_t i = 0; i < tess.triangles.size(); ++i) g.triangle_polygon[i] = i;
  g.polygon_is_quad.assign(tess.triangles.size(), false);
  return g;
}

class Pipeline {
 public:
  Pipeline(const scene::Scene& input, const LodOptions& options) : opt_(options) {
    std::unordered_map<const Node*, NodePtr> done;
    set_header(input.header);
    for (const auto& r : input.roots) result_.scene.roots.push_back(scene::copy_subtree(r, done));
  }
  Pipeline(scene::Scene&& input, const LodOptions& options) : opt_(options) {
    set_header(input.header);
    result_.scene.roots = std::move(input.roots);
  }

  // The output is in the input's language: an Inventor scene keeps its
  // Inventor nodes, so it is written as Inventor 2.1 (whose LOD node has the
  // fields of VRML 1.0's).
  void set_header(const std::string& input_header) {
    result_.scene.header =
        scene::is_inventor_header(input_header) ? "#Inventor V2.1 ascii" : "#VRML V1.0 ascii";
  }

  LodResult run() {
    if (opt_.join) {
      JoinStatistics js =
          join_nodes(result_.scene, {.max_faces = opt_.join_max_faces}, result_.log);
      result_.joined = js.joined;
    }
    unshare_property_contexts(result_.scene,
                              [](const Node& shape) { return is_lod_shape(shape.type); });
    collect();
    size_scale();
    start_progress();
    // An arena of the requested size bounds this call's parallelism (nested
    // parallel loops of the simplifiers and the measurement run in it too)
    // without touching the process's other work.
    tbb::task_arena arena(opt_.threads > 0 ? opt_.threads : tbb::task_arena::automatic);
    arena.execute([&] {
      tbb::parallel_for(std::size_t(0), jobs_.size(), [&](std::size_t i) {
        make_levels(jobs_[i]);
        // The level nodes are made: the shape's working copy of its geometry
        // is not needed any more, and memory stays bounded by the output.
        jobs_[i].writer.reset();
        jobs_[i].geometry = {};
        credit(i, 1.0);
      });
    });
    for (auto& j : jobs_) result_.log.merge(j.log);
    replace();
    statistics();
    return std::move(result_);
  }

 private:
  void collect() {
    std::map<JobKey, std::size_t> job_of;
    std::map<std::pair<Node*, std::size_t>, std::size_t> occurrence_of;
    const Node* camera = nullptr;
    scene::traverse(result_.scene, [&](const scene::ShapeVisit& v) {
      if (!camera && v.camera) camera = v.camera;
      if (!is_lod_shape(v.shape.type)) return;
      const JobKey key{&v.shape, PropertyContext::of(v.state)};
      auto [jit, fresh] = job_of.try_emplace(key, jobs_.size());
      if (fresh) {
        jobs_.emplace_back();
        jobs_.back().shape = &v.shape;
        jobs_.back().state = v.state;
      }
      Node* parent = v.path.empty() ? nullptr : const_cast<Node*>(v.path.back());
      double scale = max_scale_of(v.state.transform);
      auto [oit, new_place] =
          occurrence_of.try_emplace({parent, v.child_index}, occurrences_.size());
      instances_.push_back(oit->second);
      if (new_place) {
        occurrences_.push_back({parent, v.child_index, jit->second, scale, v.state.transform, {}});
      } else {
        // The same place reached again (its group is USEd elsewhere): one
        // subtree serves all, so it takes the largest scale (the farthest ranges).
        Occurrence& o = occurrences_[oit->second];
        o.scale = std::max(o.scale, scale);
        if (o.job != jit->second)
          result_.log.warn(LogCategory::kGeneral,
                           fmt::format("line {}: {} is used under different properties in a "
                                       "shared group; its LOD is made for the first use",
                                       v.shape.first_line, v.shape.type));
      }
    });
    camera_angle_ = opt_.range.camera_angle;
    if (!opt_.camera_angle_given && camera) {
      const scene::FieldValue* h = scene::field_or_default(*camera, "heightAngle");
      if (h && !h->floats.empty() && h->floats[0] > 0 && h->floats[0] < 3.14159f)
        camera_angle_ = h->floats[0];
    }
    result_.camera_angle = camera_angle_;
  }

  // Progress in units of work: a job weighs about its input's face indices
  // (coordIndex; a vertex shape's coordinates; a primitive's tessellation),
  // plus one so that every job counts.
  std::uint64_t work_of(const Job& j) const {
    if (const scene::FieldValue* v = j.shape->value("coordIndex")) return 1 + v->ints.size();
    if (is_set_shape(j.shape->type) && j.state.coordinate3)
      if (const scene::FieldValue* p = j.state.coordinate3->value("point"))
        return 1 + p->floats.size();
    return 1000;
  }

  void start_progress() {
    if (!opt_.progress) return;
    credited_ = std::vector<std::atomic<std::uint64_t>>(jobs_.size());
    work_.resize(jobs_.size());
    for (std::size_t i = 0; i < jobs_.size(); ++i) work_[i] = work_of(jobs_[i]);
    total_work_ = 0;
    for (auto w : work_) total_work_ += w;
    opt_.progress("shapes", 0, total_work_);
  }

  // Job i is `fraction` done (its calls may come from several threads and
  // out of order: only an increase is credited).
  void credit(std::size_t i, double fraction) {
    if (!opt_.progress) return;
    const auto target = static_cast<std::uint64_t>(fraction * double(work_[i]));
    std::uint64_t seen = credited_[i].load();
    while (target > seen && !credited_[i].compare_exchange_weak(seen, target)) {
    }
    if (target <= seen) return;
    const std::uint64_t done = done_work_ += target - seen;
    opt_.progress("shapes", done, total_work_);
  }

  // Radii (for differentiate-by-size) need the geometry: primitives' from
  // their fields, sets' from their coordinates; computed up front.
  void size_scale() {
    for (const auto& o : occurrences_)
      jobs_[o.job].stats.scale = std::max(jobs_[o.job].stats.scale, o.scale);
    if (!opt_.differentiate_by_size) return;
    for (auto& o : occurrences_) {
      Job& j = jobs_[o.job];
      scene::ShapeVisit v{*j.shape, j.state, nullptr, empty_path_, 0};
      Log ignore;
      try {
        TriangleMesh m = scene::shape_mesh(v, {.world_space = false});
        Vec3 c;
        double r;
        bounding_sphere(m.positions, c, r);
        largest_radius_ = std::max(largest_radius_, r * o.scale);
      } catch (const DataError&) {
      }
    }
  }

  int quality_for(const Job& j, double radius, double scale) const {
    auto it = opt_.manual.find(type_key(j.shape->type));
    if (it == opt_.manual.end() || it->second.quality < 0) return -1;
    const int q = it->second.quality;
    return opt_.differentiate_by_size ? sized_quality(q, radius, scale, largest_radius_) : q;
  }

  void make_levels(Job& j) {
    const std::string& t = j.shape->type;
    j.stats.type = t;
    j.stats.name = j.shape->name;
    j.stats.line = j.shape->first_line;
    scene::ShapeVisit visit{*j.shape, j.state, nullptr, empty_path_, 0};
    const double scale = j.stats.scale;
    if (is_set_shape(t)) {
      j.geometry = read_shape_geometry(visit, {.triangulation = opt_.triangulation}, j.log);
      bounding_sphere(j.geometry.mesh.positions, j.center, j.radius);
      if (j.geometry.mesh.triangles.empty() && j.geometry.mesh.lines.empty()) {
        j.log.warn(LogCategory::kFace,
                   fmt::format("line {}: {} has no {}; kept as it is", j.shape->first_line, t,
                               t == "IndexedFaceSet" ? "faces" : "lines"));
        j.keep = true;
        j.stats.method = "none";
        return;
      }
    } else {
      TriangleMesh tess = scene::tessellate_primitive(*j.shape, {.segments = 32});
      bounding_sphere(tess.positions, j.center, j.radius);
      j.segments = scene::segments_for_complexity(scene::complexity_value(j.state));
    }
    if (opt_.export_flavour == ExportFlavour::kReducer)
      for (auto& p : j.geometry.mesh.positions) p -= j.center;
    int quality = quality_for(j, j.radius, scale);
    if (quality == 0) {
      j.remove = true;
      j.stats.method = "removed (quality 0)";
      return;
    }
    j.no_lod = quality == 1 || (opt_.extract && *opt_.extract <= 0);
    std::size_t max_levels = opt_.max_levels;
    if (quality >= 2) max_levels = std::size_t(quality);
    // Level 0: the input node itself, drawn under the state it was read in
    // (nothing is placed between it and that state), so it draws exactly what
    // the input draws. Rebuilt from the geometry only where the input cannot
    // be kept: an attribute index out of range (dropped), coordinates moved
    // to the origin (reducer flavour), or clean-and-reformat (--extract -1).
    if (is_set_shape(t)) {
      j.writer = std::make_unique<LevelWriter>(j.geometry, j.state, opt_.no_lines);
      const bool rebuild = j.geometry.repaired || opt_.export_flavour == ExportFlavour::kReducer ||
                           (opt_.extract && *opt_.extract < 0);
      if (rebuild) {
        j.level_nodes.push_back(j.writer->level(j.geometry.mesh, {}, {}));
      } else {
        auto original = std::make_shared<Node>(*j.shape);
        original->name.clear();
        j.level_nodes.push_back(original);
      }
      j.errors.push_back(0);
      j.stats.levels.push_back(
          {j.geometry.mesh.triangle_count(), j.geometry.mesh.vertex_count(), 0});
    } else {
      auto original = std::make_shared<Node>(*j.shape);
      original->name.clear();
      j.level_nodes.push_back(original);
      j.errors.push_back(0);
      // Level 0 draws the tessellation the input draws: under its Complexity.
      TriangleMesh tess = scene::tessellate_primitive(*j.shape, {.segments = j.segments});
      j.stats.levels.push_back({tess.triangle_count(), tess.vertex_count(), 0});
    }
    if (j.no_lod || (max_levels && max_levels <= 2)) {
      j.stats.method = j.no_lod ? "none" : to_string(opt_.method);
      return;
    }
    std::size_t simplified_max = max_levels ? max_levels - 2 : 0;
    if (is_set_shape(t)) {
      set_levels(j, simplified_max, quality);
    } else if (t != "Cube") {
      primitive_levels(j, simplified_max);
    } else {
      j.stats.method = "none";
    }
  }

  void set_levels(Job& j, std::size_t simplified_max, int quality) {
    ChooseLevelsOptions c{.method = opt_.method,
                          .min_diff = opt_.min_diff,
                          .spacing = {.spacing = opt_.level_spacing, .max_ratio = opt_.level_ratio},
                          .range = opt_.range,
                          .max_simplified = simplified_max,
                          .quality = quality,
                          .measure_samples = opt_.measure_samples,
                          .threads = opt_.threads};
    c.range.camera_angle = float(camera_angle_);
    // A fifth of the job's work when its chain is made, the rest as its
    // levels are measured (where the pipeline's time goes).
    const std::size_t job = static_cast<std::size_t>(&j - jobs_.data());
    if (opt_.progress)
      c.progress = [&, job](std::string_view, std::uint64_t done, std::uint64_t total) {
        credit(job, 0.2 + 0.8 * double(done) / double(std::max<std::uint64_t>(total, 1)));
      };
    ChosenLevels chosen = choose_levels(j.geometry.mesh, j.radius, c);
    j.stats.method = chosen.method;
    j.stats.stop_reason = chosen.stop_reason;
    for (const ChosenLevel& l : chosen.levels) {
      const SimplifyResult& r = l.measured.level;
      j.level_nodes.push_back(j.writer->level(r.mesh, r.vertex_map, r.face_map));
      j.errors.push_back(l.switch_error);
      j.stats.levels.push_back({r.mesh.triangle_count(), r.mesh.vertex_count(), l.measured.error});
    }
  }

  // The measured deviation of a primitive's tessellation at `segments` from
  // a fine one (64 segments, the smooth surface for all practical purposes).
  // Scenes repeat the same primitives many times: results are cached by the
  // primitive's fields.
  double tessellation_error(const Node& shape, int segments) {
    std::string key = fmt::format("{}/{}", shape.type, segments);
    for (const char* f : {"radius", "bottomRadius", "height", "parts"}) {
      const scene::FieldValue* v = scene::field_or_default(shape, f);
      if (!v) continue;
      for (float x : v->floats) key += fmt::format("/{}", x);
      for (const auto& x : v->strings) key += "/" + x;
    }
    {
      std::lock_guard<std::mutex> lock(cache_mutex_);
      auto it = tessellation_errors_.find(key);
      if (it != tessellation_errors_.end()) return it->second;
    }
    TriangleMesh reference =
        scene::tessellate_primitive(shape, {.segments = std::max(64, 2 * segments)});
    TriangleMesh tess = scene::tessellate_primitive(shape, {.segments = segments});
    const double h =
        DeviationMeter(reference, {.samples = opt_.measure_samples ? opt_.measure_samples : 20000})
            .hausdorff(tess);
    std::lock_guard<std::mutex> lock(cache_mutex_);
    tessellation_errors_[key] = h;
    return h;
  }

  // A simplified level of a Sphere, Cone or Cylinder: the tessellation of the
  // unit primitive of its kind (radius 1, height 2, the node's parts), shared
  // by every primitive drawn under the same kind of attribute state, under a
  // Scale to the node's size. A scene of many spheres holds one set of
  // sphere levels. (Texture coordinates of the primitives do not depend on
  // their size; normals follow the Scale as every browser transforms them.)
  NodePtr primitive_level(const Job& j, int segments) {
    auto size = [&](const char* field) {
      const scene::FieldValue* v = scene::field_or_default(*j.shape, field);
      return v && !v->floats.empty() ? std::abs(v->floats[0]) : 1.0f;
    };
    const std::string& t = j.shape->type;
    const Vec3 scale = t == "Sphere" ? Vec3{size("radius"), size("radius"), size("radius")}
                       : t == "Cone"
                           ? Vec3{size("bottomRadius"), size("height") / 2, size("bottomRadius")}
                           : Vec3{size("radius"), size("height") / 2, size("radius")};
    const bool scalable =
        scale.x > 0 && scale.y > 0 && std::isfinite(scale.x) && std::isfinite(scale.y);
    Node unit{.type = t};
    if (const scene::FieldValue* parts = j.shape->value("parts")) unit.set("parts", *parts);
    const Node& source = scalable ? unit : *j.shape;
    ShapeGeometry g =
        primitive_geometry(scene::tessellate_primitive(source, {.segments = segments}), true);
    mark_inherited_attributes(g, j.state);
    if (!scalable) return LevelWriter(g, j.state, true).level(g.mesh, {}, {});
    std::string key = fmt::format("{}/{}/{}{}{}", t, segments, int(g.override_normals),
                                  int(g.override_texcoords), int(g.override_material_binding));
    if (const scene::FieldValue* parts = j.shape->value("parts"))
      for (const auto& p : parts->strings) key += "/" + p;
    NodePtr shared;
    {
      std::lock_guard<std::mutex> lock(cache_mutex_);
      NodePtr& cached = unit_levels_[key];
      if (!cached) cached = LevelWriter(g, j.state, true).level(g.mesh, {}, {});
      shared = cached;
    }
    auto level = make_node("Separator");
    auto s = make_node("Scale");
    s->set("scaleFactor",
           scene::make_floats(FieldKind::kVec3f, false, {scale.x, scale.y, scale.z}));
    level->children = {s, shared};
    return level;
  }

  // Coarser tessellations than level 0's (j.segments: 24 without a
  // Complexity node), at 2/3, 1/3 and 1/6 of its segments (16, 8, 4 for 24),
  // each with fewer triangles than the level before by at least min_diff.
  void primitive_levels(Job& j, std::size_t simplified_max) {
    j.stats.method = "tessellation";
    std::size_t previous = j.stats.levels.front().triangles;
    std::vector<int> steps;
    for (int d : {2, 4, 8})
      steps.push_back(std::max(3, int(std::lround(double(j.segments) * 4 / (3 * d)))));
    for (int seg : steps) {
      if (seg >= j.segments) continue;
      if (simplified_max && j.level_nodes.size() - 1 >= simplified_max) break;
      TriangleMesh tess = scene::tessellate_primitive(*j.shape, {.segments = seg});
      if (double(tess.triangle_count()) > double(previous) * (1.0 - opt_.min_diff)) continue;
      const double error = kErrorMargin * tessellation_error(*j.shape, seg);
      if (error >= vanishing_error(j.radius)) break;
      j.level_nodes.push_back(primitive_level(j, seg));
      j.errors.push_back(error);
      j.stats.levels.push_back({tess.triangle_count(), tess.vertex_count(), error});
      previous = tess.triangle_count();
    }
  }

  // The subtree that replaces one occurrence.
  NodePtr subtree(Job& j, Occurrence& o) {
    if (j.remove) return make_node("Separator");
    // Each level carries its own property nodes (LevelWriter): what is
    // placed here is seen by every level, level 0 the input included.
    auto sep = make_node("Separator");
    if (opt_.export_flavour == ExportFlavour::kReducer && !is_set_shape(j.shape->type)) {
      // Primitives are centred at their origin already: nothing to move.
    } else if (opt_.export_flavour == ExportFlavour::kReducer) {
      auto tr = make_node("Translation");
      tr->set("translation",
              scene::make_floats(FieldKind::kVec3f, false, {j.center.x, j.center.y, j.center.z}));
      sep->children.push_back(tr);
    }
    if (opt_.extract) {
      std::size_t k = std::size_t(std::max(0, *opt_.extract));
      if (k < j.level_nodes.size()) sep->children.push_back(j.level_nodes[k]);
      return sep;
    }
    if (j.no_lod) {
      sep->children.push_back(j.level_nodes[0]);
      return sep;
    }
    auto lod = make_node("LOD");
    std::vector<double> errors(j.errors.begin() + 1, j.errors.end());
    errors.push_back(vanishing_error(j.radius));
    RangeOptions ro = opt_.range;
    ro.camera_angle = float(camera_angle_);
    std::vector<float> ranges = switching_ranges(errors, o.scale, j.radius * o.scale, ro);
    auto manual = opt_.manual.find(type_key(j.shape->type));
    if (manual != opt_.manual.end()) apply_given_ranges(ranges, manual->second.ranges);
    // A range is a VRML number: infinity (a shape too large for float
    // distances) cannot be written.
    for (float r : ranges)
      if (!std::isfinite(r))
        throw DataError(
            fmt::format("line {}: {}: a switching distance of its levels is {} (the "
                        "shape's bounding radius is {:g}); ranges must be finite",
                        j.shape->first_line, j.shape->type, r, j.radius * o.scale));
    lod->set("range", scene::make_floats(FieldKind::kFloat, true, ranges));
    if (opt_.export_flavour == ExportFlavour::kSpec) {
      lod->set("center",
               scene::make_floats(FieldKind::kVec3f, false, {j.center.x, j.center.y, j.center.z}));
    } else if (opt_.export_flavour == ExportFlavour::kPerformer) {
      Vec3 c = o.transform.transform_point(j.center);
      lod->set("center", scene::make_floats(FieldKind::kVec3f, false, {c.x, c.y, c.z}));
    }
    lod->children = j.level_nodes;
    lod->children.push_back(make_node("Separator"));  // the empty last level
    sep->children.push_back(lod);
    if (j.stats.ranges.empty()) j.stats.ranges = ranges;
    o.ranges = ranges;
    return sep;
  }

  void replace() {
    for (auto& o : occurrences_) {
      Job& j = jobs_[o.job];
      if (j.keep) continue;
      NodePtr s = subtree(j, o);
      if (!j.shape->name.empty()) s->name = j.shape->name;
      if (o.parent)
        o.parent->children[o.index] = s;
      else
        result_.scene.roots[o.index] = s;
    }
  }

  // Every instance a viewer draws (a shape in a group USEd n times is drawn n
  // times), each with the ranges of the LOD node it draws.
  void statistics() {
    std::vector<std::size_t> instance_count(jobs_.size(), 0);
    std::set<double> distances = {0.0};
    for (std::size_t oi : instances_) {
      ++instance_count[occurrences_[oi].job];
      for (float r : occurrences_[oi].ranges) distances.insert(r);
    }
    for (std::size_t i = 0; i < jobs_.size(); ++i) {
      jobs_[i].stats.occurrences = instance_count[i];
      jobs_[i].stats.radius = jobs_[i].radius;
      result_.shapes.push_back(jobs_[i].stats);
    }
    // Each instance draws the level whose range interval holds the distance
    // (--extract: its one level).
    for (double d : distances) {
      std::size_t total = 0;
      for (std::size_t oi : instances_) {
        const Occurrence& o = occurrences_[oi];
        const Job& j = jobs_[o.job];
        const ShapeStatistics& s = j.stats;
        if (s.levels.empty() || j.remove) continue;
        std::size_t level = 0;
        if (opt_.extract && !j.keep)
          level = std::size_t(std::max(0, *opt_.extract));
        else
          while (level < o.ranges.size() && d >= o.ranges[level]) ++level;
        if (level < s.levels.size()) total += s.levels[level].triangles;
      }
      result_.triangles_by_distance.emplace_back(d, total);
    }
  }

  const LodOptions& opt_;
  LodResult result_;
  std::vector<Job> jobs_;
  std::vector<Occurrence> occurrences_;
  std::vector<std::size_t> instances_;  // the occurrence of every shape visit
  std::vector<const Node*> empty_path_;
  double camera_angle_ = 0.785398;
  double largest_radius_ = 0;
  // Progress (start_progress): each job's weight and the part credited.
  std::vector<std::uint64_t> work_;
  std::vector<std::atomic<std::uint64_t>> credited_;
  std::uint64_t total_work_ = 0;
  std::atomic<std::uint64_t> done_work_{0};
  std::mutex cache_mutex_;
  std::map<std::string, double> tessellation_errors_;
  std::map<std::string, NodePtr> unit_levels_;  // primitive_level's shared tessellations
};

}  // namespace

int sized_quality(int quality, double radius, double scale, double largest) {
  if (quality < 2 || !(largest > 0) || !(radius > 0)) return quality;
  const double halvings = std::floor(std::log2(largest / (radius * scale)));
  return std::max(2, quality - int(std::max(0.0, halvings)));
}

LodResult generate_lod(const scene::Scene& scene, const LodOptions& options) {
  return Pipeline(scene, options).run();
}

LodResult generate_lod(scene::Scene&& scene, const LodOptions& options) {
  return Pipeline(std::move(scene), options).run();
}

}  // namespace lodforge
