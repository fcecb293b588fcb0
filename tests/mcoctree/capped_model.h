#pragma once
// The run-time model of a mesh built with its holes capped, for tests that
// query or extract it.
#include "lodforge/mcoctree/build_mc_octree.h"
#include "lodforge/mcoctree/mc_lod_model.h"

namespace lodforge {

inline McLodModel model_of(const TriangleMesh& mesh, int resolution) {
  return compile_mc_lod(
      build_mc_octree(mesh, {.resolution = resolution, .holes = McHoles::kCapped}).tree);
}

}  // namespace lodforge
