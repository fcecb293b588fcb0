#include "lodforge/mcoctree/mc_parts.h"

#include <algorithm>
#include <cmath>

#include "lodforge/mesh/adjacency.h"

namespace lodforge {
namespace {

std::vector<McPart> parts_of(const TriangleMesh& m) {
  const std::vector<std::uint32_t> label = triangle_parts(m);
  std::vector<McPart> parts;
  for (std::size_t f = 0; f < label.size(); ++f) {
    if (label[f] >= parts.size()) parts.resize(label[f] + 1);
    McPart& p = parts[label[f]];
    ++p.triangles;
    for (std::uint32_t v : m.triangles[f]) p.bounds.add(m.positions[v]);
  }
  return parts;
}

// Whether a and b, a grown by `near` on every side, overlap.
bool meet(const Box3& a, const Box3& b, float near) {
  for (int k = 0; k < 3; ++k)
    if (a.lo[k] - near > b.hi[k] || b.lo[k] > a.hi[k] + near) return false;
  return true;
}

}  // namespace

int resolution_to_keep(const McPart& part, const Box3& box) {
  const Vec3 size = part.bounds.size(), all = box.size();
  const float thinnest = std::min({size.x, size.y, size.z});
  const float longest = std::max({all.x, all.y, all.z});
  if (!(thinnest > 0)) return 1001;
  // Rounded up, past the float noise of the part's bounds.
  return static_cast<int>(std::min(1001.0, std::ceil(2.0 * longest / thinnest - 1e-3)));
}

McPartsCheck check_mc_parts(const TriangleMesh& input, const TriangleMesh& full, std::size_t most,
                            float near) {
  McPartsCheck out;
  const std::vector<McPart> in = parts_of(input);
  out.input_parts = in.size();
  std::vector<McPart> model = parts_of(full);
  out.model_parts = model.size();
  if (out.kept()) return out;
  for (const McPart& p : in) {
    if (!(near > 0) || out.vanished.size() >= most) break;
    if (std::none_of(model.begin(), model.end(),
                     [&](const McPart& m) { return meet(p.bounds, m.bounds, near); }))
      out.vanished.push_back(p);
  }
  std::stable_sort(model.begin(), model.end(),
                   [](const McPart& a, const McPart& b) { return a.triangles < b.triangles; });
  model.resize(std::min(model.size(), most));
  out.smallest = std::move(model);
  return out;
}

}  // namespace lodforge
