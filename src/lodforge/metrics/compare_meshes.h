#pragma once
/// Metro-style measurement of how far two surfaces are apart: the geometric
/// and normal deviation of the LODCreator thesis §5.2 (definitions 5.2.1-5.2.8).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "lodforge/core/memory_budget.h"
#include "lodforge/core/progress.h"
#include "lodforge/mesh/triangle_mesh.h"

namespace lodforge {

struct CompareOptions {
  /// Area samples per direction. 0 picks max(10 x the larger triangle count,
  /// 100 000), at most 4 000 000.
  std::size_t samples = 0;
  std::uint64_t seed = 1;        ///< A is sampled with `seed`, B with `seed + 1`
  int threads = 0;               ///< worker threads; 0 = all cores
  bool vertices = true;          ///< also sample every vertex (catches the extremes)
  std::size_t edge_samples = 0;  ///< samples along edges per direction (0: none)
  bool per_vertex = true;        ///< fill CompareResult::vertex_deviation
  /// Give a mesh without vertex normals the area-weighted average of its face
  /// normals at each vertex (the LODCreator thesis §5.2.2: "vertex normals are estimated
  /// averaging face normals in the vertex neighbourhood") instead of comparing
  /// face normals. Smooth normals measure the shape's orientation without the
  /// facet noise of scanned meshes.
  bool estimate_normals = false;
  /// Distances below the rounding noise of single-precision input
  /// (16 x FLT_EPSILON x the largest |coordinate| of A and B) count as 0, so
  /// that coincident surfaces measure exactly 0.
  bool snap_noise = true;
  std::string a_name = "A";  ///< names used in error messages (e.g. file paths)
  std::string b_name = "B";
  /// The samples of both directions may take at most this many bytes
  /// (estimated before sampling; DataError if more). 0: no limit.
  std::uint64_t max_memory = kDefaultMemoryBudget;
  /// Samples measured, stages "A to B", "B to A" and (per_vertex) "vertices",
  /// every 16 384 samples, from worker threads (core/progress.h). Empty: none.
  ProgressCallback progress;
};

/// Angles between the normal at a sample and at its closest point (radians).
/// Samples where either normal is undefined (degenerate triangle without
/// vertex normals) are left out.
struct NormalDeviation {
  std::size_t samples = 0;
  double mean = 0;  ///< definition 5.2.7
  double max = 0;
  double variance = 0;  ///< definition 5.2.8 (population variance)
};

/// Distance in RGB (each channel in [0,1], Euclidean, so at most sqrt 3)
/// between the colour at a sample and the colour interpolated at its closest
/// point. Measured only when both meshes have vertex colours.
struct ColorDeviation {
  std::size_t samples = 0;  ///< 0: a mesh has no colours
  double mean = 0;          ///< over the area samples, like Deviation::mean
  double max = 0;           ///< over every sample
  double rms = 0;
};

/// One-sided deviation E(S1, S2): samples on S1, distances to S2, in the
/// meshes' units; the *_pct fields are percent of A's bounding-box diagonal.
/// max and min run over every sample (vertices included); mean, rms and
/// variance over the area samples, which estimate the surface averages
/// without the bias of the vertex distribution (over all samples if the
/// surface has no area).
struct Deviation {
  std::size_t samples = 0;  ///< vertex + edge + area samples on S1
  double min = 0;
  double max = 0;   ///< definition 5.2.2
  double mean = 0;  ///< definition 5.2.4
  double rms = 0;
  double variance = 0;  ///< definition 5.2.5 (population variance)
  double max_pct = 0;
  double mean_pct = 0;
  double rms_pct = 0;
  NormalDeviation normal;  ///< definition 5.2.6, samples on S1 against S2
  ColorDeviation color;    ///< samples on S1 against S2, when both have colours
};

struct CompareResult {
  Deviation a_to_b;                     ///< samples on A, closest points on B
  Deviation b_to_a;                     ///< samples on B, closest points on A
  double hausdorff = 0;                 ///< max(a_to_b.max, b_to_a.max), definition 5.2.3
  double hausdorff_pct = 0;             ///< percent of A's bounding-box diagonal
  double diagonal = 0;                  ///< A's bounding-box diagonal
  std::size_t samples = 0;              ///< area samples requested per direction
  bool vertex_normals = false;          ///< normals interpolated from vertex normals (else faces)
  std::vector<float> vertex_deviation;  ///< #V of A: distance of each vertex to B (per_vertex)
};

/// Compares surface A (the reference, e.g. the original) with B (e.g. its
/// simplification): samples both, finds each sample's exact closest point on
/// the other surface, and reports the deviations both ways. Vertex normals are
/// used only when both meshes have them: mixing smooth and faceted normals
/// would measure shading, not shape. Degenerate triangles, duplicate vertices,
/// open borders and several components need no special care.
///
/// Deterministic for given meshes and options, whatever the thread count.
/// Throws DataError (naming options.a_name / b_name) when a mesh has no
/// triangles, a triangle index is out of range or a used coordinate is not
/// finite.
CompareResult compare_meshes(const TriangleMesh& a, const TriangleMesh& b,
                             const CompareOptions& options = {});

}  // namespace lodforge
