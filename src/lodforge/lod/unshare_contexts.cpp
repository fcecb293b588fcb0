#include "lodforge/lod/unshare_contexts.h"

#include <map>
#include <unordered_map>
#include <unordered_set>
#include <utility>

namespace lodforge {
namespace {

using scene::Node;
using scene::NodePtr;

// How many child slots (and roots) hold each node.
std::unordered_map<const Node*, std::size_t> reference_counts(const scene::Scene& scene) {
  std::unordered_map<const Node*, std::size_t> refs;
  std::unordered_set<const Node*> expanded;
  std::vector<const Node*> stack;
  for (const auto& r : scene.roots) {
    ++refs[r.get()];
    stack.push_back(r.get());
  }
  while (!stack.empty()) {
    const Node* n = stack.back();
    stack.pop_back();
    if (!expanded.insert(n).second) continue;
    for (const auto& c : n->children) {
      ++refs[c.get()];
      stack.push_back(c.get());
    }
  }
  return refs;
}

// A slot to re-point: child `index` of `holder` (nullptr: Scene::roots).
struct Slot {
  Node* holder;
  std::size_t index;
  auto operator<=>(const Slot&) const = default;
};

struct Copy {
  const Node* shared;
  PropertyContext context;
};

}  // namespace

PropertyContext PropertyContext::of(const scene::TraversalState& s) {
  return {s.coordinate3, s.normal,           s.texture_coordinate2,
          s.material,    s.material_binding, s.normal_binding,
          s.shape_hints, s.texture2,         s.complexity};
}

std::size_t unshare_property_contexts(scene::Scene& scene,
                                      const std::function<bool(const Node&)>& is_lod_shape,
                                      int max_passes) {
  std::map<std::pair<const Node*, PropertyContext>, NodePtr> copies;
  std::size_t made = 0;
  for (int pass = 0; pass < max_passes; ++pass) {
    const auto refs = reference_counts(scene);
    std::map<std::pair<const Node*, std::size_t>, PropertyContext> first_context;
    std::map<Slot, Copy> to_copy;
    scene::traverse(scene, [&](const scene::ShapeVisit& v) {
      if (!is_lod_shape(v.shape)) return;
      const Node* parent = v.path.empty() ? nullptr : v.path.back();
      const PropertyContext context = PropertyContext::of(v.state);
      auto [it, fresh] = first_context.try_emplace({parent, v.child_index}, context);
      if (fresh || it->second == context) return;
      // The same place in another context: some group on the path is
      // shared. Its shallowest one is held by a slot of its own (nothing
      // above it is shared), so re-pointing that slot affects this use only.
      for (std::size_t k = 0; k < v.path.size() && k < v.path_index.size(); ++k) {
        auto r = refs.find(v.path[k]);
        if (r == refs.end() || r->second < 2) continue;
        Node* holder = k ? const_cast<Node*>(v.path[k - 1]) : nullptr;
        to_copy.try_emplace(Slot{holder, v.path_index[k]}, Copy{v.path[k], context});
        return;
      }
    });
    if (to_copy.empty()) break;
    for (const auto& [slot, c] : to_copy) {
      auto& children = slot.holder ? slot.holder->children : scene.roots;
      NodePtr& copy = copies[{c.shared, c.context}];
      if (!copy) {
        std::unordered_map<const Node*, NodePtr> done;
        copy = scene::copy_subtree(children[slot.index], done);
        ++made;
      }
      children[slot.index] = copy;
    }
  }
  return made;
}

}  // namespace lodforge
