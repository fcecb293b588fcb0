#include "lodforge/simplify/simplify_result.h"

#include <algorithm>
#include <cmath>

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

}  // namespace lodforge
