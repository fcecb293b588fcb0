#pragma once
/// A shape inside a group that is USEd under different property nodes (a
/// Coordinate3, Material, bindings, ... before each use) is drawn once per
/// context, but the LOD node that replaces it is placed once and its levels
/// carry one context's vertex data. This step gives each further context a
/// copy of the shared group, so every context gets LODs of its own.
#include <cstddef>
#include <functional>

#include "lodforge/scene/node.h"
#include "lodforge/scene/traverse.h"

namespace lodforge {

/// The property nodes a shape's geometry and its levels depend on.
struct PropertyContext {
  const scene::Node* coordinate3 = nullptr;
  const scene::Node* normal = nullptr;
  const scene::Node* texture_coordinate2 = nullptr;
  const scene::Node* material = nullptr;
  const scene::Node* material_binding = nullptr;
  const scene::Node* normal_binding = nullptr;
  const scene::Node* shape_hints = nullptr;
  const scene::Node* texture2 = nullptr;
  const scene::Node* complexity = nullptr;  ///< Inventor: primitives' tessellation

  static PropertyContext of(const scene::TraversalState& state);
  auto operator<=>(const PropertyContext&) const = default;
};

/// Copies shared groups until every shape for which `is_lod_shape` holds is
/// drawn in one property context per place (parent and child index): the
/// shallowest shared group on the path of a use in another context is
/// replaced there by a copy, one copy per (group, context), shared by every
/// use in that context. Returns the number of copies made; stops after
/// `max_passes` traversals (a pathological graph keeps its sharing).
std::size_t unshare_property_contexts(scene::Scene& scene,
                                      const std::function<bool(const scene::Node&)>& is_lod_shape,
                                      int max_passes = 16);

}  // namespace lodforge
