#pragma once
/// Simplification whose error is measured, not estimated: one of the three
/// simplifiers, then the one-sided Hausdorff distance from its result to its
/// input, sampled and refined (DeviationMeter) and enlarged by kErrorMargin.
/// That figure is meant to stay above what a denser measurement finds (a
/// sampled measurement with a margin, not a proof; the error checks in bench/
/// compare it with 10^6-sample measurements) and at most kErrorMargin x the
/// distance it found, whatever the method; the
/// simplifiers' own figures are not (quadric error and Schroeder's
/// accumulated distance overstate or understate it many times, a vertex
/// displacement is no surface bound at all).
///
/// An error budget is met against the measured bound: the result is the
/// smallest one found whose bound is within it, by measuring every level of
/// the method's chain (halving steps; clustering's octree levels) and then,
/// for quadric collapse and decimation, counts below the smallest result
/// within the budget in steps of 2^(1/8), until one at most half its size
/// measures twice the budget (the measured error does not fall strictly with
/// the count: a thin part can vanish at one count and not at a smaller one,
/// so no bisection).
#include <cstddef>
#include <limits>

#include "lodforge/core/progress.h"
#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/simplify/level_chain.h"
#include "lodforge/simplify/simplify_result.h"

namespace lodforge {

struct MeasuredSimplifyOptions {
  SimplifyMethod method = SimplifyMethod::kQem;
  /// A triangle count or ratio and/or max_error (model units, compared with
  /// the measured bound); both given: the first limit met ends it. `{}`
  /// keeps the mesh as it is.
  SimplifyTarget target;
  /// Area samples of each measurement (0: measure_samples_for the input and
  /// the method, at most 100 000, four times that for decimation).
  std::size_t samples = 0;
  /// Stages as the search runs (core/progress.h): a count target "simplify"
  /// (the run, then its measurement); an error budget "chain" (its levels
  /// made), "measure" (each level measured), "scan" (counts tried below the
  /// best, out of the most it could try). Empty: none.
  ProgressCallback progress;
};

struct MeasuredSimplifyResult {
  /// The simplified mesh; result.error is the simplifier's own figure (see
  /// its header), result.stop_reason says which limit ended the search.
  SimplifyResult result;
  /// kErrorMargin x the measured largest distance from the result to the
  /// input (model units): an upper bound on the one-sided Hausdorff distance.
  double error = 0;
  std::size_t simplifier_runs = 0;  ///< simplifications the search made
  std::size_t measurements = 0;     ///< one-sided measurements it made
};

/// Simplifies `mesh` (which has triangles) to `options.target` with the
/// method and measures the result. For a count target alone, one run of the
/// method: quadric collapse and decimation land at or just below the count;
/// clustering takes the first of its levels at or below it (its levels fall
/// at octree depths), and stop_detail says how far that is from the count. Throws
/// DataError for an index out of range or a used coordinate that is not
/// finite.
MeasuredSimplifyResult simplify_measured(const TriangleMesh& mesh,
                                         const MeasuredSimplifyOptions& options);

}  // namespace lodforge
