#pragma once
/// The scene LOD pipeline (the original LODCreator): every
/// IndexedFaceSet, IndexedLineSet, Cone, Cylinder, Sphere and Cube of a VRML
/// 1.0 scene (and of an Open Inventor scene, with its FaceSets, strip sets,
/// QuadMeshes and LineSets, output with an `#Inventor V2.1 ascii` header)
/// becomes
///
///     Separator { [Material] [MaterialBinding] [NormalBinding] [ShapeHints]
///                 LOD { range [...] center ... level0 level1 ... empty } }
///
/// with levels made by the chosen simplifier and switching ranges from the
/// screen-space error of each level's measured deviation. The rest of the
/// scene (hierarchy, DEF/USE, cameras, lights, anchors, inlines, unknown
/// nodes) is kept. A shape met several times under the same properties is
/// simplified once; its levels are shared (DEF/USE) by its LOD nodes.
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "lodforge/core/log.h"
#include "lodforge/core/progress.h"
#include "lodforge/lod/simplify_levels.h"
#include "lodforge/lod/switching_ranges.h"
#include "lodforge/mesh/triangulate_polygon.h"
#include "lodforge/scene/node.h"

namespace lodforge {

/// Where the LOD centre goes (the original's §4.4 "center problem").
enum class ExportFlavour {
  kSpec,       ///< `center` in the shape's local coordinates (VRML 1.0 spec)
  kPerformer,  ///< `center` at the exact global position (OpenGL Performer)
  kReducer,    ///< no center: coordinates moved to the origin, a Translation before the LOD
};

/// Manual settings of one shape type (the original's per-type tabs).
struct ShapeTypeSettings {
  /// Levels for this type: 0 = replace the shape by an empty node, 1 = no
  /// LOD, N >= 2 = N levels (original, N-2 simplified, empty). -1: automatic.
  int quality = -1;
  /// Explicit LOD ranges for this type (used in order; missing ones computed).
  std::vector<float> ranges;
};

struct LodOptions {
  SimplifyMethod method = SimplifyMethod::kQem;
  RangeOptions range;               ///< error range p and camera height angle
  bool camera_angle_given = false;  ///< else: the first PerspectiveCamera's, else range's
  /// Candidate levels: each <= (1 - min_diff) of the previous candidate.
  float min_diff = 0.2f;
  /// Automatic mode: of the candidates, a level is kept only where it is shown
  /// over a distance interval of at least this factor (space_levels in
  /// switching_ranges.h); <= 1 keeps every candidate with a larger distance.
  double level_spacing = kDefaultLevelSpacing;
  /// Automatic mode: a kept level has at most this fraction of the triangles
  /// of the level before it (>= 1: no size rule).
  double level_ratio = kDefaultLevelRatio;
  std::size_t max_levels = 0;  ///< at most this many levels, original and empty included
  /// Per shape type: "polygon" (IndexedFaceSet), "line" (IndexedLineSet),
  /// "sphere", "cone", "cylinder", "cube".
  std::map<std::string, ShapeTypeSettings> manual;
  /// Manual mode: each halving of a shape's size below the largest shape's
  /// removes one level (at least 2 remain).
  bool differentiate_by_size = false;
  bool no_lines = false;  ///< drop faces that collapse to lines
  /// Join runs of small IndexedFaceSets first (join_nodes.h), so a model
  /// broken into many parts is simplified as one.
  bool join = false;
  std::size_t join_max_faces = 1000;
  TriangulateOptions triangulation;  ///< quad split angle, keep_quads (--no-quads)
  ExportFlavour export_flavour = ExportFlavour::kSpec;
  /// Write only level K of every shape (0 = original); -1 = only clean and
  /// reformat (every shape as its cleaned level 0, no LOD nodes).
  std::optional<int> extract;
  std::size_t measure_samples = 0;  ///< compare_meshes samples per level (0: its default)
  int threads = 0;                  ///< 0: all cores; 1: single-threaded
  /// Progress of the shapes (stage "shapes"), in units of work: each
  /// distinct shape weighs about its input's face indices, a fifth of it
  /// credited when its chain is simplified, the rest as its levels are
  /// measured. Called from worker threads (core/progress.h); empty: none.
  ProgressCallback progress;
};

/// Manual mode's level count for a shape of bounding radius `radius` x
/// `scale` with --differentiate-by-size: one level fewer per halving of size
/// below the scene's largest shape (`largest`, radius x scale), never below
/// 2; `quality` itself otherwise (or when below 2 or a size is unknown).
int sized_quality(int quality, double radius, double scale, double largest);

struct LevelStatistics {
  std::size_t triangles = 0;
  std::size_t vertices = 0;
  double error = 0;  ///< measured deviation from level 0 (model units)
};

struct ShapeStatistics {
  std::string type;  ///< node type
  std::string name;  ///< DEF name, if any
  int line = 0;      ///< where the shape was read
  /// Instances a viewer draws: every DEF/USE of the shape and of the groups
  /// holding it, each under its own transform.
  std::size_t occurrences = 1;
  double radius = 0;                    ///< bounding sphere, local units
  double scale = 0;                     ///< largest transform scale among its occurrences
  std::vector<LevelStatistics> levels;  ///< level 0 .. empty level
  std::vector<float> ranges;            ///< LOD.range (levels.size() - 1 values)
  std::string method;                   ///< simplifier, or "tessellation" / "none"
  /// Why the chain ended: the vanishing error, the level limit, or the
  /// simplifier's own reason (nothing more could be removed, or its smallest
  /// target of a few triangles was reached).
  std::string stop_reason;
};

struct LodResult {
  scene::Scene scene;
  std::vector<ShapeStatistics> shapes;  ///< one entry per distinct shape (job)
  /// Triangles drawn when every shape is seen from `distance` (each occurrence
  /// counted): the original's Statistic dialog.
  std::vector<std::pair<double, std::size_t>> triangles_by_distance;
  double camera_angle = 0;  ///< the height angle used
  std::size_t joined = 0;   ///< IndexedFaceSets merged away by join
  Log log;
};

/// Runs the pipeline. The input scene is not modified. Throws DataError for a
/// shape that cannot be read (index out of range, NaN coordinates: "line N: ...").
LodResult generate_lod(const scene::Scene& scene, const LodOptions& options = {});
/// The same, taking the scene over instead of copying it: for a caller that
/// has no use for it afterwards (a big scene is then never in memory twice).
LodResult generate_lod(scene::Scene&& scene, const LodOptions& options = {});

}  // namespace lodforge
