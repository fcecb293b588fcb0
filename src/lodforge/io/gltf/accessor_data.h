#pragma once
/// The values of a glTF accessor, decoded: what the glTF 2.0 specification
/// ("Accessors") says a reader sees, whatever the component type, stride or
/// sparse substitution.
#include <cstddef>
#include <vector>

#include <tiny_gltf.h>

namespace lodforge::gltf {

struct AccessorValues {
  std::size_t count = 0;       ///< elements
  int components = 0;          ///< per element (3 for VEC3, 16 for MAT4)
  std::vector<double> values;  ///< count x components, element by element
};

/// Element i, component c of accessor `index` at values[i * components + c]:
/// floats as they are; normalized integers mapped to [0, 1] (unsigned) or
/// [-1, 1] (signed) as the specification states; other integers as their
/// value (indices). An accessor without a buffer view is zeros; sparse
/// values replace the elements they name. Preconditions: the model passed
/// read_gltf's checks (indices and byte ranges valid). Throws DataError for
/// a sparse index past the accessor's count.
AccessorValues read_accessor(const tinygltf::Model& model, int index);

}  // namespace lodforge::gltf
