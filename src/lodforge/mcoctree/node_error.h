#pragma once
/// How far the full-resolution surface inside each node of the marching-cube
/// octree lies from the node's own triangles (detail of the priority
/// numbering: McPriorityMetric::kDistance).
#include <vector>

#include "lodforge/mcoctree/mc_octree.h"

namespace lodforge::detail {

/// Per node of `tree`: the sum, over the full-resolution surface points under
/// it (the edge points of its leaves, each counted once), of the distance
/// from the point to the node's own triangulation (nothing split around it),
/// in model units; 0 for a leaf. A node with no triangles of its own hides
/// its surface entirely: each point counts the diagonal of the node's cell.
/// Preconditions: the nodes are stored level by level in Morton order
/// (children after their parent) and the leaves are the finest cells.
std::vector<double> node_distance_sums(const McOctree& tree);

}  // namespace lodforge::detail
