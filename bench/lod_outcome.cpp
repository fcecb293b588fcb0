// What `lodforge lod` buys a viewer (issue 16, "a benchmark of the outcome"):
// the triangles its output draws at 40 log-spaced distances from each shape's
// bounding radius to 200x it, summed, beside a peer chain built the way
// engines build one: meshopt_simplify to 1/2, 1/4, ... of the triangles, each
// level switched at the distance where its *measured* Hausdorff deviation
// (the same DeviationMeter, without lodforge's 10 % margin) covers the same
// error range of the same camera, and gone at the same vanishing distance.
// Both sides use each shape's bounding sphere, largest instance scale and
// instance count from lodforge's statistics. Also the output file's size
// against the input's, and a bound: the same peer with levels every 10 % of
// the triangles instead of every 50 %, each shown from its own distance
// with no spacing rule and no margin, which is about the least any chain of
// meshopt_simplify's quality can draw.
//
//   lod_outcome [--curve] FILE...  (VRML 1.0 scenes; a mesh file (PLY, OBJ,
//                                   ...) is made a scene of one IndexedFaceSet
//                                   first)
//
// --curve also prints, per shape, both chains (triangles, switching distance
// in radii) and the triangles each side draws at every sampled distance.
//
// Prints a Markdown table on stdout; ratio = lodforge / peer (target <= 0.7),
// bound = the fine chain / peer.
#include <fmt/core.h>
#include <meshoptimizer.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "lodforge/io/vrml1/read_vrml1.h"
#include "lodforge/io/vrml1/write_vrml1.h"
#include "lodforge/lod/generate_lod.h"
#include "lodforge/lod/measure_deviation.h"
#include "lodforge/lod/switching_ranges.h"
#include "lodforge/mesh/mesh_io.h"
#include "lodforge/scene/shape_mesh.h"
#include "lodforge/scene/traverse.h"

