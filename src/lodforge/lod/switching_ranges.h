#pragma once
/// Switching distances of LOD levels from their geometric error (SPEC §2):
/// level l may be shown beyond the distance at which its error, seen by the
/// camera, covers at most a fraction p of the screen height:
///
///     d_l = k * eps_l / (2 * tan(alpha / 2) * p) + r
///
/// eps_l: geometric error of level l in object units (its measured deviation
/// from level 0); k: scale of the current transform; alpha: the camera's
/// height angle; p: the error range (fraction of the screen height); r: the
/// radius of the shape's bounding sphere (distances are measured from the
/// centre, the surface can be r closer).
#include <span>
#include <vector>

namespace lodforge {

struct RangeOptions {
  float error_range = 0.02f;       ///< p, fraction of the screen height (2 %)
  float camera_angle = 0.785398f;  ///< alpha, radians (pi/4, VRML's default)
};

/// d for one error. Preconditions: error >= 0, scale > 0, radius >= 0,
/// 0 < camera_angle < pi, error_range > 0 (asserted).
double switch_distance(double error, double scale, double radius, const RangeOptions& options);

/// The error at which a whole object of bounding radius r disappears from view
/// at the error range: its diameter. An empty last level takes this error.
inline double vanishing_error(double radius) {
  return 2 * radius;
}

/// LOD.range for levels 1..n given their errors eps_1..eps_n (level 0, the
/// original, has no range). Errors are made non-decreasing (a coarser level is
/// never shown nearer than a finer one) and the ranges strictly increasing
/// (VRML requires it: equal neighbours are nudged up by one float step).
std::vector<float> switching_ranges(std::span<const double> level_errors, double scale,
                                    double radius, const RangeOptions& options);

}  // namespace lodforge
