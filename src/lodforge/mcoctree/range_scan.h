#pragma once
/// Range scans: the lattices of points a range scanner measures, in the
/// layout of the Stanford 3D scanning repository, and their alignment.
///
/// A scan is a PLY file with `obj_info num_cols N`, `obj_info num_rows M`, a
/// `vertex` element (x y z, optionally confidence, intensity, red green
/// blue) and a `range_grid` element of M x N lists (row by row, column
/// fastest) holding zero or one vertex index: the point the scanner measured
/// at that grid position, if any. The scanner looks down the scan frame's -z
/// axis (its sensor is on the +z side), as the Cyberware scans of the Stanford
/// repository do.
///
/// A `.conf` file aligns several scans: `camera ...` lines (ignored) and
/// `bmesh NAME tx ty tz qx qy qz qw` per scan, NAME relative to the .conf's
/// directory; a point p of the scan maps to R p + t (the quaternion rotates
/// the scan, then the translation moves it), where R is the matrix of q in
/// Stanford's row-vector convention (p R), i.e. the rotation by q's conjugate.
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "lodforge/core/math.h"
#include "lodforge/mcoctree/mc_octree.h"

namespace lodforge {

struct RangeScan {
  std::string name;  ///< file name (as in the .conf)
  int cols = 0, rows = 0;
  /// rows x cols, row-major: index into points, or -1 where nothing was measured.
  std::vector<std::int32_t> grid;
  std::vector<Vec3> points;  ///< in the scan frame
  std::vector<Rgb8> colors;  ///< empty or #points
  /// Empty or #points: the scanner's confidence in each point (the PLY's
  /// `confidence` property, >= 0), as Stanford's scans of other objects
  /// and VRIP's inputs carry it.
  std::vector<float> confidence;
  Vec3 translation;                           ///< scan frame -> world: R(rotation) p + translation
  std::array<float, 4> rotation{0, 0, 0, 1};  ///< unit quaternion qx qy qz qw, as in a .conf

  /// The point in world coordinates.
  Vec3 to_world(const Vec3& p) const;
  /// A world point in the scan frame (the inverse of to_world).
  Vec3 to_scan(const Vec3& p) const;
  /// Median distance between neighbours along a row (0 if none).
  float spacing() const;
  /// A direction (normal) in world coordinates.
  Vec3 rotate(const Vec3& v) const;
  /// Normals of the points in the scan frame (Kim, sec. 4.2, Fig. 4.2): the
  /// average of the unit normals of the triangles a point makes with its 4
  /// lattice neighbours (right/up, up/left, left/down, down/right), oriented
  /// towards the sensor (+z); edges longer than 4 x spacing() (depth jumps)
  /// make no triangle. A point without such a triangle gets +z. #points.
  std::vector<Vec3> normals() const;
  /// How far each point is to be trusted, in (0, 1] (Curless & Levoy 1996,
  /// "A volumetric method for building complex models from range images"):
  /// the cosine between its normal and the line of sight (grazing samples
  /// are noisy), times the fraction of its 4 lattice triangles that exist
  /// (the rim of the data, mixed pixels at depth jumps; a stray point has
  /// none), times its confidence over the scan's largest when the scan has
  /// confidences; at least kMinWeight.
  /// `normals` is normals()'s result. #points.
  std::vector<float> weights(const std::vector<Vec3>& normals) const;
  static constexpr float kMinWeight = 0.01f;
};

/// Reads one range-grid PLY (ASCII or binary, either byte order). `name` is
/// used in messages. Throws DataError ("name: ...") for a missing
/// num_cols/num_rows, a missing range_grid or vertex element, an index out
/// of range, a non-finite coordinate, a negative or non-finite confidence or
/// truncated data.
RangeScan read_range_grid_data(std::string_view data, const std::string& name);

/// Reads scans: a `.conf` file (the scans it lists, aligned), a directory
/// (its single `.conf` if it has one, else every `.ply` with identity
/// alignment) or a single range-grid `.ply`. Throws DataError.
std::vector<RangeScan> read_range_scans(const std::string& path);

/// The bytes of a binary little-endian range-grid PLY of `scan` (colours as
/// red green blue uchar, confidence as a float, when present).
std::string write_range_grid_data(const RangeScan& scan);

/// Writes every scan as DIR/<name> and DIR/<conf_name> listing them (a
/// `camera` line, then `bmesh` lines). Creates DIR. Throws DataError.
void write_range_scans(const std::vector<RangeScan>& scans, const std::string& dir,
                       const std::string& conf_name = "scans.conf");

}  // namespace lodforge
