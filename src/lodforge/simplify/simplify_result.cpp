#include "lodforge/simplify/simplify_result.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "lodforge/core/error.h"

namespace lodforge {

const char* to_string(StopReason reason) {
  switch (reason) {
    case StopReason::kTargetReached:
      return "target reached";
    case StopReason::kErrorBudgetReached:
      return "error budget reached";
    case StopReason::kCannotSimplify:
      return "cannot simplify further";
    case StopReason::kNoReduction:
      return "no reduction asked";
  }
  return "?";
}

std::size_t SimplifyTarget::triangle_target(std::size_t input_triangles) const {
  std::size_t t = input_triangles;
  if (triangles > 0) t = std::min(t, triangles);
  if (ratio > 0)
    t = std::min(t, static_cast<std::size_t>(std::floor(double(ratio) * double(input_triangles))));
  return t;
}

void check_simplify_input(const TriangleMesh& mesh, std::string_view who) {
  const std::size_t nv = mesh.positions.size();
  auto check = [&](std::uint32_t i, const char* what) {
    if (i >= nv)
      throw DataError(fmt::format("{}: {} index {} out of range ({} vertices)", who, what, i, nv));
    const Vec3& p = mesh.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw DataError(fmt::format("{}: vertex {} has a coordinate that is not finite", who, i));
  };
  for (const Triangle& t : mesh.triangles)
    for (std::uint32_t i : t) check(i, "triangle");
  for (const Segment& s : mesh.lines)
    for (std::uint32_t i : s) check(i, "line");
}

}  // namespace lodforge
