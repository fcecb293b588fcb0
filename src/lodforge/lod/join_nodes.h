#pragma once
/// Joining VRML nodes (the original thesis §4.1.5): a model broken into many
/// small IndexedFaceSets, each in its own Separator with its own Coordinate3
/// (and Material, Normal, TextureCoordinate2), is simplified piece by piece
/// and torn apart. Joining merges runs of such sibling Separators into one
/// IndexedFaceSet, with complete Material lists and a PER_FACE_INDEXED
/// binding, after removing unnecessary Separators (a Separator whose only
/// child is another Separator).
#include <cstddef>

#include "lodforge/core/log.h"
#include "lodforge/scene/node.h"

namespace lodforge {

struct JoinOptions {
  /// Only IndexedFaceSets with at most this many faces are joined ("small").
  std::size_t max_faces = 1000;
};

struct JoinStatistics {
  std::size_t runs = 0;    ///< groups of Separators joined into one
  std::size_t joined = 0;  ///< IndexedFaceSets merged away
  std::size_t separators_removed = 0;
};

/// Joins in place. Only nodes that nothing else refers to are touched: no
/// DEF name and no second parent inside a joined piece. Reports each join to
/// `log` (category join).
JoinStatistics join_nodes(scene::Scene& scene, const JoinOptions& options, Log& log);

}  // namespace lodforge