namespace {

using namespace lodforge;

constexpr int kDistances = 40;
constexpr double kFarthest = 200;  // x the radius

std::string scene_text_of(const TriangleMesh& mesh) {
  std::string s = "#VRML V1.0 ascii\nSeparator {\nCoordinate3 { point [\n";
  for (const auto& p : mesh.positions) s += fmt::format("{} {} {},\n", p.x, p.y, p.z);
  s += "] }\nIndexedFaceSet { coordIndex [\n";
  for (const auto& t : mesh.triangles) s += fmt::format("{}, {}, {}, -1,\n", t[0], t[1], t[2]);
  return s + "] }\n}\n";
}

// The peer's chain of one mesh: triangle counts and switching distances at
// scale 1 (level 0 first, distance 0).
struct PeerChain {
  std::vector<std::size_t> triangles;
  std::vector<double> distance;
};

// `step`: each level's target is this fraction of the one before.
PeerChain peer_chain(const TriangleMesh& mesh, double radius, const RangeOptions& range,
                     double step) {
  PeerChain c{{mesh.triangle_count()}, {0.0}};
  std::vector<unsigned> indices;
  for (const auto& t : mesh.triangles) indices.insert(indices.end(), {t[0], t[1], t[2]});
  std::vector<float> xyz;
  for (const auto& p : mesh.positions) xyz.insert(xyz.end(), {p.x, p.y, p.z});
  DeviationMeter meter(
      mesh, {.samples = std::clamp<std::size_t>(20 * mesh.triangle_count(), 20000, 200000)});
  double worst = 0;
  for (auto target = std::size_t(step * double(indices.size())); target >= 3;
       target = std::size_t(step * double(target))) {
    std::vector<unsigned> out(indices.size());
    out.resize(meshopt_simplify(out.data(), indices.data(), indices.size(), xyz.data(),
                                mesh.positions.size(), 3 * sizeof(float), target / 3 * 3,
                                std::numeric_limits<float>::max(), 0, nullptr));
    if (out.empty()) break;
    if (out.size() / 3 >= c.triangles.back()) continue;
    TriangleMesh level;
    level.positions = mesh.positions;
    for (std::size_t i = 0; i < out.size(); i += 3)
      level.triangles.push_back({out[i], out[i + 1], out[i + 2]});
    worst = std::max(worst, meter.hausdorff(level));
    const double d = switch_distance(worst, 1, radius, range);
    if (d >= switch_distance(vanishing_error(radius), 1, radius, range)) break;
    c.triangles.push_back(level.triangle_count());
    c.distance.push_back(d);
  }
  return c;
}

// The triangles a chain draws at distance d (scale k, nothing past `vanish`).
std::size_t drawn(const PeerChain& c, double k, double d, double vanish) {
  if (d >= vanish) return 0;
  std::size_t p = 0;
  while (p + 1 < c.distance.size() && k * c.distance[p + 1] <= d) ++p;
  return c.triangles[p];
}

struct Outcome {
  double lodforge = 0, peer = 0, fine = 0;
  std::size_t input_bytes = 0, output_bytes = 0;
  std::size_t shapes = 0;
};

Outcome measure(const std::string& path, bool curve) {
  namespace fs = std::filesystem;
  const std::string ext = fs::path(path).extension().string();
  scene::Scene in;
  Outcome o;
  if (ext == ".wrl" || ext == ".iv") {
    in = vrml1::read_vrml1_file(path).scene;
    o.input_bytes = fs::file_size(path);
  } else {
    const std::string text = scene_text_of(read_mesh(path));
    in = vrml1::read_vrml1(text).scene;
    o.input_bytes = text.size();
  }
  const LodResult r = generate_lod(in, {});
  o.output_bytes = vrml1::write_vrml1(r.scene).size();
  RangeOptions range;
  range.camera_angle = float(r.camera_angle);
  // The input mesh of each IndexedFaceSet, by line (lodforge's statistics name it so).
  std::map<int, TriangleMesh> meshes;
  scene::traverse(in, [&](const scene::ShapeVisit& v) {
    if (v.shape.type == "IndexedFaceSet" && !meshes.count(v.shape.first_line))
      meshes[v.shape.first_line] = scene::shape_mesh(v, {.world_space = false});
  });
  for (const ShapeStatistics& s : r.shapes) {
    if (s.type != "IndexedFaceSet" || s.levels.empty() || s.radius <= 0) continue;
    auto m = meshes.find(s.line);
    if (m == meshes.end() || m->second.triangles.empty()) continue;
    ++o.shapes;
    const PeerChain peer = peer_chain(m->second, s.radius, range, 0.5);
    const PeerChain fine = peer_chain(m->second, s.radius, range, 0.9);
    const double k = s.scale > 0 ? s.scale : 1.0;
    const double vanish = k * switch_distance(vanishing_error(s.radius), 1, s.radius, range);
    if (curve) {
      fmt::print(stderr, "{} line {}: radius {:.4g}, vanishing at {:.1f} r\n  lodforge:", path,
                 s.line, s.radius, vanish / (k * s.radius));
      for (std::size_t l = 0; l < s.levels.size(); ++l)
        fmt::print(stderr, " {}@{:.2f}", s.levels[l].triangles,
                   l == 0 ? 0.0 : s.ranges[l - 1] / (k * s.radius));
      fmt::print(stderr, "\n  peer:    ");
      for (std::size_t l = 0; l < peer.triangles.size(); ++l)
        fmt::print(stderr, " {}@{:.2f}", peer.triangles[l], peer.distance[l] / s.radius);
      fmt::print(stderr, "\n  d/r lodforge peer bound\n");
    }
    for (int i = 0; i < kDistances; ++i) {
      const double d = k * s.radius * std::pow(kFarthest, double(i) / (kDistances - 1));
      // lodforge: the level whose range interval holds d (past the last: empty).
      std::size_t level = 0;
      while (level < s.ranges.size() && d >= s.ranges[level]) ++level;
      const std::size_t ours = level < s.levels.size() ? s.levels[level].triangles : 0;
      o.lodforge += double(s.occurrences * ours);
      // The peer: its coarsest level allowed at d, nothing past vanishing.
      const std::size_t theirs = drawn(peer, k, d, vanish);
      const std::size_t bound = drawn(fine, k, d, vanish);
      o.peer += double(s.occurrences * theirs);
      o.fine += double(s.occurrences * bound);
      if (curve) fmt::print(stderr, "  {:.2f} {} {} {}\n", d / (k * s.radius), ours, theirs, bound);
    }
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const bool curve = argc > 1 && std::string(argv[1]) == "--curve";
  if (argc < 2 + int(curve)) {
    fmt::print(stderr, "usage: lod_outcome [--curve] FILE...\n");
    return 2;
  }
  fmt::print(
      "| file | shapes | triangles drawn, lodforge | peer | ratio | bound | output / input size "
      "|\n");
  fmt::print("|---|---|---|---|---|---|---|\n");
  Outcome all;
  for (int a = 1 + int(curve); a < argc; ++a) {
    Outcome o;
    try {
      o = measure(argv[a], curve);
    } catch (const std::exception& e) {
      fmt::print(stderr, "{}: {}\n", argv[a], e.what());
      continue;
    }
    if (o.shapes == 0) continue;
    all.lodforge += o.lodforge;
    all.peer += o.peer;
    all.fine += o.fine;
    all.input_bytes += o.input_bytes;
    all.output_bytes += o.output_bytes;
    all.shapes += o.shapes;
    fmt::print("| {} | {} | {:.0f} | {:.0f} | {:.2f} | {:.2f} | {:.2f} |\n",
               std::filesystem::path(argv[a]).filename().string(), o.shapes, o.lodforge, o.peer,
               o.lodforge / o.peer, o.fine / o.peer,
               double(o.output_bytes) / double(o.input_bytes));
  }
  if (all.peer > 0)
    fmt::print("| all | {} | {:.0f} | {:.0f} | {:.2f} | {:.2f} | {:.2f} |\n", all.shapes,
               all.lodforge, all.peer, all.lodforge / all.peer, all.fine / all.peer,
               double(all.output_bytes) / double(all.input_bytes));
  return 0;
}
