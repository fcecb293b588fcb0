#pragma once
/// Keeping a closed mesh's connected parts whole in the sign lattice (detail
/// of build_mc_octree): a part thinner than a cell leaves lattice points
/// inside it on each side of its thinnest place but none in between, and the
/// marching cubes surface comes apart there; a bridge of lattice points along
/// the thin place, made inside, keeps it in one piece.
#include <cstddef>

#include "lodforge/mcoctree/mesh_signs.h"
#include "lodforge/mcoctree/sign_lattice.h"

namespace lodforge::detail {

struct PartBridges {
  std::size_t regions = 0;  ///< 6-connected inside regions before bridging
  std::size_t bridges = 0;  ///< bridges made (each joins two regions of one part)
  std::size_t points = 0;   ///< outside points made inside by them
};

/// Joins the inside regions of `lat` (6-connected inside points) that belong
/// to one connected part of sd's mesh (triangle_parts; a region belongs to
/// the parts of the triangles nearest its exact points). Each bridge is a
/// path through exact points between two regions of a part whose largest
/// distance to the surface is least (one search from all regions at once, in
/// order of that distance): the thin place's core, within a cell of its
/// surface. Its outside points are made inside and their distances negated,
/// so that the surface runs around them at the distance they had from the
/// input. Meant for closed meshes (an open one's regions follow its holes).
/// Time O(L + B log B) for L lattice points and B exact ones, whatever the
/// number of bridges; memory about 17 bytes per exact point and a queue.
/// Precondition: lat.distance sorted by index, one entry per point with
/// kExact.
PartBridges bridge_mesh_parts(Lattice& lat, const SignedDistance& sd);

}  // namespace lodforge::detail
