#include "lodforge/mcoctree/mc_parts.h"

#include <algorithm>

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

}  // namespace

McPartsCheck check_mc_parts(const TriangleMesh& input, const TriangleMesh& full, std::size_t most) {
  McPartsCheck out;
  out.input_parts = parts_of(input).size();
  std::vector<McPart> model = parts_of(full);
  out.model_parts = model.size();
  if (out.kept()) return out;
  std::stable_sort(model.begin(), model.end(),
                   [](const McPart& a, const McPart& b) { return a.triangles < b.triangles; });
  model.resize(std::min(model.size(), most));
  out.smallest = std::move(model);
  return out;
}

}  // namespace lodforge
